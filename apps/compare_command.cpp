// `tripath compare`: several integrators, the same wall-clock budget each, their error against
// a reference over time, and a report (CSV, chart, images, summary, index.html) in one directory.
#include <fmt/format.h>

#include <filesystem>
#include <iostream>

#include "commands.h"
#include "core/error.h"
#include "evaluation/compare.h"
#include "requests/interrupt.h"
#include "processes.h"
#include "render_options.h"

namespace tripath::app {

namespace fs = std::filesystem;

namespace {

struct CompareCommand {
    RenderOptions render;  // scene, size, depth, MIS, seed, threads and --time
    evaluation::CompareRequest options;
    std::string integrators = "pt,lt,bdpt";
    std::string crop;
    std::string theme = "dark";
    bool noLabels = false;
    std::string formats;
};

std::optional<Region> parseCrop(const std::string& text) {
    if (text.empty()) return std::nullopt;
    const auto parts = splitCommas(text);
    int v[4];
    bool ok = parts.size() == 4;
    for (size_t i = 0; ok && i < 4; ++i) {
        size_t used = 0;
        try {
            v[i] = std::stoi(parts[i], &used);
        } catch (const std::exception&) {
            ok = false;
        }
        ok = ok && used == parts[i].size();
    }
    if (!ok) throw InputError(fmt::format("--crop must be x,y,w,h in pixels (got '{}')", text));
    return Region{v[0], v[1], v[2], v[3]};  // checked against the image by evaluation::validate
}

// Every check that can fail before the first sample is rendered.
void validate(CompareCommand& c) {
    evaluation::CompareRequest& o = c.options;
    validateRenderOptions(c.render, false);
    o.render = c.render;
    o.methods = splitCommas(c.integrators);
    o.crop = parseCrop(c.crop);
    o.sheet = {themeNamed(c.theme), !c.noLabels};
    o.sheetFormats = c.formats.empty() ? std::vector<std::string>{} : splitCommas(c.formats);
    o.team = &team();
    o.narrator = terminalNarrator();
    evaluation::validate(o, Spelling::CommandLine);
    o.stop = installInterruptHandler();  // Ctrl-C: the render under way stops at its next pass
}

// Ctrl-C leaves the methods without their equal budgets, so there is no report; what was rendered
// to the end is kept: a reference rendered here is written with the samples it has.
std::string interruptedMessage(const evaluation::CompareRequest& o, const evaluation::Comparison& result) {
    const bool rendered = o.referencePath.empty() && !result.reference.file.empty();
    return fmt::format("compare interrupted: no report, as the methods did not all get their {} each{}",
                       evaluation::formatSeconds(o.render.seconds),
                       rendered ? fmt::format("; the reference ({}) is in {}", result.reference.description,
                                              result.reference.file)
                                : std::string());
}

void run(CompareCommand& c) {
    std::unique_ptr<Scene> scene;
    together([&] {
        validate(c);
        scene = loadScene(c.options.render);
    });
    const evaluation::CompareRequest& o = c.options;
    const evaluation::Comparison result = compare(o, *scene);
    if (result.interrupted) throw InputError(interruptedMessage(o, result));
    if (!isRankZero()) return;
    const evaluation::MethodSummary& best = result.summaries[bestMethod(result.summaries)];
    std::cerr << fmt::format("lowest error at equal time: {} (relMSE {:.4g}); report in {}\n", best.method,
                             best.error.relMse, (fs::path(o.outDir) / "index.html").string());
}

}  // namespace

void addCompareCommand(CLI::App& app) {
    auto c = std::make_shared<CompareCommand>();
    auto* cmd = app.add_subcommand(
        "compare",
        "Render a scene with several integrators for the same wall-clock time each and compare their error "
        "against a reference over time: error.csv, error-vs-time.svg/.png, side-by-side.png, each image's crop, "
        "summary.md and index.html in --out");
    addRenderOptions(*cmd, c->render, false);
    // Every method gets the same time; a sample count would not be a fair budget across methods.
    cmd->remove_option(cmd->get_option("--spp"));
    cmd->remove_option(cmd->get_option("--checkpoint"));  // runs are short and timed: nothing to resume
    cmd->get_option("--time")->required()->description("Wall-clock budget in seconds for each run of each integrator");
    cmd->add_option("--integrators", c->integrators, "Comma-separated integrators to compare (pt, lt, bdpt, vcm, bpm, ppm, mlt)")
        ->capture_default_str();
    auto* reference = cmd->add_option("--reference", c->options.referencePath,
                    "Reference EXR of the same scene and size (see `tripath reference`, whose random streams are "
                    "independent of every run's, whatever the seeds); without it, --reference-integrator renders one "
                    "for 10x --time into <out>/reference.exr. An image from `tripath render` whose seed one of the "
                    "runs would reuse is refused: it would share their samples");
    cmd->add_option("--reference-integrator", c->options.referenceIntegrator,
                    "The integrator that renders the reference when --reference is not given: vcm by default, the "
                    "method that samples every path a scene has (bdpt misses caustics seen through glass under a "
                    "point light)")
        ->capture_default_str()
        ->excludes(reference);
    inRange(cmd->add_option("--runs", c->options.runs,
                            "Independent runs per integrator (seeds seed, seed+1, ...); the chart shows their mean and "
                            "min-max band")
                ->capture_default_str(),
            evaluation::kRunsRange);
    cmd->add_option("--crop", c->crop,
                    "x,y,w,h: the region magnified under each image in side-by-side.png and written alone, magnified "
                    "(nearest neighbour) to about 512 pixels, as <method>-crop.png and reference-crop.png (default: "
                    "an eighth of the image where the methods' errors differ most)");
    cmd->add_option("--theme", c->theme, "side-by-side's colours: dark (for screens) or light (for a paper's page)")
        ->capture_default_str();
    cmd->add_flag("--no-labels", c->noLabels,
                  "side-by-side without the method names and figures above the images, for a figure captioned "
                  "elsewhere");
    cmd->add_option("--formats", c->formats,
                    "Comma-separated: side-by-side also as pdf and/or svg (labels stay text, images stay pixels); "
                    "side-by-side.png is always written");
    cmd->add_option("--out", c->options.outDir, "Output directory (created, if missing, when the first file is written)")
        ->required();
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
