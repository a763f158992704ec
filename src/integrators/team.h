// The processes that share one render. The render loop (render.h) deals canonical blocks of passes
// out to them round by round and asks the team, at each round's end, whether any of them must
// stop; at the end it adds their films into rank 0's. Comparisons (evaluation/) deal whole runs
// out and gather them as bytes. One process is a team of one (`solo()`); under mpirun the command
// line passes the team of its MPI ranks (apps/processes.h), so that this layer knows nothing of
// MPI and a render gives the same bits whichever team renders it.
#pragma once
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

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
    // Collective: rank 0's bytes, on every rank.
    virtual void broadcast(std::string& bytes) = 0;
    // Collective: every rank's bytes in rank order, on rank 0 (nothing on the others).
    virtual std::vector<std::string> gather(const std::string& mine) = 0;
};

// The team of one process: every collective is the identity.
Team& solo();

// Runs `step` on every rank; if it throws InputError on any, every rank throws one InputError with
// the lowest failing rank's message (prefixed "rank N: " when that is not rank 0). Whatever a rank
// could find differently from rank 0 (a file, a folder) is checked this way, so that one bad rank
// ends the job with one line naming it instead of leaving the others waiting in a collective.
void together(Team& team, const std::function<void()>& step);

}  // namespace tripath
