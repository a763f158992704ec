#include "paths/primary_samples.h"

#include <cmath>
#include <numbers>


namespace tripath {

namespace {

// A standard normal number (Box–Muller's cosine branch), in double on every compiler alike.
double standardNormal(Rng& rng) {
    const double u1 = 1.0 - double(rng.uniform()), u2 = rng.uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

// x wrapped into [0, 1).
float wrap(double x) {
    const float w = static_cast<float>(x - std::floor(x));
    return w < 1.0f ? w : 0.0f;
}

}  // namespace

void PrimarySamples::propose(bool largeStep, Rng& fresh) {
    ++proposal_;
    largeStep_ = largeStep || proposal_ == 0;
    fresh_ = &fresh;
    next_.fill(0);
    stream_ = 0;
}

void PrimarySamples::accept() {
    if (largeStep_) lastLargeStep_ = proposal_;
}

void PrimarySamples::reject() {
    for (Coordinate& c : x_)
        if (c.moved == proposal_) {
            c.value = c.backup;
            c.moved = c.backupMoved;
        }
    --proposal_;
}

float PrimarySamples::uniform() {
    const size_t i = size_t(next_[size_t(stream_)]++) * kStreams + size_t(stream_);
    if (i >= x_.size()) x_.resize(i + 1);
    Coordinate& c = x_[i];
    if (!largeStep_ && c.moved < lastLargeStep_) {  // not read since the last large step: drawn as it would have
        c.value = fresh_->uniform();
        c.moved = lastLargeStep_;
    }
    c.backup = c.value;
    c.backupMoved = c.moved;
    if (largeStep_)
        c.value = fresh_->uniform();
    else
        c.value = wrap(c.value + kSmallStepSigma * std::sqrt(double(proposal_ - c.moved)) * standardNormal(*fresh_));
    c.moved = proposal_;
    return c.value;
}

size_t PrimarySamples::bytesFor(size_t coordinates) { return coordinates * sizeof(Coordinate); }

void PrimarySamples::write(std::string& out) const {
    putBytes(out, proposal_);
    putBytes(out, lastLargeStep_);
    putBytes(out, uint64_t(x_.size()));
    for (const Coordinate& c : x_) {
        putBytes(out, c.value);
        putBytes(out, c.moved);
    }
}

void PrimarySamples::read(std::string_view& in) {
    proposal_ = takeBytes<int64_t>(in);
    lastLargeStep_ = takeBytes<int64_t>(in);
    const uint64_t n = takeBytes<uint64_t>(in);
    if (n > in.size()) throw InputError("a Markov chain's saved state is cut short");
    x_.assign(n, {});
    for (Coordinate& c : x_) {
        c.value = takeBytes<float>(in);
        c.moved = takeBytes<int64_t>(in);
    }
}

}  // namespace tripath
