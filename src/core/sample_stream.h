// What a path draws its numbers from in the render loop: a pixel's sample or a light path of a
// pass, under `--sampler`.
//
// - independent: one random stream (rng.h) per sample, its numbers in the order they are asked for.
// - sobol: scrambled Sobol points (sobol.h). The path says which set of four dimensions its next
//   draws belong to (paths/sample_dimensions.h: a set per purpose and vertex, so that a longer
//   path never shifts an earlier vertex's numbers); the set's numbers are dimensions 0–3 of point
//   `index` (the sample's pass) of a stream whose index is keyed by the seed, the domain, the
//   stream (a pixel or a light path) and the set, and whose dimensions by the same but the set
//   (sobol.h). Draws past four in a set come from the sample's independent stream.
//   So the samples of a pixel, pass after pass, are stratified in each set's dimensions, and
//   independent between pixels, between sets and between domains (a reference's never share a
//   run's).
// A sample's numbers depend on the seed, the domain, the stream, the pass and the dimension only:
// the same for any thread or rank that draws them.
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "core/rng.h"
#include "core/sobol.h"

namespace tripath {

enum class SamplerKind { Independent, Sobol };

// Whose numbers a render draws: its seed, the domain of its camera samples (its light paths' is
// lightPathDomain's) and its sampler; and, for Sobol points, which of the seed's scrambles (0: its
// own). Passes of different scrambles are independent, as passes of independent numbers are;
// passes of one are stratified together.
struct StreamSource {
    uint64_t seed = 1;
    StreamDomain domain = StreamDomain::CameraSample;
    SamplerKind sampler = SamplerKind::Sobol;
    uint64_t scramble = 0;
    // The seed a Sobol stream is keyed by.
    uint64_t sobolSeed() const { return scramble == 0 ? seed : mix64(seed ^ mix64(scramble)); }
};

// The sampler named "independent" or "sobol"; nullopt for another name.
std::optional<SamplerKind> samplerNamed(const std::string& name);

class SampleStream {
public:
    // Sample `index` of stream `stream` in `domain`; `independent` is its random stream (the whole
    // of an independent sample; a Sobol sample's draws past four in a set).
    SampleStream(SamplerKind kind, uint64_t seed, StreamDomain domain, uint64_t stream, uint64_t index, Rng independent)
        : rng_(independent),
          key_(kind == SamplerKind::Sobol ? mix64(seed ^ mix64(static_cast<uint64_t>(domain) ^ mix64(stream ^ mix64(index >> 32))))
                                          : 0),
          index_{kind == SamplerKind::Sobol ? reverseBits(static_cast<uint32_t>(index)) : 0},
          dimensionKeys_(kind == SamplerKind::Sobol ? SobolPoint::dimensionKeys(key_) : SobolPoint::DimensionKeys{}),
          sobol_(kind == SamplerKind::Sobol) {
        dimensions({0, 0});
    }
    // The next draws are set `set`'s dimensions, from its first on (the set's point made once
    // for draws from it in turn).
    void dimensions(DimensionSet set) {
        if (!sobol_) return;
        if (set.index != set_) {
            point_ = SobolPoint(index_, static_cast<uint32_t>(mix64(key_ + set.index)), dimensionKeys_);
            set_ = set.index;
        }
        first_ = set.first;
        used_ = 0;
    }
    float uniform() {
        if (used_ < 4) return fractionToFloat(point_[(first_ + used_++) & 3]);
        return rng_.uniform();
    }

private:
    Rng rng_;
    uint64_t key_;
    SobolPoint::ReversedIndex index_;
    SobolPoint::DimensionKeys dimensionKeys_;
    bool sobol_;
    int first_ = 0, used_ = 4;
    uint32_t set_ = UINT32_MAX;  // the set of point_
    SobolPoint point_;
};

}  // namespace tripath
