// LDR-FLIP and HDR-FLIP (evaluation/flip.h). The expected values are worked out by hand from the
// papers' formulas in the comments, or are properties the papers state (zero for identical
// images, the normalisation's maximum, the maximum over exposures); each test names the mistake
// in the code it is there to catch. Images are small, so the file runs in well under a second.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/error.h"
#include "evaluation/flip.h"
#include "image/image.h"

using namespace tripath;

namespace {

Image uniform(int w, int h, float r, float g, float b) {
    Image img(w, h);
    for (std::size_t p = 0; p < img.pixelCount(); ++p) {
        img.rgb[3 * p] = r;
        img.rgb[3 * p + 1] = g;
        img.rgb[3 * p + 2] = b;
    }
    return img;
}

void setPixel(Image& img, int x, int y, float r, float g, float b) {
    float* p = img.at(x, y);
    p[0] = r;
    p[1] = g;
    p[2] = b;
}

// Grey black for columns below `step`, white from it on.
Image stepEdge(int w, int h, int step) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = step; x < w; ++x) setPixel(img, x, y, 1, 1, 1);
    return img;
}

// A smooth HDR image spanning about 6 stops, with colour.
Image hdrGradient(int w, int h) {
    Image img(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = std::exp2(6.0f * float(x) / float(w) - 3.0f);
            setPixel(img, x, y, v, v * (0.5f + 0.5f * float(y) / float(h)), 0.7f * v);
        }
    return img;
}

float at(const std::vector<float>& map, int w, int x, int y) { return map[std::size_t(y) * std::size_t(w) + std::size_t(x)]; }

// The worked numbers below use, as the papers do: sRGB → XYZ with the D65 white of RGB (1, 1, 1);
// CIELAB f(t) = t^(1/3) above (6/29)³; Hunt adjustment (L, 0.01 L a, 0.01 L b); HyAB distance
// |ΔL| + √(Δa² + Δb²); q_c = 0.7, p_c = 0.4, p_t = 0.95.
// cmax: green Lab (87.736, −86.182, 83.187) → Hunt (87.736, −75.612, 72.984); blue Lab (32.301,
// 79.195, −107.855) → Hunt (32.301, 25.581, −34.838); HyAB = 55.435 + √(101.193² + 107.822²)
// = 203.305, cmax = 203.305^0.7 = 41.277, knee p_c cmax = 16.511.
constexpr float kHandTolerance = 1e-3f;

}  // namespace

// Catches: any term that is nonzero without a difference (a bias in the filters' borders, an
// epsilon in HyAB), and exposures of the test image leaking into the reference's tone mapping.
TEST(FlipTest, IdenticalImagesHaveZeroError) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0, 4);
    Image img(24, 20);
    for (float& v : img.rgb) v = u(rng);
    for (float e : hdrFlipMap(img, img, flipExposures(img))) EXPECT_EQ(e, 0.0f);
    for (float& v : img.rgb) v /= 4;
    for (float e : ldrFlipMap(img, img)) EXPECT_EQ(e, 0.0f);
}

// Uniform images: every filter preserves a constant and the feature responses vanish, so LDR-FLIP
// is the colour term of the two colours. Catches wrong q_c, p_c, p_t, a missing Hunt adjustment
// (cmax would be 308.1^0.7 = 55.1 and black-white 0.955), cmax from other primaries, a missing
// sRGB decoding, and the two branches of the compression swapped.
TEST(FlipTest, UniformColoursMatchHandComputation) {
    const Image black = uniform(16, 16, 0, 0, 0);
    // White: L = 100, a = b = 0; HyAB = 100, 100^0.7 = 25.119 ≥ knee:
    // ΔE_c = 0.95 + (25.119 − 16.511) / (41.277 − 16.511) × 0.05 = 0.96738.
    for (float e : ldrFlipMap(uniform(16, 16, 1, 1, 1), black)) EXPECT_NEAR(e, 0.96738f, kHandTolerance);
    // sRGB grey 0.25: linear ((0.25 + 0.055) / 1.055)^2.4 = 0.050876, L = 116 × 0.050876^(1/3) − 16
    // = 26.983; 26.983^0.7 = 10.041 < knee: ΔE_c = 0.95 × 10.041 / 16.511 = 0.57773.
    for (float e : ldrFlipMap(uniform(16, 16, 0.25f, 0.25f, 0.25f), black)) EXPECT_NEAR(e, 0.57773f, kHandTolerance);
    // Red: Lab (53.237, 80.090, 67.203) → Hunt (53.237, 42.638, 35.777); HyAB to black
    // = 53.237 + √(42.638² + 35.777²) = 108.897, ^0.7 = 26.663:
    // ΔE_c = 0.95 + (26.663 − 16.511) / 24.766 × 0.05 = 0.97050.
    for (float e : ldrFlipMap(uniform(16, 16, 1, 0, 0), black)) EXPECT_NEAR(e, 0.97050f, kHandTolerance);
}

// [1] normalises by the green-blue distance, so that pair is the top of the scale. Catches a
// normalisation by another pair, or an upper branch of the compression that does not reach 1.
TEST(FlipTest, GreenAgainstBlueIsTheLargestError) {
    for (float e : ldrFlipMap(uniform(8, 8, 0, 1, 0), uniform(8, 8, 0, 0, 1))) EXPECT_NEAR(e, 1.0f, 1e-5f);
}

// Both terms of [1] compare the images through symmetric differences. Catches features taken
// from one image only, or a signed difference.
TEST(FlipTest, LdrFlipIsSymmetric) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    Image a(20, 16), b(20, 16);
    for (float& v : a.rgb) v = u(rng);
    for (float& v : b.rgb) v = u(rng);
    const auto ab = ldrFlipMap(a, b), ba = ldrFlipMap(b, a);
    for (std::size_t i = 0; i < ab.size(); ++i) EXPECT_NEAR(ab[i], ba[i], 1e-6f);
}

// Contrast filtering blurs the chroma channels more than the achromatic one, so yellow crossed by
// thin black lines comes out darker than yellow yet nearly as chromatic: a colour outside the RGB
// cube, which [1] clips before CIELAB. Unclipped, its distance to black exceeds the green-blue
// maximum and the error leaves [0, 1] (1.022 here). Catches a missing clip, and a compression that
// is not bounded.
TEST(FlipTest, ErrorsStayInUnitRangeWhereFilteringLeavesTheGamut) {
    const int w = 32;
    Image lines = uniform(w, 8, 1, 1, 0);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < w; x += 4) setPixel(lines, x, y, 0, 0, 0);
    std::mt19937 rng(11);
    std::bernoulli_distribution coin(0.5);
    Image noise(w, 8);
    for (float& v : noise.rgb) v = coin(rng) ? 1.0f : 0.0f;
    for (const Image* img : {&lines, &noise})
        for (float e : ldrFlipMap(*img, uniform(w, 8, 0, 0, 0))) {
            EXPECT_GE(e, 0.0f);
            EXPECT_LE(e, 1.0f);
        }
}

// A black-to-white step in the reference, none in the test. The edge detector's taps on either
// side of the centre sum to ∓1, so at the two columns touching the step the edge response is
// exactly 1 (the point response there is 0.149): ΔE_f = (1/√2)^0.5 = 2^(−1/4) = 0.84090.
// Nine columns into the white (σ = 0.5 × 0.082 × 67.02 = 2.7478 px, radius ⌈3σ⌉ = 9), only the
// kernels' last tap reaches the black. The point kernel's (x²/σ² − 1) e^(−x²/2σ²) is 0.045556 there
// against a positive sum of 3.2997, so its response is 0.013806 (the edge's, 0.005659, is smaller):
// ΔE_f = (0.013806/√2)^0.5 = 0.09881. One column further, no tap reaches: ΔE_f ≈ 0.
// Catches wrong q_f or 1/√2, derivative kernels not normalised per sign, a wrong w or 3σ radius.
TEST(FlipTest, FeatureTermOfAStepMatchesHandComputation) {
    const int w = 40;
    const FlipTerms terms = ldrFlipTerms(uniform(w, 8, 0, 0, 0), stepEdge(w, 8, 16));
    for (int y = 0; y < 8; ++y) {
        EXPECT_NEAR(at(terms.feature, w, 15, y), 0.84090f, kHandTolerance);
        EXPECT_NEAR(at(terms.feature, w, 16, y), 0.84090f, kHandTolerance);
        EXPECT_NEAR(at(terms.feature, w, 24, y), 0.09881f, kHandTolerance);
        EXPECT_LT(at(terms.feature, w, 25, y), 1e-3f);
    }
}

// The same step, shifted by one column in the test (black up to column 16, not 15). The colour
// term next to the moved edge is what a blurred colour difference gives; the edge's move must raise
// the error above it there, ΔE_c^(1 − ΔE_f) > ΔE_c. At column 15 (17 by symmetry) the reference
// is one column from its step and the test two; from the step's responses above, edge 1 vs
// 0.87435 and point 0.14945 vs 0.39215, so ΔE_f = (0.24270/√2)^0.5 = 0.41426. (At column 16 both
// images have an edge response of 1 and ΔE_f ≈ 0.) Catches a dropped or inverted feature term,
// and the larger of the edge and point differences not being taken.
TEST(FlipTest, ShiftedEdgeRaisesTheErrorAboveTheColourTerm) {
    const int w = 32;
    const Image reference = stepEdge(w, 8, 16), test = stepEdge(w, 8, 17);
    const FlipTerms terms = ldrFlipTerms(test, reference);
    const std::vector<float> flip = ldrFlipMap(test, reference);
    for (int x : {15, 17}) {
        const float colour = at(terms.colour, w, x, 4);
        EXPECT_GT(colour, 0.05f);
        EXPECT_NEAR(at(terms.feature, w, x, 4), 0.41426f, kHandTolerance);
        EXPECT_GT(at(flip, w, x, 4), colour + 0.05f);
    }
}

// One bluer column in a grey image. The widest contrast filter, blue-yellow's b = 0.04 deg², has
// σ = √(0.04 / 2π²) = 0.045016° = 3.017 px at 67.02 px/°, so radius ⌈3σ⌉ = ⌈9.051⌉ = 10: the colour
// term is nonzero 10 columns away and exactly 0 at 11 (identical neighbourhoods). Catches a wrong
// radius rule or viewing distance, and filters not applied to the chromatic channels.
TEST(FlipTest, ColourTermReachesTheContrastFilterRadius) {
    const int w = 41, column = 15;
    const Image reference = uniform(w, 6, 0.5f, 0.5f, 0.5f);
    Image test = reference;
    for (int y = 0; y < 6; ++y) setPixel(test, column, y, 0.5f, 0.5f, 1.0f);
    const FlipTerms terms = ldrFlipTerms(test, reference);
    for (int y = 0; y < 6; ++y) {
        EXPECT_GT(at(terms.colour, w, column + 10, y), 0.0f);
        EXPECT_GT(at(terms.colour, w, column - 10, y), 0.0f);
        EXPECT_EQ(at(terms.colour, w, column + 11, y), 0.0f);
        EXPECT_EQ(at(terms.colour, w, column - 11, y), 0.0f);
    }
}

// Catches an error that does not grow with the difference (e.g. a saturating exponent, or a sign
// error in the compression), with a fixed seed and the same noise pattern scaled.
TEST(FlipTest, MeanErrorGrowsWithNoiseAmplitude) {
    const Image reference = hdrGradient(48, 32);
    const FlipExposures exposures = flipExposures(reference);
    std::mt19937 rng(5);
    std::normal_distribution<float> gauss(0, 1);
    std::vector<float> noise(reference.rgb.size());
    for (float& n : noise) n = gauss(rng);
    double previous = 0;
    for (float amplitude : {0.02f, 0.05f, 0.1f, 0.2f, 0.4f}) {
        Image test = reference;
        for (std::size_t i = 0; i < test.rgb.size(); ++i) test.rgb[i] *= std::max(0.0f, 1 + amplitude * noise[i]);
        const double flip = hdrFlip(test, reference, exposures);
        EXPECT_GT(flip, previous) << "amplitude " << amplitude;
        previous = flip;
    }
}

// [2]'s range for a reference of grey pixels (luminance = value) with maximum 10 and median 0.5
// (mean 4.3). The ACES fit y = (0.9036 x² + 0.018 x) / (0.8748 x² + 0.354 x + 0.14) reaches 0.85 at
// the positive root of 0.16002 x² − 0.2829 x − 0.119 = 0: x = (0.2829 + √(0.080032 + 0.076170))
// / 0.32004 = 2.11887. start = log2(2.11887 / 10) = −2.23863, stop = log2(2.11887 / 0.5) = 2.08330,
// count = ⌈4.32193⌉ = 5. Catches the mean for the median, a wrong target (0.85), a wrong tone mapper
// (e.g. without the 0.6 pre-scale), and a count not rounded up.
TEST(FlipTest, ExposureRangeFromMaximumAndMedian) {
    Image reference(5, 1);
    const float values[5] = {0.5f, 10, 0.5f, 10, 0.5f};
    for (int x = 0; x < 5; ++x) setPixel(reference, x, 0, values[x], values[x], values[x]);
    const FlipExposures e = flipExposures(reference);
    EXPECT_NEAR(e.start, -2.23863, 1e-4);
    EXPECT_NEAR(e.stop, 2.08330, 1e-4);
    EXPECT_EQ(e.count, 5);
}

// Six black pixels out of ten: [2]'s median is 0 and its stop exposure infinite. flip.h's rule:
// the median of the positive luminances {1, 2, 3, 8}, element ⌊4/2⌋ = 3, so stop = log2(2.11887 / 3)
// = −0.50167, start = log2(2.11887 / 8) = −1.91670, count = max(2, ⌈1.415⌉) = 2. Non-finite pixels
// take no part; an all-black reference ranges as luminance 1: start = stop = log2 2.11887 = 1.08330.
TEST(FlipTest, ExposureRangeWhenTheMedianIsZero) {
    Image reference(12, 1);
    const float values[10] = {0, 1, 0, 2, 0, 3, 0, 8, 0, 0};
    for (int x = 0; x < 10; ++x) setPixel(reference, x, 0, values[x], values[x], values[x]);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    setPixel(reference, 10, 0, nan, 0, 0);
    setPixel(reference, 11, 0, inf, inf, inf);
    const FlipExposures e = flipExposures(reference);
    EXPECT_NEAR(e.start, -1.91670, 1e-4);
    EXPECT_NEAR(e.stop, -0.50167, 1e-4);
    EXPECT_EQ(e.count, 2);

    const FlipExposures black = flipExposures(Image(4, 4));
    EXPECT_NEAR(black.start, 1.08330, 1e-4);
    EXPECT_NEAR(black.stop, 1.08330, 1e-4);
    EXPECT_EQ(black.count, 2);
}

// A reference half bright (1.0) and half dark (0.001, so the median), and a test whose dark half
// has a patch at twice the value. At the first exposure (the bright half at 0.85) the patch is all
// but black in both; at the last (the dark half at 0.85) it is plainly brighter. HDR-FLIP is the
// per-pixel maximum over exposures. Catches a mean (or the first or last exposure only) in place of
// the maximum, and evenly spaced exposures that miss an end of the range.
TEST(FlipTest, HdrFlipIsTheMaximumOverExposures) {
    const int w = 40, h = 20;
    Image reference(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = x < 19 ? 1.0f : 0.001f;
            setPixel(reference, x, y, v, v, v);
        }
    Image test = reference;
    for (int y = 6; y < 14; ++y)
        for (int x = 26; x < 34; ++x) setPixel(test, x, y, 0.002f, 0.002f, 0.002f);
    const FlipExposures range = flipExposures(reference);
    ASSERT_GE(range.count, 3);

    const std::vector<float> flip = hdrFlipMap(test, reference, range);
    std::vector<float> largest(flip.size(), 0.0f);
    for (int i = 0; i < range.count; ++i) {
        const double c = range.start + i * (range.stop - range.start) / (range.count - 1);
        const std::vector<float> one = hdrFlipMap(test, reference, {c, c, 1});
        for (std::size_t p = 0; p < one.size(); ++p) largest[p] = std::max(largest[p], one[p]);
    }
    for (std::size_t p = 0; p < flip.size(); ++p) EXPECT_FLOAT_EQ(flip[p], largest[p]);

    EXPECT_GT(at(flip, w, 30, 10), 0.3f);  // caught at the high exposures...
    EXPECT_LT(at(hdrFlipMap(test, reference, {range.start, range.start, 1}), w, 30, 10), 0.05f);  // ...not the first
}

// [2] clips the tone mapped values to [0, 1]: the ACES fit tends to 2.51/2.43 > 1, so without the
// clip two highlights of 100 and 200 would differ (1.029 vs 1.031) where the display shows white
// for both. One pixel on black, so that the contrast filter spreads it below 1 and its own clip
// does not hide the difference. Catches a missing clip after tone mapping.
TEST(FlipTest, HighlightsBeyondWhiteAreEqual) {
    Image reference(9, 9), test(9, 9);
    setPixel(reference, 4, 4, 100, 100, 100);
    setPixel(test, 4, 4, 200, 200, 200);
    for (float e : hdrFlipMap(test, reference, {0, 0, 1})) EXPECT_EQ(e, 0.0f);
}

// flip.h: a non-finite test pixel gives NaN near it, not a clipped colour, and a NaN mean; far
// away (beyond the filters' 10 px) the map is unaffected.
TEST(FlipTest, NonFinitePixelsPropagateAsNaN) {
    const Image reference = hdrGradient(40, 12);
    const FlipExposures range = flipExposures(reference);
    for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
        Image test = reference;
        setPixel(test, 5, 6, bad, 0.5f, 0.5f);
        const auto flip = hdrFlipMap(test, reference, range);
        EXPECT_TRUE(std::isnan(at(flip, 40, 5, 6)));
        EXPECT_TRUE(std::isnan(at(flip, 40, 12, 6)));
        EXPECT_EQ(at(flip, 40, 30, 6), 0.0f);
        EXPECT_TRUE(std::isnan(hdrFlip(test, reference, range)));
        Image ldr = uniform(40, 12, 0.5f, 0.5f, 0.5f);
        setPixel(ldr, 5, 6, bad, 0.5f, 0.5f);
        EXPECT_TRUE(std::isnan(at(ldrFlipMap(ldr, uniform(40, 12, 0.5f, 0.5f, 0.5f)), 40, 5, 6)));
    }
}

// Catches missing argument checks (they would read out of bounds or divide by zero).
TEST(FlipTest, BadInputThrows) {
    const Image a(8, 8), b(8, 9);
    EXPECT_THROW(ldrFlipMap(a, b), InputError);
    EXPECT_THROW(hdrFlipMap(a, b, {0, 0, 2}), InputError);
    EXPECT_THROW(hdrFlip(a, a, {0, 0, 0}), InputError);
    EXPECT_THROW(hdrFlip(a, a, {0, std::numeric_limits<double>::infinity(), 2}), InputError);
    EXPECT_THROW(ldrFlipMap(a, a, 0.0), InputError);
    EXPECT_THROW(ldrFlipMap(Image(), Image()), InputError);
    EXPECT_THROW(flipExposures(Image()), InputError);
}
