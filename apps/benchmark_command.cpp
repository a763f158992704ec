// `tripath benchmark`: every method on every scene at equal time, R independent runs each, against
// a cached reference per scene, with a bias test per method, in one report.
//
// Each scene is one `compare` (its page, CSVs and chart in <out>/<scene>/), run with the methods
// plus the bias reference. References are rendered when missing, by a consistent method (vcm by
// default: it also samples the specular–diffuse–specular paths that bdpt lacks) for a multiple
// of the time, in the reference streams, and cached in <out>/references/ under a name that
// carries the settings; a cached one is reused when its metadata matches. From the R runs of each
// method and of the bias reference, Welch's t-test per block (image/bias.h) says where a
// difference is bias rather than noise. <out>/index.html has the scenes × methods table,
// <out>/results.csv the same numbers. Ctrl-C finishes nothing new: the scenes done so far are
// reported.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "compare.h"
#include "core/error.h"
#include "image/bias.h"
#include "image/markup.h"
#include "image/text.h"
#include "processes.h"

namespace tripath::app {

namespace {

namespace fs = std::filesystem;

// --reference-time defaults to this many times --time.
constexpr double kReferenceBudget = 10;

struct BenchmarkCommand {
    RenderOptions render;  // size, depth, MIS, seed, threads and --time (the per-run budget)
    std::string scenes, integrators = "pt,lt,bdpt,vcm";
    std::string referenceIntegrator = "vcm", biasReference = "bdpt", baseline;
    double referenceSeconds = 0;
    int runs = 4;
    std::string outDir;
};

// One method on one scene: means over its runs.
struct Cell {
    std::string scene, method;
    MethodSummary summary{};
    double relMseWithoutTail = 0;  // mean over runs
    double speedUp = 0;            // the baseline's relMSE × seconds over this method's
    int biasedBlocks = 0, blocks = 0;
    std::string biasMap{};         // PNG, relative to the output directory
    std::array<double, kEventCount> events{};  // every counter of core/stats.h, mean per run
};

std::vector<std::string> splitList(const std::string& text, const char* what) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (item.empty()) throw InputError(fmt::format("--{} has an empty entry: '{}'", what, text));
        if (std::find(out.begin(), out.end(), item) != out.end())
            throw InputError(fmt::format("--{} names '{}' twice", what, item));
        out.push_back(item);
    }
    if (out.empty()) throw InputError(fmt::format("--{} needs at least one entry", what));
    return out;
}

// A file or folder name for a scene: a built-in's name, or a glTF file's stem.
std::string slug(const std::string& scene) {
    std::string s = fs::path(scene).stem().string();
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return s.empty() ? "scene" : s;
}

// The blocks of the bias test: 16 across the image's larger side, at least 4 pixels.
int biasBlockSize(int width, int height) { return std::max(4, (std::max(width, height) + 15) / 16); }

// The bias map as a picture: the method's image (grey) under its blocks, red where the test finds
// bias, and otherwise darker the smaller the block's p-value (black at p ≤ 1e-6).
Image biasPicture(const BiasMap& map, const Image& image) {
    Image out(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const int b = (y / map.blockSize) * map.blocksX + x / map.blockSize;
            const float* p = &image.rgb[3 * (size_t(y) * image.width + x)];
            const float lum = std::min(1.0f, 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]);
            const float shade = float(std::clamp(1 + std::log10(std::max(map.tests[b].p, 1e-6)) / 6, 0.0, 1.0));
            static constexpr std::array<float, 3> kRed{1, 0.05f, 0.05f};
            for (int c = 0; c < 3; ++c)
                out.rgb[3 * (size_t(y) * image.width + x) + c] = 0.3f * lum + 0.7f * (map.biased[b] ? kRed[c] : shade);
        }
    return out;
}

void validate(BenchmarkCommand& c, std::vector<std::string>& scenes, std::vector<std::string>& methods) {
    RenderOptions& o = c.render;
    validateRenderOptions(o);
    if (!(o.seconds > 0)) throw InputError("--time must be more than 0 seconds");
    if (c.runs < 2 || c.runs > 100)
        throw InputError(fmt::format("--runs must be between 2 and 100 (the bias test needs two runs; got {})", c.runs));
    if (c.referenceSeconds < 0) throw InputError(fmt::format("--reference-time must be above 0 (got {})", c.referenceSeconds));
    scenes = splitList(c.scenes, "scenes");
    methods = splitList(c.integrators, "integrators");
    for (const std::string& m : methods) makeIntegrator(m, {});
    makeIntegrator(c.referenceIntegrator, {});
    makeIntegrator(c.biasReference, {});
    if (c.baseline.empty()) c.baseline = methods.front();
    if (std::find(methods.begin(), methods.end(), c.baseline) == methods.end())
        throw InputError(fmt::format("--baseline '{}' is not one of --integrators", c.baseline));
    if (!isRankZero()) return;
    requireFont();
    std::error_code ec;
    fs::create_directories(fs::path(c.outDir) / "references", ec);
    if (ec) throw InputError(fmt::format("cannot create --out directory '{}': {}", c.outDir, ec.message()));
    checkWritable((fs::path(c.outDir) / "results.csv").string());
}

// The compare of one scene: methods plus the bias reference, the cached reference if it fits.
CompareOptions sceneOptions(const BenchmarkCommand& c, const std::string& scene, const std::vector<std::string>& methods) {
    CompareOptions co;
    co.render = c.render;
    co.render.scene = scene;
    co.methods = methods;
    if (std::find(methods.begin(), methods.end(), c.biasReference) == methods.end()) co.methods.push_back(c.biasReference);
    co.referenceIntegrator = c.referenceIntegrator;
    co.referenceSeconds = c.referenceSeconds > 0 ? c.referenceSeconds : kReferenceBudget * c.render.seconds;
    co.runs = c.runs;
    co.outDir = (fs::path(c.outDir) / slug(scene)).string();
    const RenderOptions& r = co.render;
    co.referenceOut = (fs::path(c.outDir) / "references" /
                       fmt::format("{}-{}x{}-{}-depth{}-rr{}-{}.exr", slug(scene), r.width, r.height,
                                   c.referenceIntegrator, r.maxDepth, r.rrDepth, r.mis)).string();
    return co;
}

// A cached reference is reused if it was rendered for these settings (else it is rendered again).
bool cachedReferenceFits(const CompareOptions& co) {
    if (!fs::exists(co.referenceOut)) return false;
    try {
        const ReferenceFile ref = readReference(co.referenceOut);
        requireSize(ref, co.render.width, co.render.height);
        Metadata settings = convergenceSettings(co.render, co.referenceIntegrator);
        settings.push_back({"tripath:streams", "reference"});
        requireSettings(ref, settings, false);
        return true;
    } catch (const InputError& e) {
        std::cerr << fmt::format("benchmark: not reusing {}: {}\n", co.referenceOut, e.what());
        return false;
    }
}

std::vector<Cell> benchmarkScene(const BenchmarkCommand& c, const std::string& scene, const std::vector<std::string>& methods,
                                 const std::atomic<bool>* stop) {
    CompareOptions co = sceneOptions(c, scene, methods);
    co.stop = stop;
    std::unique_ptr<Scene> loaded;
    bool reuse = false;
    together([&] {
        loaded = loadScene(co.render);
        if (isRankZero()) {
            fs::create_directories(co.outDir);
            reuse = cachedReferenceFits(co);
        }
    });
    std::array<uint64_t, 1> shared{reuse};
    team().max(shared);
    if (shared[0]) co.referencePath = co.referenceOut;
    if (isRankZero() && shared[0]) std::cerr << fmt::format("benchmark: reusing the reference {}\n", co.referenceOut);
    const Reference ref = shareReference(co, *loaded);
    std::vector<RunOutput> outputs = runEverywhere(co, *loaded, ref.image, true);
    if (!isRankZero() || (stop && stop->load())) return {};  // an interrupted scene is left out, not reported half-done
    writePng((fs::path(co.outDir) / "reference.png").string(), ref.image);
    KeptRuns kept = keepRuns(outputs, co.outDir);
    const std::vector<Run>& runs = kept.runs;
    std::map<std::string, Image>& images = kept.images;
    Report report{co, ref, runs, images, {}, {}, {}};
    writeReport(report, co.outDir);

    const size_t pixels = size_t(co.render.width) * co.render.height;
    std::vector<Cell> cells;
    for (const std::string& m : methods) {
        Cell cell{scene, m};
        cell.summary = *std::find_if(report.summaries.begin(), report.summaries.end(), [&](const auto& s) { return s.method == m; });
        int n = 0;
        for (const Run& run : runs) {
            if (run.method != m) continue;
            ++n;
            cell.relMseWithoutTail += relMseWithoutTail(run.final().error, pixels);
            for (int e = 0; e < kEventCount; ++e) cell.events[e] += double(run.stats.events[e]);
        }
        cell.relMseWithoutTail /= n;
        for (double& e : cell.events) e /= n;
        if (m != c.biasReference) {
            const BiasMap map = biasMap(kept.everyImage[m], kept.everyImage[c.biasReference], biasBlockSize(co.render.width, co.render.height));
            cell.biasedBlocks = map.count();
            cell.blocks = int(map.tests.size());
            cell.biasMap = (fs::path(slug(scene)) / ("bias-" + m + ".png")).string();
            writePng((fs::path(c.outDir) / cell.biasMap).string(), biasPicture(map, images[m]));
        }
        cells.push_back(cell);
    }
    const Cell& base = *std::find_if(cells.begin(), cells.end(), [&](const Cell& x) { return x.method == c.baseline; });
    for (Cell& cell : cells)
        cell.speedUp = (base.summary.error.relMse * base.summary.seconds) / (cell.summary.error.relMse * cell.summary.seconds);
    return cells;
}

constexpr const char* kFormulas =
    "relMSE: mean over pixels and channels of (x − r)² / (r² + 0.01), against the scene's reference; "
    "relMSE without tail: the same with the 0.1 % of pixels of largest relative squared error left out; "
    "HDR-FLIP: the mean of Andersson et al.'s perceptual difference map (Eurographics 2021) at one range of exposures "
    "set from the scene's reference, at 67 pixels per degree (0 none, 1 the largest); "
    "inefficiency: relMSE × seconds (lower is better); speed-up: the baseline's inefficiency over the method's; "
    "biased blocks: blocks where Welch's t-test of the runs' mean luminance against the bias reference's runs is "
    "significant at family-wise level 0.01 (Holm's correction).";

std::vector<std::string> scenesOf(const std::vector<Cell>& cells) {
    std::vector<std::string> out;
    for (const Cell& x : cells)
        if (std::find(out.begin(), out.end(), x.scene) == out.end()) out.push_back(x.scene);
    return out;
}
std::vector<std::string> methodsOf(const std::vector<Cell>& cells) {
    std::vector<std::string> out;
    for (const Cell& x : cells)
        if (std::find(out.begin(), out.end(), x.method) == out.end()) out.push_back(x.method);
    return out;
}
const Cell& cellOf(const std::vector<Cell>& cells, const std::string& scene, const std::string& method) {
    return *std::find_if(cells.begin(), cells.end(), [&](const Cell& x) { return x.scene == scene && x.method == method; });
}
double bestRelMse(const std::vector<Cell>& cells, const std::string& scene) {
    double best = INFINITY;
    for (const Cell& x : cells)
        if (x.scene == scene) best = std::min(best, x.summary.error.relMse);
    return best;
}

// results.md: the table as Markdown, for documents (docs/failures.md is one benchmark's).
std::string markdownTable(const std::vector<Cell>& cells) {
    const std::vector<std::string> methods = methodsOf(cells);
    std::string md = "| scene |";
    for (const std::string& m : methods) md += " " + m + " |";
    md += "\n|---|";
    for (size_t i = 0; i < methods.size(); ++i) md += "---|";
    md += "\n";
    for (const std::string& s : scenesOf(cells)) {
        md += "| `" + s + "` |";
        for (const std::string& m : methods) {
            const Cell& x = cellOf(cells, s, m);
            std::string cell = fmt::format("{:.3g} ({:.0f} spp, FLIP {:.2g})", x.summary.error.relMse, x.summary.spp,
                                           x.summary.flip);
            if (x.summary.error.relMse == bestRelMse(cells, s)) cell = "**" + cell + "**";
            if (x.biasedBlocks > 0) cell += fmt::format(", biased {}/{}", x.biasedBlocks, x.blocks);
            md += " " + cell + " |";
        }
        md += "\n";
    }
    return md;
}

void writeResults(const BenchmarkCommand& c, const std::vector<Cell>& cells) {
    std::string csv = std::string("# ") + kFormulas + "\n";
    csv += fmt::format("# per run: {} s, {} runs; bias reference {}; baseline {}\n", c.render.seconds, c.runs,
                       c.biasReference, c.baseline);
    csv += "# counters (rays, BSDF calls, merges, ...): what the renderer counted, mean per run\n";
    csv += "scene,integrator,relmse,relmse_sd,relmse_without_tail,mse,mae,hdr_flip,spp,seconds,inefficiency,speedup,"
           "biased_blocks,blocks,rays_per_s" + counterColumns() + "\n";
    for (const Cell& x : cells) {
        csv += fmt::format("{},{},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.1f},{:.3f},{:.6g},{:.4g},{},{},{:.4g}", x.scene,
                           x.method, x.summary.error.relMse, x.summary.relMseStd, x.relMseWithoutTail, x.summary.error.mse,
                           x.summary.error.mae, x.summary.flip, x.summary.spp, x.summary.seconds,
                           x.summary.error.relMse * x.summary.seconds, x.speedUp, x.biasedBlocks, x.blocks, x.summary.raysPerSecond);
        for (double e : x.events) csv += fmt::format(",{:.0f}", e);
        csv += "\n";
    }
    writeText((fs::path(c.outDir) / "results.csv").string(), csv);
    writeText((fs::path(c.outDir) / "results.md").string(), markdownTable(cells));

    const std::vector<std::string> scenes = scenesOf(cells), methods = methodsOf(cells);
    std::string html = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>tripath benchmark</title>\n"
                       "<style>body{font-family:\"DejaVu Sans\",Verdana,sans-serif;margin:2em;color:#222}"
                       "table{border-collapse:collapse}th,td{border:1px solid #bbb;padding:.3em .7em;text-align:right}"
                       "th:first-child,td:first-child{text-align:left}td.best{background:#ffe98a;font-weight:bold}"
                       "td small{color:#555}.maps img{width:160px;image-rendering:pixelated;margin:.2em}</style></head><body>\n";
    html += fmt::format("<h1>tripath benchmark</h1>\n<p>{} s per run, {} runs per method, {}×{} pixels; references by {}; "
                        "bias tested against {}; speed-up against {}.</p>\n",
                        c.render.seconds, c.runs, c.render.width, c.render.height, escapeMarkup(c.referenceIntegrator),
                        escapeMarkup(c.biasReference), escapeMarkup(c.baseline));
    html += "<table><tr><th>scene</th>";
    for (const std::string& m : methods) html += "<th>" + escapeMarkup(m) + "</th>";
    html += "</tr>\n";
    for (const std::string& s : scenes) {
        const double best = bestRelMse(cells, s);
        html += fmt::format("<tr><td><a href=\"{0}/index.html\">{1}</a></td>", slug(s), escapeMarkup(s));
        for (const std::string& m : methods) {
            const Cell& x = cellOf(cells, s, m);
            html += fmt::format(
                        "<td{}><a href=\"{}/index.html\">{:.4g} ± {:.2g}</a><br><small>w/o tail {:.3g} · FLIP {:.3g} · "
                        "{:.0f} spp · {:.3g} Mrays/s · ×{:.3g}{}</small></td>",
                        x.summary.error.relMse == best ? " class=\"best\"" : "", slug(s), x.summary.error.relMse,
                        x.summary.relMseStd, x.relMseWithoutTail, x.summary.flip, x.summary.spp,
                        x.summary.raysPerSecond / 1e6, x.speedUp,
                        x.blocks > 0 ? fmt::format(" · <b>{}</b>/{} biased", x.biasedBlocks, x.blocks) : std::string(""));
        }
        html += "</tr>\n";
    }
    html += "</table>\n<p>Each cell: relMSE mean ± standard deviation over runs; below it, relMSE without the worst "
            "0.1 % of pixels, HDR-FLIP, samples per pixel, rays (closest-hit and shadow) per second, speed-up against the baseline, biased blocks. Best per scene "
            "highlighted.</p>\n<p>" + std::string(kFormulas) + "</p>\n<h2>Bias maps</h2>\n"
            "<p>Red: blocks with significant bias; otherwise darker where the p-value is smaller.</p>\n";
    for (const std::string& s : scenes) {
        html += "<div class=\"maps\"><h3>" + escapeMarkup(s) + "</h3>";
        for (const Cell& x : cells)
            if (x.scene == s && !x.biasMap.empty())
                html += fmt::format("<figure style=\"display:inline-block\"><img src=\"{}\" alt=\"bias map of {}\"><figcaption>"
                                    "{}: {} of {}</figcaption></figure>",
                                    x.biasMap, escapeMarkup(x.method), escapeMarkup(x.method), x.biasedBlocks, x.blocks);
        html += "</div>\n";
    }
    html += "</body></html>\n";
    writeText((fs::path(c.outDir) / "index.html").string(), html);
}

void run(BenchmarkCommand& c) {
    std::vector<std::string> scenes, methods;
    together([&] { validate(c, scenes, methods); });
    const std::atomic<bool>* stop = installInterruptHandler();
    std::vector<Cell> cells;
    // At most: a reference per scene (unless cached), and the runs (the bias reference's too).
    const double perScene = (methods.size() + 1) * c.runs * c.render.seconds / team().size() +
                            (c.referenceSeconds > 0 ? c.referenceSeconds : kReferenceBudget * c.render.seconds);
    for (size_t i = 0; i < scenes.size(); ++i) {
        if (stop->load()) break;
        if (isRankZero())
            std::cerr << fmt::format("benchmark: scene {}/{} {}: {} methods × {} runs × {} s; at most {:.0f} s left in all\n",
                                     i + 1, scenes.size(), scenes[i], methods.size(), c.runs, c.render.seconds,
                                     perScene * double(scenes.size() - i));
        std::vector<Cell> done = benchmarkScene(c, scenes[i], methods, stop);
        if (stop->load()) break;  // an interrupted scene is left out, not reported half-done
        cells.insert(cells.end(), done.begin(), done.end());
    }
    if (!isRankZero()) return;
    if (cells.empty()) throw InputError("benchmark interrupted before its first scene was done: nothing to report");
    writeResults(c, cells);
    std::cerr << fmt::format("benchmark: {} scenes; report in {}\n", cells.size() / methods.size(),
                             (fs::path(c.outDir) / "index.html").string());
}

}  // namespace

void addBenchmarkCommand(CLI::App& app) {
    auto c = std::make_shared<BenchmarkCommand>();
    auto* cmd = app.add_subcommand(
        "benchmark",
        "Every integrator on every scene for the same time each, several independent runs, against a cached "
        "reference per scene; with a bias test per method and block. Writes <out>/index.html (scenes x methods), "
        "<out>/results.csv and a compare report per scene in <out>/<scene>/");
    addRenderOptions(*cmd, c->render, false);
    cmd->remove_option(cmd->get_option("--scene"));
    cmd->remove_option(cmd->get_option("--spp"));
    cmd->remove_option(cmd->get_option("--checkpoint"));
    cmd->get_option("--time")->required()->description("Wall-clock budget in seconds for each run of each integrator");
    cmd->add_option("--scenes", c->scenes, "Comma-separated scenes: built-in names (see `tripath scenes`) or glTF files")
        ->required();
    cmd->add_option("--integrators", c->integrators, "Comma-separated integrators to compare")->capture_default_str();
    cmd->add_option("--runs", c->runs, "Independent runs per integrator and scene (seeds seed, seed+1, ...); at least 2")
        ->capture_default_str();
    cmd->add_option("--reference-integrator", c->referenceIntegrator,
                    "Renders each scene's reference when <out>/references/ has none for these settings: a consistent "
                    "method that samples every path (vcm)")
        ->capture_default_str();
    cmd->add_option("--reference-time", c->referenceSeconds,
                    "Seconds for each reference (default: 10 x --time); references are cached and reused")
        ->capture_default_str();
    cmd->add_option("--bias-reference", c->biasReference,
                    "The unbiased method whose runs each method's runs are tested against for bias (rendered as well "
                    "if it is not one of --integrators)")
        ->capture_default_str();
    cmd->add_option("--baseline", c->baseline, "The integrator speed-ups are measured against (default: the first)");
    cmd->add_option("--out", c->outDir, "Output directory (created if missing)")->required();
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
