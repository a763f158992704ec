// The benchmark (benchmark.h): every method on every scene at equal time, R independent runs each,
// against a cached reference per scene, with a bias test per method, in one report.
//
// Each scene is one comparison (its page, CSVs and chart in <out>/<scene>/), run with the methods
// plus the bias reference. References are given (a folder of <scene>.exr), or rendered when
// missing, by a consistent method (vcm by default: it also samples the specular–diffuse–specular
// paths that bdpt lacks) for a multiple of the time, in the reference streams, and cached in
// <out>/references/ under a name that carries the settings; a cached one is reused when its
// metadata matches. Every scene and given reference is checked before the first render. From the R runs of each
// method and of the bias reference, Welch's t-test per block (evaluation/bias.h) says where a
// difference is bias rather than noise. <out>/index.html has the scenes × methods table (a
// thumbnail per cell, the clear winner per scene marked), the bias maps and their scale,
// <out>/results.csv the same numbers. Ctrl-C finishes nothing new: the scenes done so far are
// reported.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "evaluation/benchmark.h"
#include "core/error.h"
#include "evaluation/bias.h"
#include "evaluation/markup.h"
#include "evaluation/sheet.h"
#include "image/draw.h"
#include "image/font.h"

namespace tripath::evaluation {

namespace {

namespace fs = std::filesystem;

// A file or folder name for a scene: a built-in's name, or a glTF file's stem.
std::string slug(const std::string& scene) {
    std::string s = fs::path(scene).stem().string();
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
    return s.empty() ? "scene" : s;
}

// The blocks of the bias test: 16 across the image's larger side, at least 4 pixels.
int biasBlockSize(int width, int height) { return std::max(4, (std::max(width, height) + 15) / 16); }

// The colour of a bias map's pixel over an image of luminance `lum` (clamped to 1): the image in
// grey at 30 %, under red where the block is biased, and otherwise a grey darker the smaller the
// block's p-value (black at p ≤ 1e-6).
Rgb biasColour(double p, bool biased, float lum) {
    const float shade = float(std::clamp(1 + std::log10(std::max(p, 1e-6)) / 6, 0.0, 1.0));
    const float under = 0.3f * std::min(1.0f, lum);
    return biased ? Rgb{under + 0.7f, under + 0.035f, under + 0.035f}
                  : Rgb{under + 0.7f * shade, under + 0.7f * shade, under + 0.7f * shade};
}

Image biasPicture(const BiasMap& map, const Image& image) {
    Image out(image.width, image.height);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const int b = (y / map.blockSize) * map.blocksX + x / map.blockSize;
            const float* p = image.at(x, y);
            fillRect(out, {x, y, 1, 1}, biasColour(map.tests[b].p, map.biased[b], 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2]));
        }
    return out;
}

// The scale that reads the bias maps, on the report's white page: the p-value ramp from 1e-6 to 1
// and the colour of a biased block, both as over a black pixel of the image.
Sheet biasScale() {
    return colourBar({"p-value of the block's t-test against the bias reference:",
                      [](double t) { return biasColour(std::pow(10.0, 6 * t - 6), false, 0); },
                      {"1e-6", "1e-5", "1e-4", "1e-3", "1e-2", "1e-1", "1"}, 520, 360, 30,
                      std::pair{biasColour(1, true, 0), std::string("biased")}},
                     kLightTheme);
}

// Run 0's image at the comparison's exposure, shrunk to at most kThumbnail pixels across.
constexpr int kThumbnail = 128;
void writeThumbnail(const std::string& path, const Image& image, float exposureStops) {
    writePng(path, shrink(image, std::max(1, (std::max(image.width, image.height) + kThumbnail - 1) / kThumbnail)),
             exposureStops);
}

const std::string& baselineOf(const BenchmarkRequest& r) { return r.baseline.empty() ? r.methods.front() : r.baseline; }

double referenceSeconds(const BenchmarkRequest& r) {
    return r.referenceSeconds > 0 ? r.referenceSeconds : kReferenceBudget * r.render.seconds;
}

// The comparison of one scene: methods plus the bias reference, the cached reference if it fits.
CompareRequest sceneRequest(const BenchmarkRequest& b, const std::string& scene) {
    CompareRequest co;
    co.render = b.render;
    co.render.scene = scene;
    co.methods = b.methods;
    if (std::find(b.methods.begin(), b.methods.end(), b.biasReference) == b.methods.end()) co.methods.push_back(b.biasReference);
    co.referenceIntegrator = b.referenceIntegrator;
    co.referenceSeconds = referenceSeconds(b);
    co.runs = b.runs;
    co.outDir = (fs::path(b.outDir) / slug(scene)).string();
    const RenderRequest& r = co.render;
    co.referenceOut = (fs::path(b.outDir) / "references" /
                       fmt::format("{}-{}x{}-{}-depth{}-rr{}-{}.exr", slug(scene), r.width, r.height,
                                   b.referenceIntegrator, r.maxDepth, rouletteDepth(r, b.referenceIntegrator), r.mis)).string();
    if (!b.referenceDir.empty()) co.referencePath = referenceFile(b, scene);
    co.stop = b.stop;
    co.team = b.team;
    co.narrator = b.narrator;
    co.spelling = b.spelling;
    return co;
}

// What renders: the methods, the bias reference, and the references' integrator unless they are given.
std::vector<std::string> renderingIntegrators(const BenchmarkRequest& r) {
    std::vector<std::string> all = r.methods;
    all.push_back(r.biasReference);
    if (r.referenceDir.empty()) all.push_back(r.referenceIntegrator);
    return all;
}

// Every scene loads, and every given reference fits its scene, before the first one renders: a
// mistake in the last scene of a long list costs nothing. Scenes on every rank (each loads them),
// references on rank 0 (which alone reads them).
void resolveScenes(const BenchmarkRequest& r, Spelling spelling) {
    for (const std::string& scene : r.scenes) {
        RenderRequest request = r.render;
        request.scene = scene;
        const auto loaded = loadScene(request, [](const std::string&) {});  // its warnings are told when its turn comes
        if (r.referenceDir.empty() || r.team->rank() != 0) continue;
        const CompareRequest co = sceneRequest(r, scene);
        if (!fs::is_regular_file(co.referencePath))
            throw InputError(fmt::format("{} '{}' has no reference for the scene '{}': {} is missing",
                                         parameterName("reference", spelling), r.referenceDir, scene, co.referencePath));
        readGivenReference(co, *loaded);
    }
}

// A cached reference is reused if it was rendered for these settings (else it is rendered again).
bool cachedReferenceFits(const CompareRequest& co, const Scene& scene) {
    if (!fs::exists(co.referenceOut)) return false;
    try {
        const ReferenceFile ref = readReference(co.referenceOut);
        requireSize(ref, co.render.width, co.render.height);
        Metadata settings = convergenceSettings(co.render, scene, co.referenceIntegrator);
        settings.push_back({"tripath:streams", "reference"});
        requireSettings(ref, settings, false);
        return true;
    } catch (const InputError& e) {
        co.narrator.tell(*co.team, fmt::format("benchmark: not reusing {}: {}", co.referenceOut, e.what()));
        return false;
    }
}

std::vector<Cell> benchmarkScene(const BenchmarkRequest& b, const std::string& scene) {
    CompareRequest co = sceneRequest(b, scene);
    const bool rank0 = b.team->rank() == 0;
    std::unique_ptr<Scene> loaded;
    bool reuse = false;
    together(*b.team, [&] {
        loaded = loadScene(co.render);
        if (rank0 && co.referencePath.empty()) reuse = cachedReferenceFits(co, *loaded);
    });
    std::array<uint64_t, 1> shared{reuse};
    b.team->max(shared);
    if (shared[0]) co.referencePath = co.referenceOut;
    if (shared[0]) b.narrator.tell(*b.team, fmt::format("benchmark: reusing the reference {}", co.referenceOut));
    Comparison kept = compare(co, *loaded, true);
    if (!rank0 || kept.interrupted) return {};  // an interrupted scene is left out, not reported half-done
    const std::vector<Run>& runs = kept.runs;
    std::map<std::string, Image>& images = kept.images;
    const std::vector<MethodSummary>& summaries = kept.summaries;

    const size_t pixels = size_t(co.render.width) * co.render.height;
    std::vector<Cell> cells;
    for (const std::string& m : b.methods) {
        Cell cell{scene, m};
        cell.summary = *std::find_if(summaries.begin(), summaries.end(), [&](const auto& s) { return s.method == m; });
        int n = 0;
        for (const Run& run : runs) {
            if (run.method != m) continue;
            ++n;
            cell.relMseWithoutTail += relMseWithoutTail(run.final().error, pixels);
            for (int e = 0; e < kEventCount; ++e) cell.events[e] += double(run.stats.events[e]);
        }
        cell.relMseWithoutTail /= n;
        for (double& e : cell.events) e /= n;
        if (m != b.biasReference) {
            const BiasMap map = biasMap(kept.everyImage[m], kept.everyImage[b.biasReference],
                                         biasBlockSize(co.render.width, co.render.height), b.biasLevel);
            cell.biasedBlocks = map.count();
            cell.blocks = int(map.tests.size());
            cell.biasMap = (fs::path(slug(scene)) / ("bias-" + m + ".png")).string();
            writePng((fs::path(b.outDir) / cell.biasMap).string(), biasPicture(map, images[m]));
        }
        cell.thumbnail = (fs::path(slug(scene)) / ("thumb-" + m + ".png")).string();
        writeThumbnail((fs::path(b.outDir) / cell.thumbnail).string(), images[m], kept.exposureStops);
        cells.push_back(cell);
    }
    const Cell& base = *std::find_if(cells.begin(), cells.end(), [&](const Cell& x) { return x.method == baselineOf(b); });
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
    "significant at the family-wise level below (Holm's correction).";

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
            if (x.method == clearlyBest(cells, s)) cell = "**" + cell + "**";
            if (x.biasedBlocks > 0) cell += fmt::format(", biased {}/{}", x.biasedBlocks, x.blocks);
            md += " " + cell + " |";
        }
        md += "\n";
    }
    return md;
}

void writeResults(const BenchmarkRequest& c, const std::vector<Cell>& cells) {
    std::string csv = std::string("# ") + kFormulas + "\n";
    csv += fmt::format("# per run: {} s, {} runs; bias reference {} at family-wise level {}; baseline {}\n",
                       c.render.seconds, c.runs, c.biasReference, c.biasLevel, baselineOf(c));
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
                       "td small{color:#555}td img{display:block;margin:0 auto .2em}"
                       ".maps img{width:160px;image-rendering:pixelated;margin:.2em}</style></head><body>\n";
    const std::string references = c.referenceDir.empty() ? "by " + c.referenceIntegrator : "from " + c.referenceDir;
    html += fmt::format("<h1>tripath benchmark</h1>\n<p>{} s per run, {} runs per method, {}×{} pixels; references {}; "
                        "bias tested against {} at family-wise level {}; speed-up against {}.</p>\n",
                        c.render.seconds, c.runs, c.render.width, c.render.height, escapeMarkup(references),
                        escapeMarkup(c.biasReference), c.biasLevel, escapeMarkup(baselineOf(c)));
    html += "<table><tr><th>scene</th>";
    for (const std::string& m : methods) html += "<th>" + escapeMarkup(m) + "</th>";
    html += "</tr>\n";
    for (const std::string& s : scenes) {
        const std::string best = clearlyBest(cells, s);
        html += fmt::format("<tr><td><a href=\"{0}/index.html\">{1}</a></td>", slug(s), escapeMarkup(s));
        for (const std::string& m : methods) {
            const Cell& x = cellOf(cells, s, m);
            html += fmt::format(
                        "<td{}><a href=\"{}/index.html\"><img src=\"{}\" alt=\"{} on {}\"><br>{:.4g} ± {:.2g}</a><br>"
                        "<small>w/o tail {:.3g} · FLIP {:.3g} · {:.0f} spp · {:.3g} Mrays/s · ×{:.3g}{}</small></td>",
                        x.method == best ? " class=\"best\"" : "", slug(s), x.thumbnail, escapeMarkup(m), escapeMarkup(s),
                        x.summary.error.relMse,
                        x.summary.relMseStd, x.relMseWithoutTail, x.summary.flip, x.summary.spp,
                        x.summary.raysPerSecond / 1e6, x.speedUp,
                        x.blocks > 0 ? fmt::format(" · <b>{}</b>/{} biased", x.biasedBlocks, x.blocks) : std::string(""));
        }
        html += "</tr>\n";
    }
    html += "</table>\n<p>Each cell: relMSE mean ± standard deviation over runs; below it, relMSE without the worst "
            "0.1 % of pixels, HDR-FLIP, samples per pixel, rays (closest-hit and shadow) per second, speed-up against the baseline, biased blocks. Highlighted: the "
            "method whose relMSE beats every other's on the scene beyond their error bars (mean + sd below the "
            "runner-up's mean − sd); none where the best two overlap.</p>\n<p>" + std::string(kFormulas) +
            "</p>\n<h2>Bias maps</h2>\n<p>Each method's image in grey under its blocks: red where the bias is "
            "significant, otherwise darker the smaller the block's p-value.</p>\n"
            "<img src=\"bias-scale.png\" alt=\"bias map scale\">\n";
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
    writeSheet((fs::path(c.outDir) / "bias-scale.png").string(), biasScale());
    writeText((fs::path(c.outDir) / "index.html").string(), html);
}

}  // namespace

std::string clearlyBest(const std::vector<Cell>& cells, const std::string& scene) {
    const Cell *best = nullptr, *second = nullptr;
    for (const Cell& x : cells) {
        if (x.scene != scene) continue;
        if (!best || x.summary.error.relMse < best->summary.error.relMse) {
            second = best;
            best = &x;
        } else if (!second || x.summary.error.relMse < second->summary.error.relMse) {
            second = &x;
        }
    }
    if (!second) return "";
    const bool apart = best->summary.error.relMse + best->summary.relMseStd <
                       second->summary.error.relMse - second->summary.relMseStd;
    return apart ? best->method : "";
}

std::string referenceFile(const BenchmarkRequest& r, const std::string& scene) {
    return (fs::path(r.referenceDir) / (slug(scene) + ".exr")).string();
}

void validate(const BenchmarkRequest& r, Spelling spelling) {
    auto name = [spelling](const char* flag) { return parameterName(flag, spelling); };
    validateValues(r.render, spelling);
    if (!(r.render.seconds > 0)) throw InputError(name("time") + " must be more than 0 seconds");
    if (r.runs < kBenchmarkRunsRange.min || uint64_t(r.runs) > kBenchmarkRunsRange.max)
        throw InputError(outOfRange(name("runs"), kBenchmarkRunsRange, std::to_string(r.runs)));
    if (r.referenceSeconds < 0)
        throw InputError(fmt::format("{} must be above 0 (got {})", name("reference-time"), r.referenceSeconds));
    checkList(r.scenes, "scenes", spelling);
    checkList(r.methods, "integrators", spelling, [](const std::string& m) { makeIntegrator(m, {}); });
    makeIntegrator(r.referenceIntegrator, {});
    makeIntegrator(r.biasReference, {});
    if (!(r.biasLevel > 0 && r.biasLevel < 1))
        throw InputError(fmt::format("{} must be between 0 and 1, exclusive (got {})", name("bias-level"), r.biasLevel));
    if (std::find(r.methods.begin(), r.methods.end(), baselineOf(r)) == r.methods.end())
        throw InputError(fmt::format("{} '{}' is not one of {}", name("baseline"), r.baseline, name("integrators")));
    requireUsed(r.render, renderingIntegrators(r), spelling);
    if (r.outDir.empty()) throw InputError(fmt::format("{} is needed: the report and the reference cache go there", name("out")));
    if (r.team->rank() == 0) {
        requireFont();
        checkOutDir(r.outDir, "results.csv", spelling);
    }
    resolveScenes(r, spelling);
}

std::vector<Cell> benchmark(const BenchmarkRequest& r) {
    std::vector<Cell> cells;
    // At most: a reference per scene (unless cached), and the runs (the bias reference's too).
    const double perScene = (r.methods.size() + 1) * r.runs * r.render.seconds / r.team->size() + referenceSeconds(r);
    for (size_t i = 0; i < r.scenes.size(); ++i) {
        if (r.stop && r.stop->load()) break;
        r.narrator.tell(*r.team, fmt::format("benchmark: scene {}/{} {}: {} methods × {} runs × {} s; at most {:.0f} s "
                                             "left in all",
                                             i + 1, r.scenes.size(), r.scenes[i], r.methods.size(), r.runs,
                                             r.render.seconds, perScene * double(r.scenes.size() - i)));
        std::vector<Cell> done = benchmarkScene(r, r.scenes[i]);
        if (r.stop && r.stop->load()) break;  // an interrupted scene is left out, not reported half-done
        cells.insert(cells.end(), done.begin(), done.end());
    }
    if (r.team->rank() != 0) return {};
    if (cells.empty()) throw InputError("benchmark interrupted before its first scene was done: nothing to report");
    writeResults(r, cells);
    r.narrator.tell(*r.team, fmt::format("benchmark: {} scenes; report in {}", cells.size() / r.methods.size(),
                                         (fs::path(r.outDir) / "index.html").string()));
    return cells;
}

}  // namespace tripath::evaluation
