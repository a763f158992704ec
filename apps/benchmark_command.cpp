// `tripath benchmark`: the flags of the benchmark (evaluation/benchmark.h), which does the work:
// every method on every scene at equal time, several runs each, against a given or cached reference
// per scene, with a bias test per method, in one report. Every scene and given reference is
// checked before the first render. Ctrl-C finishes nothing new: the scenes done so far are
// reported, and the exit status says the benchmark was interrupted.
#include <fmt/format.h>

#include "commands.h"
#include "core/error.h"
#include "evaluation/benchmark.h"
#include "processes.h"
#include "render_options.h"

namespace tripath::app {

namespace {

struct BenchmarkCommand {
    RenderOptions render;  // size, depth, MIS, seed, threads and --time (the per-run budget)
    evaluation::BenchmarkRequest options;
    std::string scenes, integrators = "pt,lt,bdpt,vcm";
};

void run(BenchmarkCommand& c) {
    evaluation::BenchmarkRequest& b = c.options;
    together([&] {
        validateRenderOptions(c.render, false);
        b.render = c.render;
        b.scenes = splitCommas(c.scenes);
        b.methods = splitCommas(c.integrators);
        b.team = &team();
        b.narrator = terminalNarrator();
        evaluation::validate(b, Spelling::CommandLine);
    });
    b.stop = installInterruptHandler();
    evaluation::benchmark(b);
}

}  // namespace

void addBenchmarkCommand(CLI::App& app) {
    auto c = std::make_shared<BenchmarkCommand>();
    auto* cmd = app.add_subcommand(
        "benchmark",
        "Every integrator on every scene for the same time each, several independent runs, against a given or "
        "cached reference per scene; with a bias test per method and block. Writes <out>/index.html (scenes x methods), "
        "<out>/results.csv and a compare report per scene in <out>/<scene>/");
    addRenderOptions(*cmd, c->render, false);
    cmd->remove_option(cmd->get_option("--scene"));
    cmd->remove_option(cmd->get_option("--spp"));
    cmd->remove_option(cmd->get_option("--checkpoint"));
    cmd->get_option("--time")->required()->description("Wall-clock budget in seconds for each run of each integrator");
    cmd->add_option("--scenes", c->scenes, "Comma-separated scenes: built-in names (see `tripath scenes`) or glTF files")
        ->required();
    cmd->add_option("--integrators", c->integrators, "Comma-separated integrators to compare")->capture_default_str();
    inRange(cmd->add_option("--runs", c->options.runs,
                            "Independent runs per integrator and scene (seeds seed, seed+1, ...); at least 2")
                ->capture_default_str(),
            evaluation::kBenchmarkRunsRange);
    auto* reference = cmd->add_option(
        "--reference", c->options.referenceDir,
        "Folder of references, one per scene, named <scene>.exr: a built-in's name, or a glTF file's name without "
        "its extension (e.g. refs/cornell.exr, refs/kitchen.exr for --scenes cornell,models/kitchen.glb). Make them "
        "with `tripath reference` at the same size, depth and MIS; every scene needs one, and each is checked before "
        "the first render. Without it, references are rendered and cached in <out>/references/");
    cmd->add_option("--reference-integrator", c->options.referenceIntegrator,
                    "Renders each scene's reference when neither --reference nor <out>/references/ has one for these "
                    "settings: vcm by default, the method that samples every path a scene has")
        ->capture_default_str()
        ->excludes(reference);
    cmd->add_option("--reference-time", c->options.referenceSeconds,
                    "Seconds for each rendered reference (default: 10 x --time); they are cached and reused")
        ->capture_default_str()
        ->excludes(reference);
    cmd->add_option("--bias-reference", c->options.biasReference,
                    "The unbiased method whose runs each method's runs are tested against for bias (rendered as well "
                    "if it is not one of --integrators)")
        ->capture_default_str();
    cmd->add_option("--bias-level", c->options.biasLevel,
                    "Family-wise level of the bias test: the chance, for a method as unbiased as --bias-reference, that "
                    "any of its blocks is flagged (Holm's correction over the blocks); lower it to flag only stronger "
                    "evidence. The test assumes each run's block means roughly normal: give runs enough samples")
        ->capture_default_str();
    cmd->add_option("--baseline", c->options.baseline, "The integrator speed-ups are measured against (default: the first)");
    cmd->add_option("--out", c->options.outDir, "Output directory (created, if missing, when the first file is written)")
        ->required();
    cmd->callback([c] { run(*c); });
}

}  // namespace tripath::app
