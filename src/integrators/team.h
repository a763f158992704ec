// The processes that share one render. The render loop (render.h) deals canonical blocks of passes
// out to them round by round and asks the team, at each round's end, whether any of them must
// stop; at the end it adds their films into rank 0's. One process is a team of one (`solo()`);
// under mpirun the command line passes apps/mpi_team.cpp's, so that this layer knows nothing of
// MPI and a render gives the same bits whichever team renders it.
#pragma once
#include <cstdint>
#include <span>

namespace tripath {

class Film;

class Team {
public:
    virtual ~Team() = default;
    virtual int rank() const = 0;
    virtual int size() const = 0;
    // Collective: true on every rank if `local` is true on any.
    virtual bool any(bool local) = 0;
    // Collective: every rank gets the element-wise sums over ranks.
    virtual void sum(std::span<uint64_t> values) = 0;
    // Collective: the element-wise maximum over ranks, on every rank.
    virtual void max(std::span<uint64_t> values) = 0;
    // Collective: rank 0's film becomes the sum of every rank's (their blocks ended); the others'
    // films are left as they were.
    virtual void reduce(Film& film) = 0;
};

// The team of one process: every collective is the identity.
Team& solo();

}  // namespace tripath
