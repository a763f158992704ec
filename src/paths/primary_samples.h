// A point in primary sample space: the unit hypercube whose coordinates the walks read in place of
// a random stream (Kelemen et al. 2002), and the moves a Markov chain makes in it (markov_chain.h).
//
// A proposal either draws every coordinate afresh (a large step) or moves each by a Gaussian step
// of standard deviation kSmallStepSigma wrapped around [0, 1), the coordinate space being a torus
// (a small step). Both kernels are symmetric, so the acceptance probability is the ratio of the
// targets alone. A rejected proposal restores every coordinate it changed.
//
// Coordinates move lazily, when a walk first reads them in a proposal: one last moved by n
// accepted small steps ago takes one Gaussian step of σ √n, the sum of the n it missed; one not
// read since the last accepted large step is drawn afresh, as that step would have drawn it. So a
// proposal costs what its path reads, however long the chain's other paths were.
//
// Coordinates come in streams, interleaved (coordinate i of stream s is number kStreams·i + s): the
// camera walk's, the light walk's and the strategy's (the choice of (s, t) and next-event
// estimation). A walk that draws one number more or fewer shifts its own stream only: a longer
// light subpath does not move the camera's coordinates.
#pragma once
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/rng.h"

namespace tripath {

// A value's bytes appended to `out`, and taken back off the front of `in` (InputError if `in` is
// shorter): the chains' saved states, read on the machine that wrote them.
template <class T>
void putBytes(std::string& out, const T& v) {
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
}
template <class T>
T takeBytes(std::string_view& in) {
    if (in.size() < sizeof(T)) throw InputError("a Markov chain's saved state is cut short");
    T v;
    std::memcpy(&v, in.data(), sizeof v);
    in.remove_prefix(sizeof v);
    return v;
}

class PrimarySamples {
public:
    enum class Stream { Camera, Light, Strategy };
    static constexpr int kStreams = 3;
    // The best of 1/32 to 1/1024 at equal time on door-ajar (bench/README.md, "Metropolis").
    static constexpr double kSmallStepSigma = 1.0 / 128;

    // Begins the next proposal: a large step or a small one, drawing what it needs from `fresh`
    // (which must outlive the proposal). The first proposal of a new point is a large step.
    void propose(bool largeStep, Rng& fresh);
    // Keeps the proposal as the chain's state, or goes back to the state before it.
    void accept();
    void reject();

    // The walks read the stream set last (each stream from its first coordinate on, per proposal).
    void startStream(Stream s) { stream_ = static_cast<int>(s); }
    float uniform();
    // A chain's coordinates are its own layout, a stream's in the order the walk reads them
    // (Sampler): the walks' sets of dimensions change nothing here.
    void dimensions(DimensionSet) {}

    // The state between proposals, as bytes (a checkpoint's), and back: read() takes its bytes off
    // the front of `in` and throws InputError if they are cut short.
    void write(std::string& out) const;
    void read(std::string_view& in);

    // The memory `coordinates` coordinates take.
    static size_t bytesFor(size_t coordinates);

private:
    struct Coordinate {
        float value = 0, backup = 0;
        int64_t moved = -1, backupMoved = -1;  // the proposal that last moved it (-1: never)
    };
    std::vector<Coordinate> x_;
    int64_t proposal_ = -1;       // the current proposal's number, counting accepted ones only
    int64_t lastLargeStep_ = 0;   // the number of the last accepted large step
    bool largeStep_ = true;
    Rng* fresh_ = nullptr;
    int stream_ = 0;
    std::array<uint32_t, kStreams> next_{};  // per stream, the next coordinate to read
};

}  // namespace tripath
