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
    std::string referenceIntegrator = "vcm";  // renders a scene's reference when the cache has none
    double referenceSeconds = 0;              // its budget; 0: kReferenceBudget x render.seconds
    std::string biasReference = "bdpt";       // the unbiased method every method's runs are tested against
    double biasLevel = 0.01;                  // the bias test's family-wise level: the chance that an unbiased method gets any block flagged
    std::string baseline;                     // speed-ups are against it; empty: the first method
    int runs = 4;                             // at least 2, for the bias test
    std::string outDir;                       // the report, the per-scene comparisons and references/ (the cache)
    const std::atomic<bool>* stop = nullptr;  // set (Ctrl-C): the scene under way is left out, no more start
    Team* team = &solo();
    Narrator narrator;
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

// Throws InputError (one line, parameters spelled as `spelling` writes them) for anything that can
// be refused before the first sample; creates the output directory on rank 0.
void validate(const BenchmarkRequest& r, Spelling spelling);

// Runs the benchmark on every rank of the request's team; on rank 0 it writes <out>/results.csv,
// results.md and index.html and returns the cells, scene-major (nothing on the other ranks).
// Interrupted, it reports the scenes finished so far; InputError if there are none.
std::vector<Cell> benchmark(const BenchmarkRequest& r);

}  // namespace tripath::evaluation
