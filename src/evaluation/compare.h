// Equal-time comparison: integrators rendered for the same wall-clock time, their error against a
// reference measured at checkpoints spaced logarithmically in time, reduced to curves and a table,
// and (given a directory) a report of it all. `tripath compare`, `tripath benchmark` and the Python
// module's compare() and benchmark() are front ends of this one implementation.
// compare.cpp checks the request and runs it all; compare_run.cpp renders the reference and each
// run; compare_ranks.cpp deals the runs out over a team of processes; compare_stats.cpp reduces
// them; compare_report.cpp and compare_html.cpp write the report.
#pragma once
#include <atomic>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/stats.h"
#include "evaluation/compose.h"
#include "evaluation/reference_file.h"
#include "image/draw.h"
#include "evaluation/metrics.h"
#include "requests/render_request.h"
#include "integrators/team.h"

namespace tripath::evaluation {

// What a comparison tells its front end while it works; each part may be left empty (silence).
// The command line prints it all on rank 0; Python passes progress to its callback.
struct Narrator {
    std::function<void(const std::string& line)> say;  // a line of information (what is rendered, each run's error)
    // A progress callback for the render `label` of width x height pixels (RenderSettings::progress), or none.
    std::function<std::function<void(int, double)>(const std::string& label, const RenderSettings&, int width, int height)>
        progress;
    // A render has ended (the command line prints its summary line and --stats report).
    std::function<void(const std::string& label, const RenderResult&, const RenderRequest&)> finished;

    // Says `line` on rank 0 of `team`, if anyone listens.
    void tell(const Team& team, const std::string& line) const {
        if (say && team.rank() == 0) say(line);
    }
};

// The integrator that renders a reference when none is given, in `compare` and `benchmark` alike:
// vcm, which samples every path a scene has (bdpt misses specular–diffuse–specular paths lit by a
// point light and seen through a pinhole, such as a caustic seen through glass).
inline constexpr const char* kDefaultReferenceIntegrator = "vcm";

// A comparison's runs are independent: at least one, and few enough to finish.
inline constexpr IntRange kRunsRange{1, 100};

struct CompareRequest {
    RenderRequest render;              // scene, size, depth, MIS, seed, threads; render.seconds: each run's budget
    std::vector<std::string> methods;  // integrator names, in the order given
    std::string referencePath;         // a reference EXR; empty: referenceImage, or one is rendered
    Image referenceImage;              // a reference in memory (Python), when referencePath is empty
    std::string referenceIntegrator = kDefaultReferenceIntegrator;  // renders one when none is given
    double referenceSeconds = 0;       // its budget; 0: kReferenceBudget x render.seconds
    std::string referenceOut;          // where a rendered one goes; empty: <outDir>/reference.exr (none without outDir)
    const std::atomic<bool>* stop = nullptr;  // set (Ctrl-C): the run under way ends at its next pass, no more start
    int runs = 1;
    std::optional<Region> crop;         // the inset; empty: where the methods differ most
    SheetStyle sheet;                   // side-by-side's colours and labels
    std::vector<std::string> sheetFormats;  // side-by-side.pdf/.svg too if listed (.png always)
    std::string outDir;                // the report's directory; empty: no files at all
    Team* team = &solo();              // the processes the runs are dealt out to
    Narrator narrator;
    Spelling spelling = Spelling::CommandLine;  // how messages name parameters (a refused render's)
};

// Without a reference, one is rendered for this many times the per-run budget. Its own noise then
// adds about 1/10 of a method's error to every measurement: fine for ranking methods.
constexpr double kReferenceBudget = 10;

// Throws InputError (one line, with the parameters spelled as `spelling` writes them) for anything
// that can be refused before the first sample: the render's values, the budget, the runs, the
// methods (unknown or listed twice), a parameter that none of the integrators rendering uses (the
// methods, and the reference's when it renders one), the crop, a missing reference file, an
// output directory that cannot be written or created. Nothing is created: the output directory
// is made once the inputs are known good (createDirectory). Only rank 0 checks files.
void validate(const CompareRequest& r, Spelling spelling);

// The names of a list parameter: none empty, each one `known` accepts (it throws InputError for a
// name it does not know), none twice, and at least one unless the list may be empty.
void checkList(const std::vector<std::string>& items, const char* flag, Spelling spelling,
               const std::function<void(const std::string&)>& known = {}, bool mayBeEmpty = false);

// Throws InputError unless `dir` is a directory in which `file` can be written, or one that can
// be made: the nearest of its ancestors that exists is a directory that takes new entries.
// Creates nothing.
void checkOutDir(const std::string& dir, const std::string& file, Spelling spelling);
// Creates `dir` and its parents if they are missing: called on rank 0 just before the first file
// is written into it, so that input refused on the way leaves no empty folder behind.
void createDirectory(const std::string& dir);

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
    double flip = 0;                      // HDR-FLIP of the finished render (evaluation/flip.h), at the reference's exposures
    const Checkpoint& final() const { return checkpoints.back(); }
};

struct Reference {
    Image image;
    std::string description;  // "bdpt, 4096 spp, 300 s"
    std::string file;         // where it is (given, or written into the output directory); empty in memory
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

// What a comparison found, on rank 0 (empty elsewhere, and `interrupted` when `stop` was set:
// then nothing was measured to the end and no report was written).
struct Comparison {
    Reference reference;
    std::vector<Run> runs;                        // run-major: run 0 of every method, then run 1, ...
    std::map<std::string, Image> images;          // run 0 of each method, finished
    std::map<std::string, std::vector<Image>> everyImage;  // every run's, by method in run order (when asked)
    // Run 0's channels beside R, G, B, by method: auto's classes per pixel (plan_report.h); none
    // for the other methods.
    std::map<std::string, std::vector<ExrChannel>> channels;
    std::vector<Curve> curves;                    // per method, in the request's order
    std::vector<MethodSummary> summaries;         // likewise
    // The exposure of every preview of the comparison (reference.png, <method>.png, the side-by-side
    // sheet): the reference's automatic one (image/exposure.h), one for all so that they compare.
    float exposureStops = 0;
    bool interrupted = false;
};

// compare.cpp: the whole comparison, by every rank of the request's team together: the reference
// (shared by all ranks), every run of every method, and on rank 0 the curves, the summaries and,
// with an output directory, the report. `everyImage`: keep each run's finished image, not only
// run 0's (the benchmark's bias test needs them).
Comparison compare(const CompareRequest& r, const Scene& scene, bool everyImage = false);

// compare_memory.cpp: what a comparison holds at its peak: the process and the scene, its largest
// render (memory_estimate.h: the reference's when it renders one, each method's), the images it
// keeps (the reference's and each method's run 0, every run's with `everyImage`) and, with an
// output directory, what the report takes as it draws the side-by-side sheet, the error maps and
// the crops. compare() refuses a comparison that exceeds its budget (memory_check.h) before the
// first render.
MemoryEstimate comparisonMemory(const CompareRequest& r, const Scene& scene, bool everyImage);

// compare_run.cpp
// The requests of a comparison's renders: its reference's (when it renders one) and a method's
// run `index` (seed + index).
RenderRequest referenceRequest(const CompareRequest& o);
RenderRequest runRequest(const CompareRequest& o, const std::string& method, int index);
Reference obtainReference(const CompareRequest& o, const Scene& scene);
// The reference at o.referencePath, checked against the request and its loaded `scene`: its size,
// scene files and depth limit (when it records them), and that it shares no samples with a run.
// InputError otherwise.
Reference readGivenReference(const CompareRequest& o, const Scene& scene);
struct RunOutput {
    Run run;
    Image image;    // the finished render
    Metadata meta;  // its settings, for its EXR
    std::vector<ExrChannel> channels;  // its EXR's channels beside R, G, B (auto's classes)
};
// Runs one method once (run `index`, seed + index), alone on this rank, and measures it against
// the reference.
RunOutput runMethod(const CompareRequest& o, const Scene& scene, const std::string& method, int index,
                    const Image& reference);

// compare_ranks.cpp: every run of every method, spread over the ranks, each alone on its rank; on
// rank 0 all of them in run-major order (images of run 0 only, unless allImages), nothing on the
// others.
std::vector<RunOutput> runEverywhere(const CompareRequest& o, const Scene& scene, const Image& reference,
                                     bool allImages = false);
// The reference on every rank: rendered by all ranks together, or read (or taken from memory) by
// rank 0, then sent by rank 0 to the others.
Reference shareReference(const CompareRequest& o, const Scene& scene);

// compare_stats.cpp
Curve curveOf(const std::vector<Run>& runs, const std::string& method);
std::vector<MethodSummary> summarize(const std::vector<Run>& runs, const std::vector<Curve>& curves);
// Index of the summary with the lowest final relMSE.
size_t bestMethod(const std::vector<MethodSummary>& summaries);

// compare_report.cpp: everything in the output directory but the EXRs and PNGs of the renders.
struct Report {
    const CompareRequest& options;
    const Reference& reference;
    const std::vector<Run>& runs;
    const std::map<std::string, Image>& images;
    const std::map<std::string, std::vector<ExrChannel>>& channels;
    const std::vector<Curve>& curves;
    const std::vector<MethodSummary>& summaries;
    Region inset;
    float exposureStops;  // Comparison::exposureStops
};
// ",closest_hit_rays,shadow_rays,…": a CSV column per event counter of core/stats.h.
std::string counterColumns();
// error.csv, counters.csv, the chart, side-by-side.png (its inset the request's crop or where the
// methods differ most), the error maps, summary.md and index.html into `dir`.
void writeReport(const CompareRequest& o, const Comparison& c, const std::string& dir);
// compare_html.cpp
void writeIndexHtml(const Report& r, const std::string& path);

// Text files are written whole or not at all, like the images (write a temporary, then rename).
void writeText(const std::string& path, const std::string& text);
// Text shared by summary.md and index.html.
std::string settingsLine(const CompareRequest& o);
std::string formatSeconds(double s);
// What the reports say HDR-FLIP is, and at which exposures and viewing it is measured.
extern const char* const kFlipDefinition;
// A tail share (ErrorMetrics::tailShare) as a percentage: "12.3 %".
std::string tailShareText(double share);
// "12 s", "~40 s (extrapolated)" or "not reached (error levels off)".
std::string timeToBestText(const MethodSummary& s);

}  // namespace tripath::evaluation
