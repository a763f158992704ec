// The renders of `tripath compare`: the reference (read or rendered) and each method's runs,
// with their error measured at checkpoints while they render.
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>

#include "compare.h"
#include "processes.h"
#include "core/error.h"
#include "image/flip.h"

namespace tripath::app {

namespace {

// Without --reference, --reference-integrator (bdpt) renders one for this many times the per-method
// budget. Its own noise then adds about 1/10 of that method's error to every measurement: fine for ranking methods,
// and the message says how to do better.
constexpr double kReferenceBudget = 10;

// The largest k with t_k <= seconds, or -1 before t_0.
int targetReached(double seconds, double budget) {
    if (!(seconds > 0)) return -1;
    const double k = std::floor(kTargets + kPerDecade * std::log10(seconds / budget) + 1e-9);
    return static_cast<int>(std::min<double>(kTargets, std::max(-1.0, k)));
}

Reference readGivenReference(const CompareOptions& o) {
    const RenderOptions& r = o.render;
    ReferenceFile file = readReference(o.referencePath);
    requireSize(file, r.width, r.height);
    // A reference of another scene or depth limit converges to another image; an external file
    // without metadata is taken on trust.
    requireSettings(file, {{"tripath:scene", r.scene}, {"tripath:max-depth", std::to_string(r.maxDepth)}}, true);
    // A run shares samples with the reference only if both drew from the same streams: the same
    // domain and the same seed. References from `tripath reference` use their own domain, so only
    // an image from `tripath render` (or an older reference) with one of the runs' seeds is refused.
    const auto seed = file.value("tripath:seed");
    if (seed && streamDomain(file) == r.domain) {
        const uint64_t s = std::strtoull(seed->c_str(), nullptr, 10);
        if (s >= r.seed && s < r.seed + uint64_t(o.runs))
            throw InputError(fmt::format("reference '{}' was rendered with seed {} in the render streams, which run {} "
                                         "would reuse (shared samples hide error): pass e.g. --seed {}, or make the "
                                         "reference with `tripath reference`",
                                         o.referencePath, s, s - r.seed, s + 1));
    }
    return {std::move(file.image), file.description(), o.referencePath};
}

Reference renderReference(const CompareOptions& o, const Scene& scene) {
    RenderOptions r = o.render;
    r.integrator = o.referenceIntegrator;
    r.seconds = o.referenceSeconds > 0 ? o.referenceSeconds : kReferenceBudget * o.render.seconds;
    r.domain = StreamDomain::Reference;  // the reference streams: independent of every run
    const std::string file =
        o.referenceOut.empty() ? (std::filesystem::path(o.outDir) / "reference.exr").string() : o.referenceOut;
    std::cerr << fmt::format(
        "no --reference: rendering one with {} for {:g} x {} = {} (seed {}, reference streams) into {}; its own "
        "noise adds about 1/{:g} of {}'s error to each measurement. For a cleaner one, see `tripath reference`.\n",
        r.integrator, kReferenceBudget, formatSeconds(o.render.seconds), formatSeconds(r.seconds), r.seed, file,
        kReferenceBudget, r.integrator);
    const auto integrator = makeIntegrator(r.integrator, integratorSettings(r));
    RenderSettings rs = renderSettings(r);
    rs.team = &team();  // every rank renders the reference together
    const std::string label = "reference " + r.integrator + " " + r.scene;
    rs.progress = progressReporter(rs, r.width, r.height, label);
    const RenderResult result = render(scene, *integrator, rs);  // by every rank together
    if (isRankZero()) {
        printSummary(label, result, r);
        writeExr(file, result.image(), renderMetadata(r, scene, *integrator, result, team().size()));
    }
    return {result.image(), fmt::format("{}, {} spp, {:.0f} s", r.integrator, result.passes, result.seconds), file};
}

}  // namespace

Reference obtainReference(const CompareOptions& o, const Scene& scene) {
    return o.referencePath.empty() ? renderReference(o, scene) : readGivenReference(o);
}

RunOutput runMethod(const CompareOptions& o, const Scene& scene, const std::string& method, int index,
                    const Image& reference) {
    RenderOptions ro = o.render;
    ro.integrator = method;
    ro.seed = o.render.seed + uint64_t(index);
    Run run{method, index, ro.seed, {}};
    const auto integrator = makeIntegrator(method, integratorSettings(ro));
    RenderSettings rs = renderSettings(ro);
    rs.team = &solo();  // a run is timed alone on its rank: compare_ranks.cpp deals the runs out
    rs.stop = o.stop;
    const std::string label = fmt::format("{} run {}/{}", method, index + 1, o.runs);
    rs.progress = progressReporter(rs, ro.width, ro.height, label);
    // Measuring happens inside onPass, whose time the render loop leaves out of the budget.
    rs.onPass = [&](const Film& film, int passes, double seconds) {
        const int k = targetReached(seconds, ro.seconds);
        if (k < 0 || (!run.checkpoints.empty() && k <= run.checkpoints.back().target)) return;
        run.checkpoints.push_back({k, seconds, passes, compareImages(film.image(passes), reference)});
    };
    const RenderResult r = render(scene, *integrator, rs);
    Image image = r.image();
    // The finished render is the last checkpoint, at target T, whatever the last pass measured.
    if (run.checkpoints.empty() || run.checkpoints.back().spp != r.passes)
        run.checkpoints.push_back({kTargets, r.seconds, r.passes, compareImages(image, reference)});
    run.checkpoints.back().target = kTargets;
    run.stats = r.stats;
    run.flip = hdrFlip(image, reference, flipExposures(reference));
    printSummary(label, r, ro);
    const Checkpoint& f = run.final();
    std::cerr << fmt::format("{}: relMSE {:.4g}, MSE {:.4g}, MAE {:.4g}, relMSE*spp {:.4g}, {} of the error in the worst 0.1% of "
                             "pixels, HDR-FLIP {:.4g}\n",
                             label, f.error.relMse, f.error.mse, f.error.mae, perSampleRelVariance(f.error.relMse, f.spp),
                             tailShareText(f.error.tailShare), run.flip);
    return {std::move(run), std::move(image), renderMetadata(ro, scene, *integrator, r, team().size())};
}

}  // namespace tripath::app
