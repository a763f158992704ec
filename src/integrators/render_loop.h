// The loop over passes that every method renders in, written once: the clock and stop requests,
// progress and onPass callbacks (whose time is the caller's), checkpoints at round boundaries, the
// team's reductions of counts and films, and the stats. What differs between methods is what a
// pass is and how the passes are dealt to the team's ranks; a method says that through a
// PassSource and runs runPasses with it, from its Integrator::render (integrator.h): the fixed
// methods' camera samples in tiles (PixelSampleIntegrator::render, render.cpp), mlt's Markov
// chains (metropolis_render.cpp).
//
// The loop goes in rounds. In a round each rank renders the passes its source deals it, then the
// team decides together whether to go on (the clock, a stop request, the budget), and at a
// checkpoint interval hands rank 0 the whole render so far. A source whose ranks own their
// passes (the fixed methods' blocks) may also stop a rank inside its round, at a pass boundary;
// one whose ranks share every pass (mlt's chains) stops only where the team decides.
#pragma once
#include <cstdint>

#include "integrators/render.h"

namespace tripath {

class PassSource {
public:
    virtual ~PassSource() = default;
    // Work done once before the first round, on the render's clock (mlt's bootstrap); false when
    // a stop request ended it, on every rank alike, before there was any pass to render.
    virtual bool start(RenderResult&) { return true; }
    // Before each round, on every rank together (collective): auto chooses there the plans of a
    // stretch that starts with the round, so that no choice is made for passes that never come.
    virtual void beginRound(Film&) {}
    // This rank's passes in round `round`, as offsets [begin, end) from the render's first pass,
    // clipped to `budget` passes (UINT64_MAX: no bound).
    virtual std::pair<uint64_t, uint64_t> round(uint64_t round, uint64_t budget) const = 0;
    // Whether the rounds up to `round` used the whole budget, on every rank alike.
    virtual bool budgetDone(uint64_t round, uint64_t budget) const = 0;
    // Whether a rank may stop inside its round, alone: its passes are its own.
    virtual bool stopsAlone() const = 0;
    // The pass of offset `offset` (its index the render's first pass plus it), into `result`.
    virtual void run(uint64_t offset, RenderResult& result) = 0;
    // After a round's passes, before the team decides (the fixed methods end their block).
    virtual void endRound(Film&) {}
    // The passes done over the team when this rank has done `local`, for progress.
    virtual int passesDone(uint64_t local) const = 0;
    // The team's render so far in `into` (collective): its passes, next pass, counts and the
    // method's state, and, on rank 0, every rank's film added into `into.film`; `mine` is this
    // rank's own film (`into.film` itself at the end). `local` and `localNext`: the passes this
    // rank rendered and one past the highest pass index it used. `counts` holds this rank's
    // dropped samples and guarded weights.
    virtual void gather(RenderResult& into, Film& mine, uint64_t local, uint64_t localNext, const RenderResult& counts) = 0;
};

// Renders with `source` into `result` (its film made, its budget set): the loop above. Rank 0's
// result gains the resumed render (settings.resume), unless the render stopped in its source's
// start (RenderResult::interruptedBeforeAnyPass).
RenderResult runPasses(const RenderSettings& settings, PassSource& source, RenderResult result);

}  // namespace tripath
