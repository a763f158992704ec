// Reproducible random streams. Every (pixel, sample index) and every light-path index owns a
// stream derived by hashing (seed, domain, index), so an image depends on the seed and the sample
// count only -- never on which thread drew the numbers or in what order (docs/design.md §4).
#pragma once
#include <concepts>
#include <cstdint>
#include <utility>

namespace tripath {

// SplitMix64 finaliser: a strong 64-bit mix, used to turn stream coordinates into a PCG state.
inline uint64_t mix64(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// A set of four dimensions of a low-discrepancy sampler (sample_stream.h), named by a walk before
// its draws (paths/sample_dimensions.h), and the dimension the set's first draw reads; the next
// draws follow it, wrapping around. Dimensions 0 and 1 are the best stratified pair, so a set
// whose draws are one number for a choice and then a pair for a point starts at 3.
struct DimensionSet {
    uint32_t index = 0;
    int first = 0;
};

// PCG32 (O'Neill 2014): small state, good statistics, cheap.
class Rng {
public:
    Rng(uint64_t seed, uint64_t domain, uint64_t index) {
        state_ = 0;
        inc_ = (mix64(index ^ mix64(domain)) << 1u) | 1u;
        next();
        state_ += mix64(seed ^ mix64(index + 0x632be59bd9b4e019ull * (domain + 1)));
        next();
    }
    uint32_t next() {
        const uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        const uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
    }
    // Uniform in [0, 1): 24 random bits, so the result is exactly representable and < 1.
    float uniform() { return static_cast<float>(next() >> 8) * 0x1p-24f; }
    // Independent numbers have no layout of dimensions (Sampler): the next draw is the next number.
    void dimensions(DimensionSet) {}

private:
    uint64_t state_, inc_;
};

// What the path walks draw their numbers from: a random stream (Rng), the render loop's sampler
// (sample_stream.h) or a point in primary sample space that a Markov chain moves
// (paths/primary_samples.h). Each hands out uniforms in [0, 1); a walk says before its draws which
// set of dimensions they belong to (paths/sample_dimensions.h), which only a low-discrepancy
// sampler heeds. One walk, kernel and MIS weight serves them all.
template <class S>
concept Sampler = requires(S& s) {
    { s.uniform() } -> std::same_as<float>;
    s.dimensions(DimensionSet{});
};

// Stream domains: keep camera samples, light paths and anything else from sharing streams.
// Reference: the per-pixel sample streams of `tripath reference` (and of the reference `tripath
// compare` renders for itself), so that a reference is independent of every render made with the
// same seed. LightPath and ReferenceLightPath: the light phase's paths (index pass × N_L + path)
// of renders and of references. The values are part of every stored image's identity: none is
// ever reused (2 is left unused), and new domains go at the end.
// Metropolis (MetropolisBootstrap, MetropolisChain and their Reference twins): the bootstrap
// samples of mlt's normalisation and its chains' proposals (integrators/metropolis_render.h).
enum class StreamDomain : uint64_t {
    CameraSample = 1,
    Test = 3,
    Reference = 4,
    LightPath = 5,
    ReferenceLightPath = 6,
    MetropolisBootstrap = 7,
    MetropolisChain = 8,
    ReferenceMetropolisBootstrap = 9,
    ReferenceMetropolisChain = 10
};

// The light paths' domain that goes with a camera samples' domain.
inline StreamDomain lightPathDomain(StreamDomain cameraDomain) {
    return cameraDomain == StreamDomain::Reference ? StreamDomain::ReferenceLightPath : StreamDomain::LightPath;
}

// The Metropolis domains that go with a camera samples' domain: (bootstrap, chain).
inline std::pair<StreamDomain, StreamDomain> metropolisDomains(StreamDomain cameraDomain) {
    if (cameraDomain == StreamDomain::Reference)
        return {StreamDomain::ReferenceMetropolisBootstrap, StreamDomain::ReferenceMetropolisChain};
    return {StreamDomain::MetropolisBootstrap, StreamDomain::MetropolisChain};
}

}  // namespace tripath
