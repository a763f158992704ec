// The report files of a comparison (compare.h) other than index.html: error.csv, the error-vs-time
// chart (SVG and PNG), the side-by-side sheet and its insets alone, and summary.md.
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "evaluation/compare.h"
#include "core/error.h"
#include "evaluation/chart.h"
#include "evaluation/class_map.h"
#include "evaluation/compose.h"
#include "evaluation/error_map.h"
#include "evaluation/inset.h"

namespace tripath::evaluation {

namespace {

// Colours of the usual plotting palette, so pt/lt/bdpt look as in most papers' plots.
std::array<uint8_t, 3> colorOf(size_t i) {
    static const std::array<std::array<uint8_t, 3>, 6> palette{
        {{31, 119, 180}, {255, 127, 14}, {44, 160, 44}, {214, 39, 40}, {148, 103, 189}, {140, 86, 75}}};
    return palette[i % palette.size()];
}

const MethodSummary& summaryOf(const Report& r, const std::string& method) {
    for (const MethodSummary& s : r.summaries)
        if (s.method == method) return s;
    throw std::logic_error("no summary for " + method);
}

}  // namespace

void writeText(const std::string& path, const std::string& text) {
    writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

std::string timeToBestText(const MethodSummary& s) {
    if (!std::isfinite(s.timeToBest)) return "not reached (error levels off)";
    return s.extrapolated ? fmt::format("~{} (extrapolated)", formatSeconds(s.timeToBest)) : formatSeconds(s.timeToBest);
}

const char* const kFlipDefinition =
    "HDR-FLIP: the mean over pixels of the perceptual difference map of Andersson et al. (Eurographics 2021; 0 none, 1 "
    "the largest), at one range of exposures set from the scene's reference for every method, seen at 67 pixels per "
    "degree.";

std::string tailShareText(double share) { return fmt::format("{:.3g} %", 100 * share); }

std::string formatSeconds(double s) { return s < 10 ? fmt::format("{:.3g} s", s) : fmt::format("{:.0f} s", s); }

std::string settingsLine(const CompareRequest& o) {
    const RenderRequest& r = o.render;
    const std::string seeds = o.runs == 1 ? fmt::format("seed {}", r.seed)
                                          : fmt::format("seeds {}..{}", r.seed, r.seed + o.runs - 1);
    return fmt::format("{}x{}, max depth {}, {} MIS, {} per method and run, {} thread{}, {} run{} per method ({})",
                       r.width, r.height, r.maxDepth, r.mis, formatSeconds(r.seconds),
                       r.threads > 0 ? std::to_string(r.threads) : "all", r.threads == 1 ? "" : "s", o.runs,
                       o.runs == 1 ? "" : "s", seeds);
}

std::string counterColumns() {
    std::string s;
    for (int i = 0; i < kEventCount; ++i) s += "," + eventKey(static_cast<Event>(i));
    return s;
}

namespace {

void writeCsv(const Report& r, const std::string& path) {
    // New columns go at the end, so that scripts reading columns by position keep working.
    // hdr_flip is measured on the finished render only: its rows alone have it.
    std::string s = "integrator,run,seconds,spp,relmse,mse,mae,relmse_x_spp,tail_share,hdr_flip\n";
    for (const Run& run : r.runs)
        for (const Checkpoint& c : run.checkpoints)
            s += fmt::format("{},{},{:.6f},{},{:.8g},{:.8g},{:.8g},{:.8g},{:.8g},{}\n", run.method, run.index, c.seconds,
                             c.spp, c.error.relMse, c.error.mse, c.error.mae, perSampleRelVariance(c.error.relMse, c.spp),
                             c.error.tailShare, &c == &run.final() ? fmt::format("{:.8g}", run.flip) : "");
    writeText(path, s);
}

void writeCountersCsv(const Report& r, const std::string& path) {
    std::string s = "integrator,run,seconds,spp" + counterColumns() + "\n";
    for (const Run& run : r.runs) {
        const Checkpoint& f = run.final();
        s += fmt::format("{},{},{:.6f},{}", run.method, run.index, f.seconds, f.spp);
        for (int i = 0; i < kEventCount; ++i) s += fmt::format(",{}", run.stats.events[i]);
        s += "\n";
    }
    writeText(path, s);
}

void writeChart(const Report& r, const std::string& svgPath, const std::string& pngPath) {
    LogLogChart chart;
    chart.title = r.options.runs > 1
                      ? fmt::format("{}: relMSE against time, mean of {} runs (band: min to max)", r.options.render.scene,
                                    r.options.runs)
                      : fmt::format("{}: relMSE against time", r.options.render.scene);
    chart.xLabel = "render time (s)";
    chart.yLabel = "relMSE (lower is better)";
    for (size_t i = 0; i < r.curves.size(); ++i) {
        const Curve& c = r.curves[i];
        ChartSeries s{c.method, colorOf(i), c.seconds, c.relMse, {}, {}};
        if (r.options.runs > 1) {
            s.low = c.low;
            s.high = c.high;
        }
        chart.series.push_back(std::move(s));
    }
    writeText(svgPath, chartSvg(chart));
    writePng(pngPath, chartImage(chart));
}

// The image as a preview at `stops` shows it: scaled by 2^stops.
Image exposed(Image img, float stops) {
    const float scale = std::exp2(stops);
    for (float& v : img.rgb) v *= scale;
    return img;
}

// The reference and each method's run 0 at the comparison's exposure, as their PNGs show them; the
// error maps, in display colours already, as they are. One sheet: the PNG that index.html shows,
// and the PDF and SVG when asked for.
void writeSideBySide(const Report& r, const std::string& dir) {
    std::vector<Panel> panels{{exposed(r.reference.image, r.exposureStops), "reference", r.reference.description}};
    for (const std::string& m : r.options.methods) {
        const Run& run0 = *std::find_if(r.runs.begin(), r.runs.end(), [&](const Run& x) { return x.method == m && x.index == 0; });
        panels.push_back({exposed(r.images.at(m), r.exposureStops), m,
                          fmt::format("{} spp, {}, relMSE {:.3g}", run0.final().spp, formatSeconds(run0.final().seconds),
                                      run0.final().error.relMse)});
    }
    // Under the images, each method's error map (the same inset), and the colour bar that reads them.
    std::vector<Panel> errors;
    for (const std::string& m : r.options.methods)
        errors.push_back({errorMap(r.images.at(m), r.reference.image), m + ": error",
                          fmt::format("relMSE {:.3g} (run 0)", compareImages(r.images.at(m), r.reference.image).relMse)});
    const SheetStyle& style = r.options.sheet;
    const Sheet images = sideBySide(panels, r.inset, style);
    const Sheet sheet = stackRows({images, sideBySide(errors, r.inset, style), errorColourBar(images.width(), style.theme)},
                                  style.theme);
    for (const std::string& format : kSheetFormats)
        if (format == "png" || std::ranges::count(r.options.sheetFormats, format) > 0)
            writeSheet((std::filesystem::path(dir) / ("side-by-side." + format)).string(), sheet);
    // The inset of each image on its own, for a figure that lays them out itself.
    writePng((std::filesystem::path(dir) / "reference-crop.png").string(), magnifiedCrop(panels[0].image, r.inset));
    for (size_t i = 1; i < panels.size(); ++i)
        writePng((std::filesystem::path(dir) / (panels[i].title + "-crop.png")).string(),
                 magnifiedCrop(panels[i].image, r.inset));
}

void writeSummary(const Report& r, const std::string& path) {
    const MethodSummary& best = r.summaries[bestMethod(r.summaries)];
    const bool many = r.options.runs > 1;
    std::string s = fmt::format("# tripath compare: {}\n\n{}.\n\nReference: {} (`{}`).\n\n", r.options.render.scene,
                                settingsLine(r.options), r.reference.description, r.reference.file);
    s += fmt::format("| method | relMSE | MSE | MAE | spp | time to reach {}'s relMSE | efficiency 1/(relMSE·s) | "
                     "relMSE·spp | worst 0.1 % of pixels | HDR-FLIP | Mrays/s |\n",
                     best.method);
    s += "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const std::string& m : r.options.methods) {
        const MethodSummary& x = summaryOf(r, m);
        const std::string rel = many ? fmt::format("{:.4g} ± {:.2g}", x.error.relMse, x.relMseStd)
                                     : fmt::format("{:.4g}", x.error.relMse);
        s += fmt::format("| {} | {} | {:.4g} | {:.4g} | {:.0f} | {} | {:.4g} | {:.4g} | {} | {:.4g} | {:.4g} |\n", m, rel,
                         x.error.mse, x.error.mae, x.spp, timeToBestText(x), x.efficiency, x.relVariance,
                         tailShareText(x.error.tailShare), x.flip, x.raysPerSecond / 1e6);
    }
    s += fmt::format(
        "\nLowest error at equal time: **{}**. Errors are against the reference{}; relMSE = mean of "
        "(x − r)² / (r² + 0.01) over pixels and channels. Efficiency is higher for better methods; the ratio of two "
        "methods' efficiencies is how many times longer the worse one needs for the same error. relMSE·spp is the "
        "per-sample relative variance of an unbiased method while the reference's own error is negligible (where that "
        "error or a bias is not, it grows with spp), so efficiency = (spp/s) / (relMSE·spp): speed over per-sample noise. "
        "Mrays/s: closest-hit and shadow rays per second of render time (`counters.csv` has every counter). "
        "\"Worst 0.1 % of pixels\" is the share of the relMSE sum carried by the 0.1 % of pixels (at least one) with the "
        "largest relative squared error: near 100 %, a few fireflies make the error. {} Time spent "
        "measuring the error at the checkpoints is not counted in the render time.\n",
        best.method, many ? ", means over runs (± one standard deviation)" : "", kFlipDefinition);
    s += "\nFiles: `error.csv` (every checkpoint), `counters.csv` (per run: rays, BSDF calls, connections, splats, "
         "merges; as `tripath render --stats` counts them), `error-vs-time.svg`/`.png`, "
         "`side-by-side.png` (and `.pdf`, `.svg` when asked for), `<method>.exr`/`.png` (run 0), "
         "`<method>-crop.png` and `reference-crop.png` (the inset alone, magnified), `index.html`.\n";
    if (!r.channels.empty())
        s += "`auto.exr` also holds auto's classes per pixel (channels auto.pt, auto.connect, auto.trace, auto.merge), "
             "and `auto-classes.png` shows them: " + std::string(kClassMapLegend) + ".\n";
    writeText(path, s);
}

// The user's crop, or a window of an eighth of the image (at least 8 pixels) where the methods differ most.
Region insetRegion(const CompareRequest& o, const Reference& ref, const std::map<std::string, Image>& images) {
    if (o.crop) return *o.crop;
    std::vector<Image> list;
    for (const std::string& m : o.methods) list.push_back(images.at(m));
    const int w = std::min(ref.image.width, std::max(8, ref.image.width / 8));
    const int h = std::min(ref.image.height, std::max(8, ref.image.height / 8));
    return regionOfLargestDifference(ref.image, list, w, h);
}

}  // namespace

void writeReport(const CompareRequest& o, const Comparison& c, const std::string& dir) {
    auto path = [&](const std::string& name) { return (std::filesystem::path(dir) / name).string(); };
    const Report report{o, c.reference, c.runs, c.images, c.channels, c.curves, c.summaries,
                        insetRegion(o, c.reference, c.images), c.exposureStops};
    writeCsv(report, path("error.csv"));
    writeCountersCsv(report, path("counters.csv"));
    writeChart(report, path("error-vs-time.svg"), path("error-vs-time.png"));
    writeSideBySide(report, dir);
    for (const std::string& m : o.methods) writePng(path(m + "-error.png"), errorMap(c.images.at(m), c.reference.image));
    for (const auto& [m, channels] : c.channels)
        if (const Image map = classMap(channels, c.reference.image.width, c.reference.image.height); !map.rgb.empty())
            writePng(path(m + "-classes.png"), map);
    writeSheet(path("error-scale.png"), errorColourBar(512, o.sheet.theme));
    writeSummary(report, path("summary.md"));
    writeIndexHtml(report, path("index.html"));
}

}  // namespace tripath::evaluation
