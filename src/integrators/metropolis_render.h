// mlt's passes: Markov chains of multiplexed Metropolis light transport (paths/markov_chain.h)
// over path lengths 1 … max-depth, rendered in the loop every method shares (render_loop.h),
// reproducible whatever the number of threads and of processes.
//
// 1. Bootstrap. N samples (MetropolisSettings::bootstrap), spread evenly over the lengths, each a
//    fresh point of primary sample space: b_k, the mean luminance of C_k over length k's samples,
//    estimates E[L(C_k)], the brightness of the length-k image. A stop request (RenderSettings::stop)
//    during it ends the render at once, before any pass: a partial bootstrap would give other b_k
//    and chains than a resumed render redoes, so there is nothing to write or checkpoint
//    (RenderResult::interruptedBeforeAnyPass).
// 2. Chains. The render's C chains (MetropolisSettings::chains, at most one per pixel) are shared
//    among the lengths in proportion to b_k (Hachisuka et al. 2014, §4), at least one for each
//    length with b_k > 0. Chain i of length k starts at a bootstrap sample of that length drawn in
//    proportion to its luminance (so its start follows the stationary density as closely as N
//    samples allow), the draw coming from chain i's own stream.
// 3. Passes. In each pass every chain takes m = ⌈P / C⌉ steps (P pixels): about one step per pixel,
//    so --spp counts steps per pixel. The contributions of length k's n_k chains are scaled by
//    b_k / (n_k m) per pass: the film's sum over its passes, divided by them (film.h), is then
//    Σ_k b_k / M_k Σ (contributions), M_k being length k's steps: an estimate of the image whose
//    expectation over runs is the image (unbiased), but which within one run converges to the
//    image scaled per length by b_k / E[L(C_k)], since b_k is not refined as the chains run (not
//    consistent in a run; see the last paragraph).
//
// Streams: bootstrap sample j and chain i draw from (seed, a Metropolis domain, an index made of
// the run and j or i, step by step), never from a thread's or a rank's. The run is the pass
// index the render started at (a reference continued without a checkpoint starts fresh chains
// there, independent of the earlier ones). Chains are dealt to ranks by index (i mod ranks) and
// to threads by TBB; each chain's contributions are added straight into the film's exact totals
// (Film::addExactly), in no order that matters: the image is bit-identical for any thread and rank
// count. A checkpoint holds every chain's state, so a resumed render continues each chain where it
// stopped, and ends bit-identical to an uncut one; the bootstrap, a function of the seed, is
// redone on resuming.
//
// No start-up bias, at any N: a chain starts at a bootstrap sample drawn in proportion to its
// luminance and its length is scaled by the bootstrap's mean b_k, so for any function h of its
// state after t steps E[b_k h(x_t)] = ∫ L (K^t h) = b_true π(h), the chain's kernel K keeping its
// stationary density π (docs/design.md §1.2). b_k is fixed after the bootstrap: its noise, about
// the relative spread of L(C_k) over √N_k, scales a run's length-k image and more passes do not
// reduce it (independent runs average it out; a larger N shrinks it).
#pragma once
#include "integrators/render.h"

namespace tripath {

RenderResult renderMetropolis(const Scene& scene, const Integrator& integrator, const RenderSettings& settings);

// What the loop holds besides its film, for an image of `pixels` pixels, at most: the chains' states
// (each taken over paths of `maxDepth` segments, the longest), their splats of one pass (a step per
// pixel, two splats a step) and the bootstrap's luminances as they are gathered.
struct MetropolisMemory {
    uint64_t chains = 0, splats = 0, bootstrap = 0;
};
MetropolisMemory metropolisMemory(double pixels, const MetropolisSettings& settings, int maxDepth);

}  // namespace tripath
