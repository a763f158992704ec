// compare() and benchmark() in Python: the library's equal-time comparison and benchmark
// (evaluation/compare.h, benchmark.h), the same implementation `tripath compare` and `tripath
// benchmark` run, with their tables returned as plain Python data: lists of dicts with the column
// names of error.csv and results.csv, so that pandas.DataFrame takes them as they are. Both run
// without the GIL; Ctrl-C ends the render under way at its next pass and raises KeyboardInterrupt
// (a comparison cut short has no table to give).
#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <array>
#include <filesystem>

#include "core/error.h"
#include "evaluation/benchmark.h"
#include "evaluation/compare.h"
#include "module.h"

namespace tripath::python {

namespace {

using Progress = std::function<void(const std::string&, int, double)>;

// The narrator of a call: each render's progress through the watch (Ctrl-C, the callback), and
// with `verbose` the library's lines and each render's summary on sys.stderr.
evaluation::Narrator narratorOf(Watch& watch, const Progress& progress, bool verbose) {
    evaluation::Narrator n;
    n.progress = [&watch, progress](const std::string& label, const RenderSettings&, int, int) {
        return [&watch, progress, label](int passes, double seconds) {
            watch.between([&] {
                if (progress) progress(label, passes, seconds);
            });
        };
    };
    if (!verbose) return n;
    n.say = [](const std::string& line) {
        const py::gil_scoped_acquire gil;
        py::print(line, py::arg("file") = py::module_::import("sys").attr("stderr"));
    };
    n.finished = [say = n.say](const std::string& label, const RenderResult& r, const RenderRequest&) {
        say(fmt::format("{}: {} spp in {:.2f} s, {} NaN/Inf samples dropped", label, r.passes, r.seconds, r.droppedSamples));
    };
    return n;
}

// reference_seconds: None for the default (kReferenceBudget x seconds), else a budget above 0.
double referenceBudget(std::optional<double> seconds) {
    if (seconds && !(*seconds > 0)) throw InputError("reference_seconds must be above 0");
    return seconds.value_or(0);
}

// After the work: the callback's exception, or KeyboardInterrupt for Ctrl-C.
void raiseIfStopped(Watch& watch) {
    watch.raiseFailure();
    if (!watch.interrupted) return;
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
}

py::dict summaryRow(const evaluation::MethodSummary& s) {
    py::dict d;
    d["integrator"] = s.method;
    d["relmse"] = s.error.relMse;
    d["relmse_sd"] = s.relMseStd;
    d["mse"] = s.error.mse;
    d["mae"] = s.error.mae;
    d["tail_share"] = s.error.tailShare;
    d["hdr_flip"] = s.flip;
    d["spp"] = s.spp;
    d["seconds"] = s.seconds;
    d["relmse_x_spp"] = s.relVariance;
    d["efficiency"] = s.efficiency;
    d["time_to_best"] = s.timeToBest;
    d["time_to_best_extrapolated"] = s.extrapolated;
    d["rays_per_s"] = s.raysPerSecond;
    return d;
}

// The rows of error.csv: one per checkpoint of every run; hdr_flip on each run's last row alone.
py::list checkpointRows(const std::vector<evaluation::Run>& runs) {
    py::list rows;
    for (const evaluation::Run& run : runs)
        for (const evaluation::Checkpoint& c : run.checkpoints) {
            py::dict d;
            d["integrator"] = run.method;
            d["run"] = run.index;
            d["seed"] = run.seed;
            d["seconds"] = c.seconds;
            d["spp"] = c.spp;
            d["relmse"] = c.error.relMse;
            d["mse"] = c.error.mse;
            d["mae"] = c.error.mae;
            d["relmse_x_spp"] = perSampleRelVariance(c.error.relMse, c.spp);
            d["tail_share"] = c.error.tailShare;
            d["hdr_flip"] = &c == &run.final() ? py::object(py::float_(run.flip)) : py::object(py::none());
            rows.append(d);
        }
    return rows;
}

py::list runRows(const std::vector<evaluation::Run>& runs) {
    py::list rows;
    for (const evaluation::Run& run : runs) {
        py::dict d;
        d["integrator"] = run.method;
        d["run"] = run.index;
        d["seed"] = run.seed;
        d["counters"] = counters(run.stats.events);
        rows.append(d);
    }
    return rows;
}

py::dict compareScene(const py::object& sceneArgument, double seconds, const std::vector<std::string>& integrators,
                      int runs, const py::object& reference, const std::string& referenceIntegrator,
                      std::optional<double> referenceSeconds, const std::string& out, int width, int height, uint64_t seed,
                      int maxDepth, const std::string& mis, int threads, std::optional<std::array<int, 4>> crop,
                      const std::string& theme, bool labels, const std::vector<std::string>& formats,
                      const Progress& progress, bool verbose, const py::object& memoryLimit, const py::kwargs& options) {
    const SceneArgument argument(sceneArgument);
    PyScene& scene = *argument;
    evaluation::CompareRequest r;
    r.render = requestOf(scene.where(), integrators.empty() ? "bdpt" : integrators.front(), width, height,
                         seed, maxDepth, mis, threads, options);
    r.render.seconds = seconds;
    r.render.timeGiven = true;
    setMemoryLimit(r.render, memoryLimit);
    r.spelling = Spelling::Python;
    r.methods = integrators;
    r.runs = runs;
    if (py::isinstance<py::str>(reference)) r.referencePath = reference.cast<std::string>();
    else if (!reference.is_none()) r.referenceImage = fromArray(reference.cast<ArrayIn>(), "reference");
    r.referenceIntegrator = referenceIntegrator;
    r.referenceSeconds = referenceBudget(referenceSeconds);
    r.outDir = out;
    if (crop) r.crop = Region{(*crop)[0], (*crop)[1], (*crop)[2], (*crop)[3]};
    r.sheet = {themeNamed(theme), labels};
    r.sheetFormats = formats;
    Watch watch;
    r.stop = &watch.stop;
    r.narrator = narratorOf(watch, progress, verbose);
    evaluation::validate(r, Spelling::Python);

    const std::shared_ptr<const Scene> shared = scene.at(width, height);
    std::optional<evaluation::Comparison> c;
    {
        const py::gil_scoped_release released;
        c.emplace(evaluation::compare(r, *shared));
    }
    raiseIfStopped(watch);
    py::dict result;
    py::list summary;
    for (const evaluation::MethodSummary& s : c->summaries) summary.append(summaryRow(s));
    result["summary"] = summary;
    result["checkpoints"] = checkpointRows(c->runs);
    result["runs"] = runRows(c->runs);
    py::dict images;
    for (auto& [method, image] : c->images) images[py::str(method)] = toArray(std::move(image));
    result["images"] = images;
    result["reference"] = toArray(std::move(c->reference.image));
    result["reference_description"] = c->reference.description;
    result["report"] = out.empty() ? py::object(py::none())
                                   : py::object(py::str((std::filesystem::path(out) / "index.html").string()));
    return result;
}

py::list benchmarkScenes(const std::vector<std::string>& scenes, double seconds, const std::string& out,
                         const std::vector<std::string>& integrators, int runs, const std::string& referenceIntegrator,
                         std::optional<double> referenceSeconds, const std::string& biasReference,
                         double biasLevel, const std::optional<std::string>& baseline, int width, int height, uint64_t seed, int maxDepth,
                         const std::string& mis, int threads, const std::optional<std::string>& environment,
                         std::optional<float> environmentScale, const Progress& progress, bool verbose,
                         const py::object& memoryLimit, const py::kwargs& options) {
    evaluation::BenchmarkRequest b;
    RenderRequest where;
    if (environment) where.environment = *environment, where.environmentGiven = true;
    if (environmentScale) where.environmentScale = *environmentScale, where.environmentScaleGiven = true;
    b.render = requestOf(where, integrators.empty() ? "bdpt" : integrators.front(), width, height, seed, maxDepth, mis,
                         threads, options);
    b.render.seconds = seconds;
    b.render.timeGiven = true;
    setMemoryLimit(b.render, memoryLimit);
    b.spelling = Spelling::Python;
    b.scenes = scenes;
    b.methods = integrators;
    b.runs = runs;
    b.referenceIntegrator = referenceIntegrator;
    b.referenceSeconds = referenceBudget(referenceSeconds);
    b.biasReference = biasReference;
    b.biasLevel = biasLevel;
    b.baseline = baseline.value_or("");
    b.outDir = out;
    Watch watch;
    b.stop = &watch.stop;
    b.narrator = narratorOf(watch, progress, verbose);
    evaluation::validate(b, Spelling::Python);

    std::vector<evaluation::Cell> cells;
    {
        const py::gil_scoped_release released;
        cells = evaluation::benchmark(b);
    }
    raiseIfStopped(watch);
    py::list rows;
    for (const evaluation::Cell& x : cells) {
        // The method's summary over its runs (as compare() gives it), and what the benchmark adds.
        py::dict d = summaryRow(x.summary);
        d["scene"] = x.scene;
        d["relmse_without_tail"] = x.relMseWithoutTail;
        d["inefficiency"] = x.summary.error.relMse * x.summary.seconds;
        d["speedup"] = x.speedUp;
        d["biased_blocks"] = x.biasedBlocks;
        d["blocks"] = x.blocks;
        d["counters"] = counters(x.events);
        rows.append(d);
    }
    return rows;
}

}  // namespace

void defineEvaluation(py::module_& m) {
    const std::vector<std::string> compared{"pt", "lt", "bdpt"}, benchmarked{"pt", "lt", "bdpt", "vcm"};
    m.def("compare", &compareScene, py::arg("scene"), py::arg("seconds"), py::arg("integrators") = compared,
          py::arg("runs") = 1, py::arg("reference") = py::none(), py::arg("reference_integrator") = evaluation::kDefaultReferenceIntegrator,
          py::arg("reference_seconds") = py::none(), py::arg("out") = "", py::arg("width") = 512,
          py::arg("height") = 512, py::arg("seed") = 1, py::arg("max_depth") = 16, py::arg("mis") = "power",
          py::arg("threads") = 0, py::arg("crop") = py::none(), py::arg("theme") = "dark", py::arg("labels") = true,
          py::arg("formats") = std::vector<std::string>{}, py::arg("progress") = py::none(), py::arg("verbose") = false,
          py::arg("memory_limit") = py::none(),
          "Renders scene (as for render()) with each of integrators for the same wall-clock time (seconds each; "
          "runs independent runs with seeds seed, seed+1, ...) and measures their error against a reference at "
          "checkpoints spaced logarithmically in time, as `tripath compare` does. reference: an EXR path, an array "
          "(height x width x 3), or None to render one with reference_integrator for reference_seconds (default 10 "
          "x seconds) in the reference streams. out: a directory for the full report (error.csv, chart, images, "
          "index.html); none by default. crop (x, y, w, h): the region magnified in side-by-side.png and written "
          "alone as <integrator>-crop.png (default: where the errors differ most); theme ('dark' or 'light') and "
          "labels (False: no titles) style side-by-side; formats: ['pdf', 'svg'] writes it in those too. Returns a dict: summary (a row per integrator: relmse (mean over runs), "
          "relmse_sd, mse, mae, tail_share, hdr_flip, spp, seconds, relmse_x_spp, efficiency, time_to_best, "
          "rays_per_s), checkpoints (the rows of error.csv), runs (per run: counters), images (run 0's image per "
          "integrator), reference, reference_description, report (out's index.html or None). progress(label, "
          "passes, seconds) is called after each pass of each render; verbose prints what the command line prints. "
          "Ctrl-C raises KeyboardInterrupt at the next pass. A comparison whose memory estimate (its largest render, "
          "the images it keeps, the report) exceeds memory_limit raises ValueError before its first render, as "
          "for render(). Keyword options as for render().");
    m.def("benchmark", &benchmarkScenes, py::arg("scenes"), py::arg("seconds"), py::arg("out"),
          py::arg("integrators") = benchmarked, py::arg("runs") = 4, py::arg("reference_integrator") = "vcm",
          py::arg("reference_seconds") = py::none(), py::arg("bias_reference") = "bdpt",
          py::arg("bias_level") = 0.01, py::arg("baseline") = py::none(), py::arg("width") = 512, py::arg("height") = 512, py::arg("seed") = 1,
          py::arg("max_depth") = 16, py::arg("mis") = "power", py::arg("threads") = 0, py::arg("environment") = py::none(),
          py::arg("environment_scale") = py::none(), py::arg("progress") = py::none(), py::arg("verbose") = false,
          py::arg("memory_limit") = py::none(),
          "Every integrator on every scene (built-in names or glTF files, each under environment if given, as load() "
          "takes it) for seconds each, runs independent runs "
          "(at least 2), against a reference per scene cached in out/references (rendered with reference_integrator "
          "when missing), with a per-block bias test against bias_reference at family-wise level bias_level, as `tripath benchmark` does; the report "
          "goes to out. Returns the rows of results.csv as a list of dicts: scene, integrator, relmse, relmse_sd, "
          "relmse_without_tail, mse, mae, hdr_flip, spp, seconds, inefficiency, speedup (against baseline, default "
          "the first integrator), biased_blocks, blocks, rays_per_s, counters, and the rest of compare()'s summary "
          "row (tail_share, relmse_x_spp, efficiency, time_to_best). progress, verbose, Ctrl-C, memory_limit and "
          "keyword options as for compare().");
}

}  // namespace tripath::python
