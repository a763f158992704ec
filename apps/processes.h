// The processes a `tripath` command runs as: one, or N under mpirun or srun (Open MPI).
//
// Run without a launcher, tripath never initialises MPI and behaves as a plain program. Under a
// launcher (detected from its environment), every rank parses the same command line and so
// reaches the same verdict on it; only rank 0 writes to the terminal and to files. Whatever a rank
// could find differently from rank 0 (the scene file, an output folder) is checked by `together`,
// so that one bad rank ends the whole job with one error line naming it, not a hang. Each rank pins
// the narrowest of the ranks' best Embree ISAs before it builds a scene (embree_isa.h).
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "integrators/team.h"

namespace tripath::app {

class Processes {
public:
    // Initialises MPI when launched by mpirun/srun; otherwise a team of one.
    Processes(int& argc, char**& argv);
    ~Processes();
    Processes(const Processes&) = delete;
    Processes& operator=(const Processes&) = delete;

    // An error thrown on this rank after the command line was parsed, where other ranks may wait
    // in a collective: prints it with the rank and ends the job (MPI_Abort), or returns to report
    // it normally when this is the only process.
    void fail(const std::string& message, int exitCode);
};

// True under mpirun/srun, even with one rank.
bool launched();
// The team of this command's processes (solo() without a launcher).
Team& team();
bool isRankZero();

// tripath::together (integrators/team.h) over this command's team.
void together(const std::function<void()>& step);

}  // namespace tripath::app
