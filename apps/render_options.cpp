#include "render_options.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <charconv>
#include <iostream>
#include <sstream>

#include "core/error.h"
#include "geometry/embree_isa.h"
#include "processes.h"
#include "requests/integrator_parameters.h"
#include "requests/memory_check.h"
#include "stats_report.h"

namespace tripath::app {

void addSceneOptions(CLI::App& cmd, std::string& scene, GltfOptions& gltf) {
    cmd.add_option("--scene", scene, "Built-in scene name (see `tripath scenes`) or a .gltf/.glb file")->required();
    cmd.add_flag("--allow-external-files", gltf.allowExternalFiles,
                 "Let a glTF file's buffer and image URIs name files outside its folder (absolute paths, '..', "
                 "symlinks leading out); by default only regular files in the folder and its subfolders are read");
}

CLI::Option* inRange(CLI::Option* option, const IntRange& range) {
    auto check = [option, range](std::string& text) {
        const char *begin = text.data(), *end = begin + text.size();
        bool ok = false;
        if (text.starts_with('-')) {
            int64_t v = 0;
            const auto [stop, ec] = std::from_chars(begin, end, v);
            ok = ec == std::errc{} && stop == end && v >= range.min;
        } else {
            uint64_t v = 0;
            const auto [stop, ec] = std::from_chars(begin, end, v);
            ok = ec == std::errc{} && stop == end && v <= range.max && (range.min <= 0 || v >= uint64_t(range.min));
        }
        // Thrown rather than returned: CLI11 would put "--flag: " before the message, which then
        // reads unlike validate()'s for a value that converts.
        if (!ok) throw InputError(outOfRange(option->get_name(), range, clipped(text)));
        return std::string();
    };
    return option->check(CLI::Validator(check, fmt::format("INT in [{}, {}]", range.min, range.max)));
}

CLI::Option* documented(CLI::Option* option, const RenderRequest& defaults) {
    const IntegratorParameter& p = integratorParameter(option->get_name().substr(2));
    return option->description(describe(p))->default_str(p.shownDefault(defaults));
}

std::vector<std::string> splitCommas(const std::string& text) {
    std::vector<std::string> items;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        const auto b = item.find_first_not_of(" \t"), e = item.find_last_not_of(" \t");
        items.push_back(b == std::string::npos ? "" : item.substr(b, e - b + 1));
    }
    if (!text.empty() && text.back() == ',') items.push_back("");
    return items;
}

void addRenderOptions(CLI::App& cmd, RenderOptions& o, bool withIntegrator) {
    addSceneOptions(cmd, o.scene, o.gltf);
    cmd.add_option_function<std::string>(
        "--environment", [&o](const std::string& v) { o.environment = v, o.environmentGiven = true; },
        "Light the scene from infinitely far away: an equirectangular map OpenImageIO reads (.exr, .hdr, ...; linear "
        "radiance in the output's units) or a constant radiance R,G,B. A direction d = (x,y,z) toward the sky (glTF "
        "world space, +Y up) reads column u = 0.5 + atan2(x,-z)/(2 pi) and row v = acos(y)/pi, row 0 at the top; "
        "u = 0.5 is -Z, where an unrotated glTF camera looks. Rays that leave the scene see it; every integrator "
        "samples it");
    cmd.add_option_function<float>(
        "--environment-scale", [&o](float v) { o.environmentScale = v, o.environmentScaleGiven = true; },
        "Multiplies the environment's radiance (default 1)");
    if (withIntegrator)
        cmd.add_option("--integrator", o.integrator,
                       "pt: path tracing with next-event estimation; lt: light tracing; bdpt: bidirectional "
                       "path tracing with MIS over every (s,t); vcm: vertex connection and merging (bdpt plus "
                       "photon merges at every non-delta camera vertex, one MIS); bpm: bidirectional photon "
                       "mapping (merges only); ppm: progressive photon mapping (one merge where the camera path "
                       "first meets a non-delta surface); mlt: multiplexed Metropolis light transport (Markov chains "
                       "over bdpt's paths and connections, for light that independent samples rarely find); auto: "
                       "vcm's strategies, choosing while it renders the light paths per pass and, per 16x16 tile, "
                       "which classes of them pay (efficiency-aware MIS; what it chose is in the EXR and --stats): "
                       "pick it when you do not know which method wins")
            ->capture_default_str();
    // Functions rather than plain bindings: a given value is checked, whatever it is (even 0 or -1).
    auto* spp = cmd.add_option_function<int>(
        "--spp", [&o](int v) { o.spp = v, o.sppGiven = true; },
        "Samples per pixel, one per pass (mlt: steps of its chains per pixel); default 16 when --time is not given");
    inRange(spp, kSppRange);
    auto* time = cmd.add_option_function<double>(
        "--time", [&o](double v) { o.seconds = v, o.timeGiven = true; },
        "Wall-clock budget in seconds: render whole passes until it is spent (at least one)");
    spp->excludes(time);
    inRange(cmd.add_option("--width", o.width, "Image width in pixels")->capture_default_str(), kSizeRange);
    inRange(cmd.add_option("--height", o.height, "Image height in pixels")->capture_default_str(), kSizeRange);
    inRange(cmd.add_option("--max-depth", o.maxDepth,
                           "Longest path kept, in segments k: 1 = emitters seen directly, 2 = direct lighting, ...")
                ->capture_default_str(),
            kMaxDepthRange);
    inRange(documented(cmd.add_option("--rr-depth", o.rrDepth), o), kRrDepthRange);
    cmd.add_option("--mis", o.mis, "MIS heuristic: balance, power (beta = 2) or none (uniform weights)")
        ->capture_default_str();
    documented(cmd.add_option_function<std::string>(
        "--sampler", [&o](const std::string& v) { o.sampler = v, o.samplerGiven = true; }), o);
    // The integrators' own parameters, documented in integrator_parameters.cpp.
    auto* radius = documented(cmd.add_option_function<float>(
        "--radius", [&o](float v) { o.merge.radius = v, o.radiusGiven = true; }), o);
    auto* factor = documented(cmd.add_option_function<float>(
        "--radius-factor", [&o](float v) { o.merge.radiusFactor = v, o.radiusFactorGiven = true; }), o);
    documented(cmd.add_option_function<float>(
                  "--radius-pixels", [&o](float v) { o.merge.radiusPixels = v, o.radiusPixelsGiven = true; }), o)
        ->excludes(radius)
        ->excludes(factor);
    radius->excludes(factor);
    documented(cmd.add_option_function<float>(
        "--alpha", [&o](float v) { o.merge.alpha = v, o.alphaGiven = true; }), o);
    inRange(documented(cmd.add_option_function<int64_t>(
                "--light-paths", [&o](int64_t v) { o.lightPaths = v, o.lightPathsGiven = true; }), o),
            kLightPathsRange);
    inRange(documented(cmd.add_option_function<int64_t>(
                "--bootstrap", [&o](int64_t v) { o.metropolis.bootstrap = v, o.bootstrapGiven = true; }), o),
            kBootstrapRange);
    inRange(documented(cmd.add_option_function<int>(
                "--chains", [&o](int v) { o.metropolis.chains = v, o.chainsGiven = true; }), o),
            kChainsRange);
    documented(cmd.add_option_function<float>(
        "--large-step", [&o](float v) { o.metropolis.largeStep = v, o.largeStepGiven = true; }), o);
    inRange(cmd.add_option("--seed", o.seed, "Seed: the same seed and sample count give the same image on any thread count")
                ->capture_default_str(),
            kSeedRange);
    inRange(cmd.add_option("--threads", o.threads,
                           "Worker threads per process (0: all cores; under mpirun give each rank its share)")
                ->capture_default_str(),
            kThreadsRange);
    cmd.add_option("--embree-isa", o.embreeIsa,
                   "Embree's instruction set for the ray queries: sse2, sse4.2, avx, avx2 or avx512. Each builds "
                   "its own BVH, so the same seed gives another (statistically equal) image, and the EXR records "
                   "it (tripath:embree): pin the one an image was made with to continue or repeat it. Default: "
                   "the widest this CPU runs (under mpirun, the narrowest of the ranks' widest)");
    cmd.add_option("--checkpoint", o.checkpointSeconds,
                   "Every this many seconds (at the next round of passes), write the image so far to --out and the "
                   "state to go on from to <out>.checkpoint, atomically; a render or reference started again with "
                   "the same settings and --out continues from it (a --spp render then ends bit-identical to an "
                   "uninterrupted one). Also written when the render is interrupted; 0: none")
        ->capture_default_str();
    cmd.add_option_function<std::string>(
        "--memory-limit",
        [&o](const std::string& v) { o.memoryLimit = parseMemoryLimit(v, Spelling::CommandLine), o.memoryLimitGiven = true; },
        "The memory a render may take, e.g. 8G or 512M (K, M, G, T: powers of 1024). Before it allocates its film "
        "and light paths, a render whose memory estimate (film, light paths, splats, scene; docs/memory.md) exceeds "
        "this is refused, naming what to lower. Default: what the machine can give the process (MemAvailable, or "
        "a cgroup's limit less its use). Give more than the machine has to render anyway (swap)")
        ->type_name("SIZE");
    cmd.add_flag("--stats", o.stats,
                 "At the end, print what the render did (rays, BSDF calls, connections, splats, merges: in total, per "
                 "camera sample and per second) and where its CPU time went among the render loop's phases (the light "
                 "phase's light paths and merge index, the tiles of camera samples, the film); the phase sampling "
                 "runs only with this flag");
}

void validateRenderOptions(const RenderOptions& o, bool withIntegrator) {
    if (withIntegrator)
        validate(o, Spelling::CommandLine);
    else
        validateValues(o, Spelling::CommandLine);
    if (!(o.checkpointSeconds >= 0 && o.checkpointSeconds <= 1e7))
        throw InputError(fmt::format("--checkpoint must be a number of seconds, at least 0 and at most 1e7 (got {})",
                                     o.checkpointSeconds));
    if (o.embreeIsa.empty()) return;
    const int level = embreeIsaNamed(o.embreeIsa);
    if (level < 0)
        throw InputError(fmt::format("--embree-isa must be one of {} (got '{}')", fmt::join(kEmbreeIsas, ", "), o.embreeIsa));
    if (level > bestEmbreeIsaLevel())
        throw InputError(fmt::format("--embree-isa {}: this CPU does not run it (the widest it runs is {})", o.embreeIsa,
                                     kEmbreeIsas[bestEmbreeIsaLevel()]));
    useEmbreeIsa(level);  // under mpirun every rank gets the same flag: they agree, or one of them fails here
}

std::function<void(int, double)> progressReporter(const RenderSettings& s, int width, int height,
                                                  const std::string& label) {
    if (!isatty(STDERR_FILENO) || !isRankZero()) return {};
    const double pixels = double(width) * height;
    return [s, pixels, label](int passes, double seconds) {
        const double fraction = s.seconds > 0 ? std::min(1.0, seconds / s.seconds) : double(passes) / s.spp;
        const double left = fraction > 0 ? seconds * (1 - fraction) / fraction : 0;
        const int bar = static_cast<int>(fraction * 30);
        std::cerr << fmt::format("\r{} [{:<30}] {:3.0f}%  {} spp  {:.2f} Msamples/s  {:.0f} s left ", label,
                                 std::string(bar, '#'), 100 * fraction, passes, passes * pixels / seconds / 1e6, left)
                  << std::flush;
    };
}

void printSummary(const std::string& label, const RenderResult& r, const RenderRequest& o) {
    const int width = o.width, height = o.height;
    if (isatty(STDERR_FILENO)) std::cerr << "\n";
    if (r.interruptedBeforeAnyPass) {
        std::cerr << label << ": interrupted in mlt's bootstrap, before its first pass: no image\n";
        return;
    }
    const std::string done = r.interrupted ? "interrupted " + interruptionText(r)
                                           : fmt::format("{} spp in {:.2f} s", r.passes, r.seconds);
    std::cerr << fmt::format("{}: {} ({:.2f} Msamples/s), {} NaN/Inf samples dropped, {} MIS weights guarded to 0\n", label,
                             done, r.passes * double(width) * height / r.seconds / 1e6, r.droppedSamples, r.guardedWeights);
    if (!r.droppedLog.empty()) {
        std::string where;
        for (const DroppedSample& d : r.droppedLog) where += fmt::format(" {},{}", d.pass, d.pixel);
        std::cerr << fmt::format("NaN/Inf samples (PASS,PIXEL; the first {}):{}; add --replay PASS,PIXEL to the same "
                                 "command to see one's contributions\n",
                                 r.droppedLog.size(), where);
    }
    if (launched())
        std::cerr << fmt::format("{} ranks; their films were added into rank 0's in {:.3f} s\n", team().size(), r.reduceSeconds);
    if (o.stats) std::cerr << statsReport(r, uint64_t(width) * height);
}

evaluation::Narrator terminalNarrator() {
    evaluation::Narrator n;
    n.say = [](const std::string& line) { std::cerr << line << "\n"; };
    n.progress = [](const std::string& label, const RenderSettings& s, int width, int height) {
        return progressReporter(s, width, height, label);
    };
    n.finished = printSummary;
    return n;
}

}  // namespace tripath::app
