// Is a difference between two renderers bias or noise? Welch's t-test per block of pixels over
// independent runs of each (Jung, Hanika, Dachsbacher, "Detecting Bias in Monte Carlo Renderers
// using Welch's t-test", JCGT 9(2), 2020), with Holm's correction for testing many blocks at once.
//
// Each run of a renderer is one sample of each block's mean. Welch's test asks whether two sets
// of such samples, with unequal variances, can share one mean: t = (m_a − m_b) / √(v_a/n_a + v_b/n_b)
// with the Welch–Satterthwaite degrees of freedom, and its two-sided p-value from Student's t.
// Testing every block at level α would flag α of the blocks of two unbiased renderers; Holm's
// step-down procedure keeps the chance that any block of them is flagged (the family-wise error)
// at most α, so a flagged block is evidence of bias, not a routine false alarm.
// The test assumes the run means are roughly normal: a block whose runs are dominated by rare
// fireflies needs more samples per run before its verdict means anything.
#pragma once
#include <vector>

#include "image/image.h"

namespace tripath {

struct WelchTest {
    double t = 0;
    double dof = 0;
    double p = 1;  // two-sided: the chance of a |t| at least this large if the means are equal
};

// Welch's t-test of two samples (each of at least two values). Samples without spread are a
// deterministic difference: p = 0 if their means differ, 1 if they agree.
WelchTest welchTest(const std::vector<double>& a, const std::vector<double>& b);

// P(|T| ≥ |t|) for Student's t with `dof` degrees of freedom (dof > 0, not an integer necessarily).
double studentTwoSidedP(double t, double dof);

// Holm's step-down procedure: which of the p-values are significant at family-wise level alpha.
std::vector<bool> holmSignificant(const std::vector<double>& p, double alpha);

struct BiasMap {
    int blockSize = 0, blocksX = 0, blocksY = 0;
    double alpha = 0;
    std::vector<WelchTest> tests;  // per block, row by row
    std::vector<bool> biased;      // per block: significant after Holm's correction
    int count() const;
};

// Per block of blockSize² pixels (the last row and column of blocks may be smaller), Welch's test
// of the runs' mean luminance in the block, `runs` against `referenceRuns` (at least two of each,
// all the same size), Holm-corrected at family-wise level alpha.
BiasMap biasMap(const std::vector<Image>& runs, const std::vector<Image>& referenceRuns, int blockSize, double alpha = 0.01);

}  // namespace tripath
