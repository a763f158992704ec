// `tripath compare`: integrators rendered for the same wall-clock time, their error against a
// reference measured at checkpoints spaced logarithmically in time, and a report of it all.
// The command (compare_command.cpp) runs the renders (compare_run.cpp), reduces the runs to
// curves and a table (compare_stats.cpp) and writes the report (compare_report.cpp,
// compare_html.cpp).
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "image/draw.h"
#include "image/metrics.h"
#include "reference_file.h"
#include "render_options.h"

namespace tripath::app {

struct CompareOptions {
    RenderOptions render;              // scene, size, depth, MIS, seed, threads and --time
    std::vector<std::string> methods;  // integrator names, in the order given
    std::string referencePath;         // empty: render one
    std::string referenceIntegrator = "bdpt";  // the integrator that renders it
    double referenceSeconds = 0;       // its budget; 0: kReferenceBudget x --time (compare_run.cpp)
    std::string referenceOut;          // where a rendered one goes; empty: <outDir>/reference.exr
    const std::atomic<bool>* stop = nullptr;  // set (Ctrl-C): the run under way ends at its next pass, no more start
    int runs = 1;
    std::optional<Region> crop;
    std::string outDir;
};

// Error measurement k of a run: after the first pass that ended at or after target time
// t_k = T * 10^((k - kTargets) / kPerDecade), k = 0..kTargets; the last one (k = kTargets, t = T)
// is the finished render. Targets are shared by all runs so that runs can be averaged point by point.
constexpr int kPerDecade = 4, kTargets = 16;

struct Checkpoint {
    int target;
    double seconds;
    int spp;
    ErrorMetrics error;
};

struct Run {
    std::string method;
    int index;  // 0..runs-1
    uint64_t seed;
    std::vector<Checkpoint> checkpoints;  // the last one is the finished render
    StatsSnapshot stats{};                // what the finished render did (rays, BSDF calls, …)
    double flip = 0;                      // HDR-FLIP of the finished render (image/flip.h), at the reference's exposures
    const Checkpoint& final() const { return checkpoints.back(); }
};

struct Reference {
    Image image;
    std::string description;  // "bdpt, 4096 spp, 300 s"
    std::string file;         // where it is (given, or written into the output directory)
};

// One method's runs, averaged at each target time that every run reached.
struct Curve {
    std::string method;
    std::vector<double> seconds, spp, relMse, low, high;  // low/high: min and max over runs
};

struct MethodSummary {
    std::string method;
    ErrorMetrics error;       // finished renders, mean over runs
    double relMseStd = 0;     // standard deviation over runs (0 for one run)
    double spp = 0, seconds = 0;
    double timeToBest = 0;    // time to reach the best method's final relMSE
    bool extrapolated = false;  // never reached: extrapolated assuming relMSE ∝ 1/time
    double efficiency = 0;    // 1 / (relMSE * seconds)
    double relVariance = 0;   // per-sample relative variance relMSE * spp, mean over runs of each run's product
    double raysPerSecond = 0; // closest-hit and shadow rays per second of render time, mean over runs
    double flip = 0;          // HDR-FLIP of the finished renders, mean over runs
};

// compare_run.cpp
Reference obtainReference(const CompareOptions& o, const Scene& scene);
struct RunOutput {
    Run run;
    Image image;    // the finished render
    Metadata meta;  // its settings, for its EXR
};
// Runs one method once (run `index`, seed + index) and measures it against the reference.
RunOutput runMethod(const CompareOptions& o, const Scene& scene, const std::string& method, int index,
                    const Image& reference);
// Every run of every method, spread over the ranks (compare_ranks.cpp), each alone on its rank;
// on rank 0 all of them in run-major order (images of run 0 only, unless allImages), nothing on
// the others.
std::vector<RunOutput> runEverywhere(const CompareOptions& o, const Scene& scene, const Image& reference,
                                     bool allImages = false);
// The reference on every rank: rendered by all ranks together, or read by rank 0 (--reference),
// then sent by rank 0 to the others.
Reference shareReference(const CompareOptions& o, const Scene& scene);
std::string packReference(const Reference& ref);
Reference unpackReference(const std::string& bytes);
// Rank 0, after runEverywhere: the runs, and run 0's image of each method (also written to
// <dir>/<method>.exr and .png); every image the outputs carry, by method, in run order.
struct KeptRuns {
    std::vector<Run> runs;
    std::map<std::string, Image> images;
    std::map<std::string, std::vector<Image>> everyImage;
};
KeptRuns keepRuns(std::vector<RunOutput>& outputs, const std::string& dir);

// compare_stats.cpp
Curve curveOf(const std::vector<Run>& runs, const std::string& method);
std::vector<MethodSummary> summarize(const std::vector<Run>& runs, const std::vector<Curve>& curves);
// Index of the summary with the lowest final relMSE.
size_t bestMethod(const std::vector<MethodSummary>& summaries);

// compare_report.cpp: everything in the output directory but the EXRs and PNGs of the renders.
struct Report {
    const CompareOptions& options;
    const Reference& reference;
    const std::vector<Run>& runs;
    const std::map<std::string, Image>& images;  // run 0 of each method, finished
    std::vector<Curve> curves;
    std::vector<MethodSummary> summaries;
    Region inset;
};
void writeCsv(const Report& r, const std::string& path);
// ",closest_hit_rays,shadow_rays,…": a CSV column per event counter of core/stats.h.
std::string counterColumns();
// counters.csv: one row per run, every event counter of core/stats.h in total.
void writeCountersCsv(const Report& r, const std::string& path);
void writeChart(const Report& r, const std::string& svgPath, const std::string& pngPath);
void writeSideBySide(const Report& r, const std::string& path);
void writeSummary(const Report& r, const std::string& path);
// compare_html.cpp
void writeIndexHtml(const Report& r, const std::string& path);
// Everything above into `dir`: curves and summaries first, then error.csv, counters.csv, the
// chart, side-by-side.png (its inset the user's crop or where the methods differ most),
// summary.md and index.html.
void writeReport(Report& report, const std::string& dir);

// Text files are written whole or not at all, like the images (write a temporary, then rename).
void writeText(const std::string& path, const std::string& text);
// Text shared by summary.md and index.html.
std::string settingsLine(const CompareOptions& o);
std::string formatSeconds(double s);
// What the reports say HDR-FLIP is, and at which exposures and viewing it is measured.
extern const char* const kFlipDefinition;
// A tail share (ErrorMetrics::tailShare) as a percentage: "12.3 %".
std::string tailShareText(double share);
// "12 s", "~40 s (extrapolated)" or "not reached (error levels off)".
std::string timeToBestText(const MethodSummary& s);

}  // namespace tripath::app
