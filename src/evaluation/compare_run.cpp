// The renders of a comparison: the reference (read, given or rendered) and each method's runs,
// with their error measured at checkpoints while they render.
#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <filesystem>

#include "evaluation/compare.h"
#include "core/error.h"
#include "evaluation/flip.h"
#include "requests/scene_identity.h"

namespace tripath::evaluation {

namespace {

// The largest k with t_k <= seconds, or -1 before t_0.
int targetReached(double seconds, double budget) {
    if (!(seconds > 0)) return -1;
    const double k = std::floor(kTargets + kPerDecade * std::log10(seconds / budget) + 1e-9);
    return static_cast<int>(std::min<double>(kTargets, std::max(-1.0, k)));
}

}  // namespace

Reference readGivenReference(const CompareRequest& o, const Scene& scene) {
    const RenderRequest& r = o.render;
    ReferenceFile file = readReference(o.referencePath);
    requireSize(file, r.width, r.height);
    // A reference of other scene files or another depth limit converges to another image; an
    // external file without metadata is taken on trust.
    requireSettings(file,
                    {{kSceneFilesKey, sceneFilesText(scene.sources())}, {"tripath:max-depth", std::to_string(r.maxDepth)}},
                    true);
    // A run shares samples with the reference only if both drew from the same streams: the same
    // domain and the same seed. References from `tripath reference` use their own domain, so only
    // an image from `tripath render` (or an older reference) with one of the runs' seeds is refused.
    const auto seed = file.value("tripath:seed");
    if (seed && streamDomain(file) == r.domain) {
        const uint64_t s = file.wholeNumber("tripath:seed", UINT64_MAX, 0);
        if (s >= r.seed && s < r.seed + uint64_t(o.runs))
            throw InputError(fmt::format("reference '{}' was rendered with seed {} in the render streams, which run {} "
                                         "would reuse (shared samples hide error): pass e.g. --seed {}, or make the "
                                         "reference with `tripath reference`",
                                         o.referencePath, s, s - r.seed, s + 1));
    }
    return {std::move(file.image), file.description(), o.referencePath};
}

namespace {

// The callbacks of a render on this rank: progress and the summary at its end come from rank 0 alone.
void narrate(const CompareRequest& o, RenderSettings& rs, const std::string& label) {
    if (o.narrator.progress && o.team->rank() == 0) rs.progress = o.narrator.progress(label, rs, o.render.width, o.render.height);
}
void finished(const CompareRequest& o, const std::string& label, const RenderResult& result, const RenderRequest& r) {
    if (o.narrator.finished && o.team->rank() == 0) o.narrator.finished(label, result, r);
}

Reference renderReference(const CompareRequest& o, const Scene& scene) {
    const RenderRequest r = referenceRequest(o);
    const std::string file = !o.referenceOut.empty() ? o.referenceOut
                             : o.outDir.empty()      ? std::string()
                                                     : (std::filesystem::path(o.outDir) / "reference.exr").string();
    o.narrator.tell(*o.team,
                    fmt::format("no reference given: rendering one with {} for {:g} x {} = {} (seed {}, reference "
                                "streams){}; its own noise adds about 1/{:g} of {}'s error to each measurement. For a "
                                "cleaner one, make it with `tripath reference` and pass it as the reference.",
                                r.integrator, kReferenceBudget, formatSeconds(o.render.seconds), formatSeconds(r.seconds),
                                r.seed, file.empty() ? "" : " into " + file, kReferenceBudget, r.integrator));
    const auto integrator = makeIntegrator(r.integrator, integratorSettings(r));
    RenderSettings rs = renderSettings(r, o.spelling);
    rs.team = o.team;  // every rank renders the reference together
    rs.stop = o.stop;
    const std::string label = "reference " + r.integrator + " " + r.scene;
    narrate(o, rs, label);
    const RenderResult result = render(scene, *integrator, rs);  // by every rank together
    finished(o, label, result, r);
    // Stopped in mlt's bootstrap, it has no pass, so no file: the compare ends interrupted.
    if (result.interruptedBeforeAnyPass) return {};
    if (o.team->rank() == 0 && !file.empty()) {
        createDirectory(std::filesystem::path(file).parent_path().string());
        writeExr(file, result.image(), renderMetadata(r, scene, *integrator, result, o.team->size()));
    }
    return {result.image(), fmt::format("{}, {} spp, {:.0f} s", r.integrator, result.passes, result.seconds), file};
}

}  // namespace

RenderRequest referenceRequest(const CompareRequest& o) {
    RenderRequest r = o.render;
    r.integrator = o.referenceIntegrator;
    r.seconds = o.referenceSeconds > 0 ? o.referenceSeconds : kReferenceBudget * o.render.seconds;
    r.domain = StreamDomain::Reference;  // the reference streams: independent of every run
    return r;
}

RenderRequest runRequest(const CompareRequest& o, const std::string& method, int index) {
    RenderRequest r = o.render;
    r.integrator = method;
    r.seed = o.render.seed + uint64_t(index);
    return r;
}

Reference obtainReference(const CompareRequest& o, const Scene& scene) {
    if (!o.referencePath.empty()) return readGivenReference(o, scene);
    if (!o.referenceImage.rgb.empty()) return {o.referenceImage, "given image", ""};
    return renderReference(o, scene);
}

RunOutput runMethod(const CompareRequest& o, const Scene& scene, const std::string& method, int index,
                    const Image& reference) {
    const RenderRequest ro = runRequest(o, method, index);
    Run run{method, index, ro.seed, {}};
    const auto integrator = makeIntegrator(method, integratorSettings(ro));
    RenderSettings rs = renderSettings(ro, o.spelling);
    rs.team = &solo();  // a run is timed alone on its rank: compare_ranks.cpp deals the runs out
    rs.stop = o.stop;
    const std::string label = fmt::format("{} run {}/{}", method, index + 1, o.runs);
    narrate(o, rs, label);
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
    finished(o, label, r, ro);
    const Checkpoint& f = run.final();
    o.narrator.tell(*o.team, fmt::format("{}: relMSE {:.4g}, MSE {:.4g}, MAE {:.4g}, relMSE*spp {:.4g}, {} of the error in "
                                         "the worst 0.1% of pixels, HDR-FLIP {:.4g}",
                                         label, f.error.relMse, f.error.mse, f.error.mae,
                                         perSampleRelVariance(f.error.relMse, f.spp), tailShareText(f.error.tailShare),
                                         run.flip));
    std::vector<ExrChannel> channels = classChannels(r.plans, image.width, image.height);
    return {std::move(run), std::move(image), renderMetadata(ro, scene, *integrator, r, o.team->size()), std::move(channels)};
}

}  // namespace tripath::evaluation
