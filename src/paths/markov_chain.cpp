#include "paths/markov_chain.h"

#include "paths/primary_samples.h"

namespace tripath {

void MarkovChain::start(const MultiplexedTarget& target, Rng& fresh, TargetPaths& paths) {
    u_ = PrimarySamples();
    steps_ = accepted_ = guarded_ = 0;
    u_.propose(true, fresh);
    current_ = evaluateTarget(target, length_, u_, paths);
    u_.accept();
}

void MarkovChain::write(std::string& out) const {
    u_.write(out);
    const PathSample& c = current_;
    putBytes(out, std::array<float, 5>{c.value.x, c.value.y, c.value.z, c.raster.x, c.raster.y});
    putBytes(out, std::array<int32_t, 2>{c.strategy.s, c.strategy.t});
    putBytes(out, std::array<uint64_t, 2>{steps_, accepted_});
}

void MarkovChain::read(std::string_view& in) {
    u_.read(in);
    const auto f = takeBytes<std::array<float, 5>>(in);
    const auto st = takeBytes<std::array<int32_t, 2>>(in);
    const auto counts = takeBytes<std::array<uint64_t, 2>>(in);
    current_ = {.value = Spectrum(f[0], f[1], f[2]), .raster = {f[3], f[4]}, .strategy = {st[0], st[1]}};
    steps_ = counts[0];
    accepted_ = counts[1];
}

}  // namespace tripath
