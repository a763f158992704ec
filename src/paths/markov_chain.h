// One Markov chain of Metropolis light transport over the paths of one length k: its state is a
// point of primary sample space (primary_samples.h), its stationary density is proportional to the
// luminance of the multiplexed target C_k (multiplexed_target.h), and each step proposes a large
// or a small step and accepts it with probability
//     a = min(1, L(proposal) / L(current)),      L = luminance of C_k,
// both kernels being symmetric. Each step contributes by expected values (Veach 1997, §11.3.4):
// the proposal's C / L with weight a and the current state's with weight 1 − a, so that rejected
// proposals are not wasted. Scaled by b_k / M_k (b_k = E[L], M_k the length's steps), the
// contributions landing in pixel j sum to that pixel's length-k value (metropolis_render.h).
//
// A proposal whose value is not finite is rejected, contributes nothing, and is reported.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

#include "paths/multiplexed_target.h"

namespace tripath {

// The acceptance probability of moving from a state of luminance `current` to one of `proposed`
// (from a state of luminance 0, which a started chain never holds, every proposal is accepted).
inline float acceptance(float current, float proposed) {
    return current > 0 ? std::min(1.0f, proposed / current) : 1.0f;
}

// What one step did.
enum class StepOutcome { Accepted, Rejected, NotFinite };

class MarkovChain {
public:
    explicit MarkovChain(int length = 1) : length_(length) {}
    int length() const { return length_; }
    const PathSample& current() const { return current_; }
    uint64_t steps() const { return steps_; }        // steps taken since start()
    uint64_t accepted() const { return accepted_; }  // of which accepted
    uint64_t guardedWeights() const { return guarded_; }  // proposals whose MIS weight was guarded to 0 (mis.h), in this process

    // Starts the chain at the point `fresh` draws, evaluated: a bootstrap sample's stream gives
    // that sample's point and value again.
    void start(const MultiplexedTarget& target, Rng& fresh, TargetPaths& paths);

    // One step: a large step with probability `largeStepProbability`, drawing every choice from
    // `rng`. splat(sample, weight) receives the proposal (weight a / L) and the current state
    // (weight (1 − a) / L) where those weights are above 0.
    template <class Splat>
    StepOutcome step(const MultiplexedTarget& target, float largeStepProbability, Rng& rng, TargetPaths& paths,
                     Splat&& splat);

    // The state between steps (its point and its value), as bytes and back; read() takes its
    // bytes off the front of `in` and throws InputError if they are cut short.
    void write(std::string& out) const;
    void read(std::string_view& in);

    // The most memory a chain over paths of length k holds: itself and its point's coordinates,
    // of which its walks read at most 9k + 3 (measured on cornell, cornell-spheres, sky and
    // furnace-0.9: 12 at k = 1, 35 at k = 4, 143 at k = 16).
    static size_t bytesFor(int k) { return sizeof(MarkovChain) + PrimarySamples::bytesFor(9 * size_t(k) + 3); }

private:
    int length_;
    PrimarySamples u_;
    PathSample current_;
    uint64_t steps_ = 0, accepted_ = 0, guarded_ = 0;
};

template <class Splat>
StepOutcome MarkovChain::step(const MultiplexedTarget& target, float largeStepProbability, Rng& rng, TargetPaths& paths,
                              Splat&& splat) {
    ++steps_;
    const bool large = rng.uniform() < largeStepProbability;
    u_.propose(large, rng);
    PathSample proposal = evaluateTarget(target, length_, u_, paths);
    guarded_ += proposal.weightGuarded;
    const bool finite = isFinite(proposal.value);
    const float lp = finite ? proposal.luminance() : 0.0f, lc = current_.luminance();
    const float a = finite ? acceptance(lc, lp) : 0.0f;
    if (a > 0 && lp > 0) splat(proposal, a / lp);
    if (a < 1 && lc > 0) splat(current_, (1 - a) / lc);
    if (rng.uniform() < a) {
        u_.accept();
        current_ = proposal;
        ++accepted_;
        return StepOutcome::Accepted;
    }
    u_.reject();
    return finite ? StepOutcome::Rejected : StepOutcome::NotFinite;
}

}  // namespace tripath
