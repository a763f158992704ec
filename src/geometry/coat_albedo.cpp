// Directional albedo of the plastic's GGX coat (coat_albedo.h), for the coupled diffuse term of
// Kelemen & Szirmay-Kalos 2001 ("A Microfacet Based Coupled Specular-Matte BRDF Model with
// Importance Sampling"). With Schlick Fresnel the coat albedo is linear in F0:
//     E(μ, r; F0) = F0 · A(μ, r) + (1 − F0) · B(μ, r),
//     A = E_vndf[G2/G1],  B = E_vndf[(1 − wo·h)^5 · G2/G1],
// so two tables in (cos θ, roughness) serve every index of refraction. They are built once, on
// first use, by a deterministic quadrature over the VNDF sample square.
//
// Its own file because it is a precomputation over the microfacet model rather than a lobe:
// the materials only look values up.
#include "geometry/coat_albedo.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "geometry/microfacet.h"

namespace tripath {

namespace {

class CoatAlbedoTable {
public:
    static constexpr int kMu = 96, kRough = 32, kQuad = 24;
    // Safety margin added to the tabulated E: for these sizes the worst underestimate of the true
    // albedo over μ ∈ (0,1], roughness ∈ [0,1], F0 ∈ [0,1] measured 1.1e-3 (vs. a 400² quadrature).
    static constexpr double kMargin = 2.5e-3;

    CoatAlbedoTable() {
        for (int j = 0; j < kRough; ++j) {
            for (int i = 0; i < kMu; ++i) integrateNode(i, j);
            aAvg_[j] = cosineAverageOf(a_[j]);
            bAvg_[j] = cosineAverageOf(b_[j]);
        }
    }

    // Coat albedo E(μ) for cos θ = mu, bilinear in (sqrt μ, log α).
    float albedo(float mu, float roughness, float f0) const {
        const Lerp m = lerpAt(std::sqrt(std::max(mu, 0.0f)), kMu);
        const Lerp r = lerpAt(roughnessCoordinate(roughness), kRough);
        auto at = [&](int j, int i) { return f0 * a_[j][i] + (1.0f - f0) * b_[j][i]; };
        const float lo = (1 - m.t) * at(r.i, m.i) + m.t * at(r.i, m.i + 1);
        const float hi = (1 - m.t) * at(r.i + 1, m.i) + m.t * at(r.i + 1, m.i + 1);
        return std::clamp((1 - r.t) * lo + r.t * hi, 0.0f, 1.0f);
    }

    // Ē = 2 ∫ E(μ) μ dμ of the *interpolated* table, so that the coupled diffuse lobe below
    // integrates exactly to albedo · (1 − E(μo)) whatever the table's own error.
    float cosineWeightedAverage(float roughness, float f0) const {
        const Lerp r = lerpAt(roughnessCoordinate(roughness), kRough);
        auto at = [&](int j) { return f0 * aAvg_[j] + (1.0f - f0) * bAvg_[j]; };
        return std::clamp((1 - r.t) * at(r.i) + r.t * at(r.i + 1), 0.0f, 1.0f);
    }

private:
    struct Lerp {
        int i;
        float t;
    };
    static Lerp lerpAt(float x, int n) {
        const float s = std::clamp(x, 0.0f, 1.0f) * static_cast<float>(n - 1);
        const int i = std::min(static_cast<int>(s), n - 2);
        return {i, s - static_cast<float>(i)};
    }
    static float nodeValue(int i, int n) { return static_cast<float>(i) / static_cast<float>(n - 1); }

    // The roughness axis is uniform in log α: near-specular coats change character with the
    // ratio of α values (the grazing masking scale μ ~ α), not with their difference.
    static constexpr float kLogAlphaMin = -6.907755279f;  // log(1e-3), the ggxAlpha floor
    static float roughnessCoordinate(float roughness) {
        return 1.0f - std::log(ggxAlpha(std::clamp(roughness, 0.0f, 1.0f))) / kLogAlphaMin;
    }
    static float alphaAtNode(int j) { return std::exp(kLogAlphaMin * (1.0f - nodeValue(j, kRough))); }

    // Nodes are uniform in t = sqrt(μ): for a smooth coat E changes on a scale μ ~ α near
    // grazing incidence (masking), which uniform μ nodes would miss.
    void integrateNode(int i, int j) {
        const float t = nodeValue(i, kMu);
        const float mu = std::max(t * t, 1e-5f);  // μ = 0 is the limit; evaluate just above it
        const Vec3 wo(std::sqrt(1.0f - mu * mu), 0.0f, mu);
        const float alpha = alphaAtNode(j);
        double sumA = 0, sumB = 0;
        for (int y = 0; y < kQuad; ++y)
            for (int x = 0; x < kQuad; ++x) {
                // Substitute u1 = 1 − (1 − v)²: the VNDF warp has a sqrt(1 − u1) edge at the rim
                // of the disk that a midpoint rule in u1 integrates poorly.
                const double v = (x + 0.5) / kQuad;
                const Vec2 u{static_cast<float>(1.0 - (1.0 - v) * (1.0 - v)), (y + 0.5f) / kQuad};
                const auto wi = sampleGgxReflection(wo, alpha, u);
                if (!wi) continue;
                const double g = 2.0 * (1.0 - v) * ggxMaskingRatio(wo, *wi, alpha);
                sumA += g;
                sumB += g * schlickWeight(halfVectorCos(wo, *wi));
            }
        // Bias upward by the margin (never past 1): the diffuse lobe then gets slightly less
        // than 1 − E_true and the total albedo stays ≤ 1 despite quadrature and interpolation.
        a_[j][i] = static_cast<float>(std::min(1.0, sumA / (kQuad * kQuad) + kMargin));
        b_[j][i] = static_cast<float>(std::min(1.0, sumB / (kQuad * kQuad) + kMargin));
    }

    // 2 ∫ E μ dμ = ∫ E(t) 4t³ dt with E linear in t on each interval: a quartic there, which
    // 3-point Gauss-Legendre integrates exactly.
    static float cosineAverageOf(const std::array<float, kMu>& e) {
        constexpr double kNode[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};
        constexpr double kWeight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
        const double h = 1.0 / (kMu - 1);
        double sum = 0;
        for (int i = 0; i + 1 < kMu; ++i)
            for (int q = 0; q < 3; ++q) {
                const double s = 0.5 * (1.0 + kNode[q]);  // position within the interval
                const double t = (i + s) * h;
                const double ev = (1.0 - s) * e[i] + s * e[i + 1];
                sum += 0.5 * h * kWeight[q] * ev * 4.0 * t * t * t;
            }
        return static_cast<float>(sum);
    }

    std::array<std::array<float, kMu>, kRough> a_{}, b_{};
    std::array<float, kRough> aAvg_{}, bAvg_{};
};

const CoatAlbedoTable& coatAlbedoTable() {
    static const CoatAlbedoTable table;  // thread-safe one-time construction (C++11 magic static)
    return table;
}

}  // namespace

float coatAlbedo(float mu, float roughness, float f0) { return coatAlbedoTable().albedo(mu, roughness, f0); }

float coatAlbedoAverage(float roughness, float f0) {
    return coatAlbedoTable().cosineWeightedAverage(roughness, f0);
}

}  // namespace tripath
