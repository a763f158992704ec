// The candidate plans' second moments as auto's passes measure them (pass_plan.h), kept the way
// the film keeps its sums (film.h): per tile of the image and per candidate, the current block's
// sums in double, added in the render loop's fixed order, then the exact totals of the finished
// blocks (exact_sum.h). So the totals, and every plan chosen from them, are the same for any
// thread count, any team of ranks and any grouping of blocks.
//
// The tiles are the render loop's: one thread writes a tile's camera contributions in a pass, and
// the splats come after the pass in tile order, as the film's do.
//
// Relative: each estimate's square is weighed by its pixel's weight, 1 / (I² + 0.01) with I the
// pixel's mean in a blurred image of the passes before (setWeights), as relMSE weighs a pixel's
// error; before the first weights, every pixel of a tile weighs as the tile's mean would.
//
// A variance, as relMSE is one: each camera sample's square less its squared mean. The mean's
// square is the product of the sample's estimate with its neighbour's in the same pass (the
// pixel to its left in the tile, the first column's to its right), an independent estimate of
// nearly the same mean: no image of means is needed, and the sample's noise cancels in the
// difference as it would not against a squared mean of the passes before. The product is
// weighed by the geometric mean of the two pixels' weights: where their means differ (an edge) it
// falls short of the square, never past it, and the variance errs upward, alike for every
// candidate whose camera strategies carry the pixel's mean. The splats need no such term:
// they come from light paths independent of the camera sample and of one another, so their
// squares are their variance but for a part in N_L.
//
// Beside each tile's totals, its outlier: the estimate (a camera sample, a splat) of the largest
// square under the plan the tile ran, with its square for every candidate; the choice reads each
// moment without it (PlanEvidence). A moment of a few thousand estimates can rest on one of them,
// a path that the running strategies sample once in thousands and weigh heavily; taken at its
// word it outweighs every other tile of the image, and the choice then buys the cheapest plans
// everywhere else. Without it, a heavy path counts once it is seen twice. The outlier is chosen by
// the running plan's square, not each candidate's own largest: a path the running plan samples
// well and a candidate badly is evidence against the candidate, kept. Of two estimates, the
// outlier is the same whatever order they come in, so the choice stays exact.
#pragma once
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/vec.h"
#include "integrators/exact_sum.h"
#include "integrators/film.h"
#include "integrators/plan_choice.h"

namespace tripath {

class PlanMoments {
public:
    PlanMoments(int width, int height, int tileSize, size_t candidates);

    // The candidates' factors over the constants of the passes to come (PassPlan::factors).
    void setFactors(std::vector<TechniqueSums> factors) { factors_ = std::move(factors); }
    // The candidate each tile runs in the passes to come: an estimate's outlier key is its square
    // under it.
    void setRunning(std::vector<size_t> running) { running_ = std::move(running); }
    // Each pixel's weight in the moments to come, 1 / (I_p² + 0.01) with I_p the pixel's mean as
    // relMSE weighs its error (relativeWeights), so that the moments are relative pixel by pixel.
    // The first weights turn the moments so far, measured without, relative tile by tile: each
    // tile's by `tileScales` (tileScales()). Between blocks only.
    void setWeights(std::vector<float> weights, std::span<const double> tileScales = {});
    // Per tile, 1 / (m² + 0.01) with m the mean of its pixels in `mean` (the image of the passes so
    // far): how a pixel of the tile weighs before there are weights.
    std::vector<double> tileScales(const Image& mean) const;
    // Back to no moments: a rank whose totals another took over.
    void clearTotals();
    const std::vector<float>& weights() const { return weights_; }
    // The weights from an image of the pixels' means, blurred over 3 × 3 pixels.
    static std::vector<float> relativeWeights(const Image& mean);
    // A splat to `pixel` as the film takes it (its weighted and unweighted values, already divided
    // by N_L) and its path's technique sums: for each candidate, F · U / D' to its moment, or 1 to
    // its count of paths it cannot sample (D' = 0, F · U > 0).
    void addSplat(int pixel, Spectrum weighted, Spectrum unweighted, const TechniqueSums& sums);

    // One camera sample's contributions to its own pixel, each as the candidate would weigh it,
    // X_k = U · factor_k,class / D'_k: their sum and the sum of their squares per candidate. The
    // contributions' own moments, F · U / D', are the diagonal of the square of the sample's
    // estimate; its cross terms Σ_{i≠j} X_i X_j are large where the strategies of one camera
    // subpath share its throughput (the merges with many light vertices, the path lengths of one
    // walk), which the diagonal alone does not see.
    struct Sample {
        int pixel = -1;
        std::vector<double> moment, sum, squares;  // moment: the diagonal, Σ_i F · U / D'
        int previous = -1;                         // the last pixel that ended, and its sums
        std::vector<double> previousSum;
    };
    // A contribution of `sample` (of class `sampled`) to its pixel: its moment and its count of
    // paths it cannot sample as a splat's, and its value to the sample's sums.
    void add(Sample& sample, int pixel, Spectrum weighted, Spectrum unweighted, const TechniqueSums& sums,
             TechniqueClass sampled);
    // Adds a finished sample's square, its diagonal and its cross terms (Σ_i X_k,i)² − Σ_i X_k,i²,
    // to each candidate's moment in its pixel's tile, and its product with its neighbour's estimate
    // (ended before it in the tile's row order) to the squared means; and clears it.
    void endSample(Sample& sample);
    // Adds the block's sums to the exact totals and clears them.
    void endBlock();
    // The totals and outliers of the finished blocks, as bytes: what a team gathers and adds, and a
    // checkpoint keeps; add() takes bytes of stateSize() only.
    std::string state() const;
    size_t stateSize() const { return totals_.words().size_bytes() + outliers_.size() * sizeof(double); }
    void add(std::string_view state);

    // What the choice reads, `mean` the image of the passes so far (a team's, all of them),
    // `measured` of them measuring: per tile and candidate, the moment less the squared means.
    PlanEvidence evidence(const Image& mean, int measured) const;

private:
    // Per tile and candidate: its moment, its count of paths it cannot sample, and the camera
    // samples' products with their neighbours'.
    static constexpr size_t kSums = 3;
    enum Sum : size_t { kMoment, kUncovered, kSquaredMean };
    // Adds the products of `sum` and `neighbour`'s, candidate by candidate, to the squared means of
    // `pixel`'s tile, at the geometric mean of the two pixels' weights.
    void addSquaredMean(int pixel, int neighbourPixel, const std::vector<double>& sum,
                        const std::vector<double>& neighbour);
    // A contribution's moment for each candidate (to `sample`'s if given, with its value).
    void add(Sample* sample, int pixel, Spectrum weighted, Spectrum unweighted, const TechniqueSums& sums,
             TechniqueClass sampled);
    size_t sumIndex(int tile, size_t candidate, size_t which) const {
        return (size_t(tile) * candidates_ + candidate) * kSums + which;
    }
    int tileOf(int pixel) const;
    // An estimate's squares, one per candidate, as the tile's outlier if its square under the
    // plan the tile runs (its key) is the largest yet.
    void offerOutlier(int tile, const double* squares);
    void keepOutlier(int tile, double key, const double* squares);
    double weightOf(int pixel) const { return weights_.empty() ? 1.0 : double(weights_[size_t(pixel)]); }
    int width_, height_, tileSize_, tilesX_, tiles_;
    size_t candidates_;
    std::vector<TechniqueSums> factors_;
    std::vector<double> block_;
    ExactSums totals_;
    std::vector<double> outliers_;  // per tile: the outlier's key, then its square per candidate
    std::vector<size_t> running_;   // per tile: the candidate it runs
    std::vector<double> scratch_;   // a splat's squares
    std::vector<float> weights_;    // per pixel; none: 1
};

}  // namespace tripath
