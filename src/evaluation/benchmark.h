// The benchmark: every method on every scene at equal time, several independent runs each, against
// a cached reference per scene, with a bias test per method and block, in one report. `tripath
// benchmark` and the Python module's benchmark() are its front ends.
#pragma once
#include <array>
#include <atomic>
#include <string>
#include <vector>

#include "evaluation/compare.h"

namespace tripath::evaluation {

struct BenchmarkRequest {
    RenderRequest render;  // size, depth, MIS, seed, threads; render.seconds: each run's budget
    std::vector<std::string> scenes;  // built-in names or glTF files
    std::vector<std::string> methods{"pt", "lt", "bdpt", "vcm"};
    // A folder holding each scene's reference as <scene>.exr (referenceFile); empty: references are
    // rendered by referenceIntegrator and cached in <outDir>/references/.
    std::string referenceDir;
    std::string referenceIntegrator = kDefaultReferenceIntegrator;  // renders a reference the cache lacks
    double referenceSeconds = 0;              // its budget; 0: kReferenceBudget x render.seconds
    std::string biasReference = "bdpt";       // the unbiased method every method's runs are tested against
    double biasLevel = 0.01;                  // the bias test's family-wise level: the chance that an unbiased method gets any block flagged
    std::string baseline;                     // speed-ups are against it; empty: the first method
    int runs = 4;                             // at least 2, for the bias test
    std::string outDir;                       // the report, the per-scene comparisons and references/ (the cache)
    const std::atomic<bool>* stop = nullptr;  // set (Ctrl-C): the scene under way is left out, no more start
    Team* team = &solo();
    Narrator narrator;
    Spelling spelling = Spelling::CommandLine;  // how messages name parameters (a refused comparison's)
};

// One method on one scene: means over its runs.
struct Cell {
    std::string scene, method;
    MethodSummary summary{};
    double relMseWithoutTail = 0;  // mean over runs
    double speedUp = 0;            // the baseline's relMSE × seconds over this method's
    int biasedBlocks = 0, blocks = 0;
    std::string biasMap{};         // PNG, relative to the output directory
    std::string thumbnail{};       // run 0's image, small, as a PNG relative to the output directory
    std::array<double, kEventCount> events{};  // every counter of core/stats.h, mean per run
};

// The method of `scene` whose mean relMSE beats every other's beyond their error bars (its mean
// plus one standard deviation over runs below the runner-up's mean minus its own); empty when
// none does, or when the scene has one method.
std::string clearlyBest(const std::vector<Cell>& cells, const std::string& scene);

// The runs of each method: at least two, for the bias test.
inline constexpr IntRange kBenchmarkRunsRange{2, 100, ", as the bias test needs two runs"};

// Throws InputError (one line, parameters spelled as `spelling` writes them) for anything that can
// be refused before the first sample: the values, the lists, every scene (each is loaded), every
// given reference (read and checked against its scene), an output directory that cannot be
// written or created. Creates nothing: each folder is made when something is written into it.
void validate(const BenchmarkRequest& r, Spelling spelling);

// The reference of `scene` in r.referenceDir: <referenceDir>/<name>.exr, the name being a
// built-in's or a glTF file's without its extension (the name of the scene's report folder too).
std::string referenceFile(const BenchmarkRequest& r, const std::string& scene);

// Runs the benchmark on every rank of the request's team; on rank 0 it writes <out>/results.csv,
// results.md and index.html and returns the cells, scene-major (nothing on the other ranks).
// Interrupted, it reports the scenes finished so far; InputError if there are none.
std::vector<Cell> benchmark(const BenchmarkRequest& r);

}  // namespace tripath::evaluation
