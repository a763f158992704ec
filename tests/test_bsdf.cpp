// Physics tests of the BSDFs (docs/design.md §3: reciprocal, non-negative, energy-conserving), plus the
// contract between sampleBsdf, evalBsdf and pdfBsdf that MIS relies on.
//
// Statistical checks use fixed-seed streams, so they are deterministic; thresholds are set from
// the estimator's own standard error (4σ) or a chi-square p-value of 1e-5, never tuned to pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "geometry/material.h"
#include "core/rng.h"
#include "core/sampling.h"

namespace tripath {
namespace {

// ---------------------------------------------------------------------------------------------
// Fixtures

Material makeMaterial(MaterialType type, Spectrum albedo, float roughness = 0.5f, float ior = 1.5f) {
    Material m;
    m.type = type;
    m.albedo = albedo;
    m.roughness = roughness;
    m.ior = ior;
    m.name = std::string(materialTypeName(type)) + " r=" + std::to_string(roughness) +
             " ior=" + std::to_string(ior);
    return m;
}

// glTF's metallic-roughness mix at the given metallic, ior 1.5 (glTF's dielectric).
Material metallicRoughness(Spectrum base, float metallic, float roughness) {
    Material m = makeMaterial(MaterialType::MetallicRoughness, base, roughness);
    m.metallic = metallic;
    m.name += " metallic=" + std::to_string(metallic);
    return m;
}

// glTF's mix with KHR_materials_transmission's factor: its dielectric half (1 − T) plastic + T
// rough glass.
Material transmissiveMix(Spectrum base, float metallic, float roughness, float transmission) {
    Material m = metallicRoughness(base, metallic, roughness);
    m.transmission = transmission;
    m.name += " transmission=" + std::to_string(transmission);
    return m;
}

// The index on w's side of a surface whose interior (z < 0) has index ior and exterior 1.
float indexOnSideOf(const Material& m, Vec3 w) { return transmits(m) && w.z < 0 ? m.ior : 1.0f; }

Rng testRng(uint64_t k) { return Rng(1234, static_cast<uint64_t>(StreamDomain::Test), k); }
Vec2 uniform2(Rng& rng) { return {rng.uniform(), rng.uniform()}; }

// sampleBsdf with u drawn first (x, then y) and uc after it, as the walks draw them. The
// arguments of one call are evaluated in an order C++ leaves unspecified (GCC and Clang differ),
// so `sampleBsdf(m, wo, uniform2(rng), rng.uniform(), mode)` would test different samples
// depending on the compiler: every draw is a statement of its own.
std::optional<BsdfSample> drawBsdfSample(const Material& m, Vec3 wo, Rng& rng, TransportMode mode) {
    const Vec2 u = uniform2(rng);
    const float uc = rng.uniform();
    return sampleBsdf(m, wo, u, uc, mode);
}

// Direction at polar angle θ (degrees) and azimuth φ; negative z for θ > 90°.
Vec3 directionAtAngle(float thetaDegrees, float phi = 0.3f) {
    const float t = thetaDegrees * kPi / 180.0f;
    return {std::sin(t) * std::cos(phi), std::sin(t) * std::sin(phi), std::cos(t)};
}

Vec3 directionFromCosPhi(double z, double phi) {
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
            static_cast<float>(z)};
}

// The non-delta materials every generic test runs over: a spread of roughness including the
// clamped extreme 0, coloured F0 and albedo, coat and glass indices, rough glass alone and mixed.
std::vector<Material> nonDeltaMaterials() {
    return {
        makeMaterial(MaterialType::Lambertian, {0.7f, 0.5f, 0.2f}),
        makeMaterial(MaterialType::Conductor, {0.95f, 0.64f, 0.54f}, 0.0f),
        makeMaterial(MaterialType::Conductor, {0.95f, 0.64f, 0.54f}, 0.1f),
        makeMaterial(MaterialType::Conductor, {0.9f, 0.9f, 0.9f}, 0.4f),
        makeMaterial(MaterialType::Conductor, {0.56f, 0.57f, 0.58f}, 0.8f),
        makeMaterial(MaterialType::Conductor, {1.0f, 1.0f, 1.0f}, 1.0f),
        makeMaterial(MaterialType::Plastic, {0.8f, 0.3f, 0.1f}, 0.0f),
        makeMaterial(MaterialType::Plastic, {0.8f, 0.3f, 0.1f}, 0.3f, 1.5f),
        makeMaterial(MaterialType::Plastic, {0.2f, 0.6f, 0.9f}, 0.7f, 2.2f),
        makeMaterial(MaterialType::Plastic, {1.0f, 1.0f, 1.0f}, 1.0f, 1.33f),
        metallicRoughness({0.9f, 0.6f, 0.3f}, 0.5f, 0.0f),
        metallicRoughness({0.9f, 0.6f, 0.3f}, 0.25f, 0.4f),
        metallicRoughness({1.0f, 1.0f, 1.0f}, 0.8f, 1.0f),
        makeMaterial(MaterialType::RoughDielectric, {0.9f, 0.7f, 0.5f}, 0.0f, 1.5f),
        makeMaterial(MaterialType::RoughDielectric, {0.9f, 0.7f, 0.5f}, 0.15f, 1.5f),
        makeMaterial(MaterialType::RoughDielectric, {1.0f, 1.0f, 1.0f}, 0.5f, 1.33f),
        makeMaterial(MaterialType::RoughDielectric, {0.6f, 0.8f, 1.0f}, 1.0f, 2.4f),
        transmissiveMix({0.9f, 0.6f, 0.3f}, 0.3f, 0.4f, 0.6f),
        transmissiveMix({1.0f, 1.0f, 1.0f}, 0.0f, 0.2f, 0.5f),
    };
}

bool relativelyEqual(float a, float b, float rel) {
    return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + 1e-30f;
}

// ---------------------------------------------------------------------------------------------
// Non-negativity and reciprocity: f(wo, wi) = f(wi, wo) (Helmholtz; Veach 1997 §6.2); across a
// refracting interface f(wo, wi) / η_o² = f(wi, wo) / η_i² (Veach 1997 §6.2, generalised), and
// importance carries the adjoint f*(wo, wi) = f(wi, wo) (§3.7)

// Half the pairs are uniform on the sphere; half are perturbed mirror configurations (and, for
// a third of those, perturbed straight-through ones) so that the narrow lobes of smooth conductors
// and of smooth rough glass are actually exercised.
std::pair<Vec3, Vec3> randomPair(Rng& rng, int i) {
    const Vec3 wo = sampleUniformSphere(uniform2(rng));
    if (i % 2 == 0) return {wo, sampleUniformSphere(uniform2(rng))};
    const Vec3 offset = sampleUniformSphere(uniform2(rng));  // drawn before the scale: sequenced
    const Vec3 jitter = offset * (0.05f * rng.uniform());
    const Vec3 centre = i % 3 == 0 ? -wo : Vec3(-wo.x, -wo.y, wo.z);
    return {wo, normalize(centre + jitter)};
}

TEST(Bsdf, NonNegativeAndReciprocal) {
    for (const Material& m : nonDeltaMaterials()) {
        Rng rng = testRng(1);
        for (int i = 0; i < 20000; ++i) {
            const auto [wo, wi] = randomPair(rng, i);
            const Spectrum a = evalBsdf(m, wo, wi, TransportMode::Radiance);
            const Spectrum b = evalBsdf(m, wi, wo, TransportMode::Radiance);
            const Spectrum adjoint = evalBsdf(m, wi, wo, TransportMode::Importance);
            const float etaO = indexOnSideOf(m, wo), etaI = indexOnSideOf(m, wi);
            ASSERT_TRUE(isFinite(a)) << m.name;
            for (int c = 0; c < 3; ++c) {
                ASSERT_GE(a[c], 0.0f) << m.name;
                // Or within 1e-6 / sr, which no integral over the sphere can see: where rough glass
                // meets a facet at grazing (a refraction at the critical angle), the float cosine
                // of the two is a difference of O(1) products, good to 1e-3 relative.
                ASSERT_TRUE(relativelyEqual(a[c] / (etaO * etaO), b[c] / (etaI * etaI), 1e-4f) ||
                            std::abs(a[c] / (etaO * etaO) - b[c] / (etaI * etaI)) < 1e-6f)
                    << m.name << " channel " << c << ": " << a[c] << " vs " << b[c] << " at " << wo.z << ", " << wi.z;
                ASSERT_TRUE(relativelyEqual(a[c], adjoint[c], 1e-4f) || std::abs(a[c] - adjoint[c]) < 1e-6f)
                    << m.name << " channel " << c << ": " << a[c] << " vs the adjoint " << adjoint[c];
            }
        }
    }
}

// Two-sidedness of the reflection lobes: mirroring both directions through the shading plane
// changes nothing, and a reflection-only lobe never connects the two sides.
TEST(Bsdf, TwoSidedReflectionOnly) {
    for (const Material& m : nonDeltaMaterials()) {
        if (transmits(m)) continue;
        Rng rng = testRng(3);
        for (int i = 0; i < 2000; ++i) {
            const auto [wo, wi] = randomPair(rng, i);
            const Vec3 woM(wo.x, wo.y, -wo.z), wiM(wi.x, wi.y, -wi.z);
            EXPECT_EQ(evalBsdf(m, wo, wi, TransportMode::Radiance),
                      evalBsdf(m, woM, wiM, TransportMode::Radiance));
            EXPECT_EQ(pdfBsdf(m, wo, wi), pdfBsdf(m, woM, wiM));
            if (wo.z * wi.z < 0) {
                EXPECT_TRUE(isBlack(evalBsdf(m, wo, wi, TransportMode::Radiance))) << m.name;
                EXPECT_EQ(pdfBsdf(m, wo, wi), 0.0f) << m.name;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Sampling contract: what sampleBsdf reports is what evalBsdf / pdfBsdf say

TEST(Bsdf, SampledValuesMatchEvalAndPdf) {
    for (const Material& m : nonDeltaMaterials()) {
        Rng rng = testRng(4);
        for (int i = 0; i < 20000; ++i) {
            const Vec3 wo = sampleUniformSphere(uniform2(rng));
            const TransportMode mode = i % 2 ? TransportMode::Importance : TransportMode::Radiance;
            const auto s = drawBsdfSample(m, wo, rng, mode);
            if (!s) continue;
            ASSERT_FALSE(s->delta) << m.name;
            ASSERT_NEAR(length(s->wi), 1.0f, 1e-4f) << m.name;
            if (!transmits(m)) ASSERT_GT(s->wi.z * wo.z, 0.0f) << m.name;
            ASSERT_GT(s->pdf, 0.0f) << m.name;
            const Spectrum f = evalBsdf(m, wo, s->wi, mode);
            for (int c = 0; c < 3; ++c) ASSERT_TRUE(relativelyEqual(s->f[c], f[c], 1e-5f)) << m.name;
            ASSERT_TRUE(relativelyEqual(s->pdf, pdfBsdf(m, wo, s->wi), 1e-5f)) << m.name;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Histogram of sampled directions against the integrated pdf (chi-square goodness of fit)

// Bins over the whole sphere in (cos θ, φ), where dω = d(cos θ) dφ; the cos θ = 0 edge falls on
// a bin boundary, so the pdf's step at the horizon does not spoil the quadrature.
struct SphereBins {
    int nCos = 16, nPhi = 32;
    int count() const { return nCos * nPhi; }
    int index(Vec3 w) const {
        const double phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
        const int ci = std::clamp(static_cast<int>((w.z + 1.0) * 0.5 * nCos), 0, nCos - 1);
        const int pi = std::clamp(static_cast<int>((phi + kPi) / (2 * kPi) * nPhi), 0, nPhi - 1);
        return ci * nPhi + pi;
    }
    // ∫ pdf over bin b with an s×s midpoint rule. In a bin at a pole the rule runs over t with
    // z = pole ∓ dz t⁴ (dz → 4 dz t³ dt), so θ ∝ t² near the pole and the points crowd there: a
    // lobe around the pole (rough glass refracting a normal ray: its width a third of α) is
    // narrow in z, as 1 − cos θ ≈ θ²/2.
    double integrate(const std::function<float(Vec3)>& pdf, int b, int s) const {
        const double dz = 2.0 / nCos, dphi = 2 * std::numbers::pi / nPhi;
        const int row = b / nPhi;
        const double z0 = -1.0 + row * dz, phi0 = -std::numbers::pi + (b % nPhi) * dphi;
        const bool south = row == 0, north = row == nCos - 1;
        double sum = 0;
        for (int i = 0; i < s; ++i) {
            const double t = (i + 0.5) / s;
            const double t4 = t * t * t * t;
            const double z = south ? -1.0 + dz * t4 : north ? 1.0 - dz * t4 : z0 + t * dz;
            const double weight = south || north ? 4 * t * t * t : 1.0;
            for (int j = 0; j < s; ++j) sum += weight * pdf(directionFromCosPhi(z, phi0 + (j + 0.5) * dphi / s));
        }
        return sum * dz * dphi / (s * s);
    }
    // Refine the midpoint rule until two resolutions agree: GGX lobes are narrow in some bins.
    double integrateAdaptive(const std::function<float(Vec3)>& pdf, int b) const {
        double coarse = integrate(pdf, b, 8);
        for (int s = 16; s <= 128; s *= 2) {
            const double fine = integrate(pdf, b, s);
            if (std::abs(fine - coarse) <= 1e-4 * fine + 1e-9) return fine;
            coarse = fine;
        }
        return coarse;
    }
    std::vector<double> probabilities(const std::function<float(Vec3)>& pdf) const {
        std::vector<double> p(count());
        for (int b = 0; b < count(); ++b) p[b] = integrateAdaptive(pdf, b);
        return p;
    }
    // ∫ f dω over the whole sphere, bin by bin.
    double integral(const std::function<float(Vec3)>& f) const {
        double sum = 0;
        for (double x : probabilities(f)) sum += x;
        return sum;
    }
};

// Upper tail P(X ≥ x) of a chi-square variable with k degrees of freedom, by the Wilson-Hilferty
// cube-root normal approximation (accurate to a few percent in p for k ≳ 30, ample for a 1e-5
// rejection threshold).
double chiSquarePValue(double x, int k) {
    const double v = 2.0 / (9.0 * k);
    const double z = (std::cbrt(x / k) - (1.0 - v)) / std::sqrt(v);
    return 0.5 * std::erfc(z / std::sqrt(2.0));
}

struct ChiSquareResult {
    double statistic = 0;
    int dof = 0;
    double pValue = 1;
};

// Pearson's statistic after pooling every cell with an expected count below 5 into one cell
// (and that pool into the smallest regular cell if it is itself too small).
ChiSquareResult chiSquare(const std::vector<double>& observed, const std::vector<double>& expected) {
    std::vector<std::pair<double, double>> cells;  // (expected, observed)
    double poolE = 0, poolO = 0;
    for (size_t i = 0; i < expected.size(); ++i) {
        if (expected[i] < 5) {
            poolE += expected[i];
            poolO += observed[i];
        } else {
            cells.push_back({expected[i], observed[i]});
        }
    }
    if (poolE >= 5 || cells.empty()) {
        cells.push_back({poolE, poolO});
    } else {
        auto smallest = std::min_element(cells.begin(), cells.end());
        smallest->first += poolE;
        smallest->second += poolO;
    }
    ChiSquareResult r;
    for (const auto& [e, o] : cells) r.statistic += (o - e) * (o - e) / std::max(e, 1e-12);
    r.dof = static_cast<int>(cells.size()) - 1;
    r.pValue = r.dof > 0 ? chiSquarePValue(r.statistic, r.dof) : 1.0;
    return r;
}

// Observed histogram of N samples plus a last cell for "no direction produced" (the pdf is
// the same in either mode).
std::vector<double> sampledHistogram(const Material& m, Vec3 wo, const SphereBins& bins, int n, Rng& rng) {
    std::vector<double> h(bins.count() + 1, 0.0);
    for (int i = 0; i < n; ++i) {
        const auto s = drawBsdfSample(m, wo, rng, TransportMode::Radiance);
        h[s ? bins.index(s->wi) : bins.count()] += 1;
    }
    return h;
}

struct SamplingCase {
    Material m;
    float thetaDegrees;
};

std::vector<SamplingCase> samplingCases() {
    std::vector<SamplingCase> cases;
    const std::vector<Material> materials = {
        makeMaterial(MaterialType::Lambertian, Spectrum(0.5f)),
        makeMaterial(MaterialType::Conductor, Spectrum(0.9f), 0.3f),
        makeMaterial(MaterialType::Conductor, Spectrum(0.9f), 0.6f),
        makeMaterial(MaterialType::Conductor, Spectrum(0.9f), 1.0f),
        makeMaterial(MaterialType::Plastic, Spectrum(0.5f), 0.3f),
        makeMaterial(MaterialType::Plastic, {0.9f, 0.2f, 0.1f}, 0.8f, 2.0f),
        metallicRoughness({0.9f, 0.5f, 0.2f}, 0.5f, 0.3f),
        metallicRoughness(Spectrum(0.7f), 0.2f, 0.7f),
        makeMaterial(MaterialType::RoughDielectric, Spectrum(0.8f), 0.3f, 1.5f),
        makeMaterial(MaterialType::RoughDielectric, {0.9f, 0.6f, 0.3f}, 0.7f, 1.33f),
        transmissiveMix({0.9f, 0.5f, 0.2f}, 0.3f, 0.4f, 0.7f),
    };
    // Normal, oblique, near-grazing, and the back side (two-sided shading; inside the glass,
    // beyond its critical angle).
    for (const Material& m : materials)
        for (float theta : {0.0f, 50.0f, 87.0f, 125.0f}) cases.push_back({m, theta});
    return cases;
}

TEST(Bsdf, SampledDirectionsFollowPdfChiSquare) {
    const SphereBins bins;
    const int n = 100000;
    int k = 0;
    for (const SamplingCase& c : samplingCases()) {
        const Vec3 wo = directionAtAngle(c.thetaDegrees);
        Rng rng = testRng(100 + k++);
        const std::vector<double> observed = sampledHistogram(c.m, wo, bins, n, rng);
        std::vector<double> p = bins.probabilities([&](Vec3 wi) { return pdfBsdf(c.m, wo, wi); });
        double total = 0;
        for (double x : p) total += x;
        p.push_back(std::max(0.0, 1.0 - total));  // probability that sampling fails
        std::vector<double> expected(p.size());
        for (size_t i = 0; i < p.size(); ++i) expected[i] = p[i] * n;
        const ChiSquareResult r = chiSquare(observed, expected);
        EXPECT_GT(r.pValue, 1e-5) << c.m.name << " θo=" << c.thetaDegrees << ": χ²=" << r.statistic
                                  << " dof=" << r.dof;
    }
}

// ∫ pdf dω is the probability that sampleBsdf produces a direction: 1 for Lambertian, and for
// the GGX lobes 1 minus the fraction of reflections that fall below the horizon.
TEST(Bsdf, PdfIntegratesToSamplingProbability) {
    const SphereBins bins;
    const int n = 100000;
    int k = 0;
    for (const SamplingCase& c : samplingCases()) {
        const Vec3 wo = directionAtAngle(c.thetaDegrees);
        const double integral = bins.integral([&](Vec3 wi) { return pdfBsdf(c.m, wo, wi); });
        Rng rng = testRng(200 + k++);
        int produced = 0;
        for (int i = 0; i < n; ++i)
            produced +=
                drawBsdfSample(c.m, wo, rng, TransportMode::Radiance).has_value();
        const double rate = static_cast<double>(produced) / n;
        const double sigma = std::sqrt(std::max(rate * (1 - rate), 1.0 / n) / n);
        EXPECT_NEAR(integral, rate, 4 * sigma + 1e-3) << c.m.name << " θo=" << c.thetaDegrees;
        EXPECT_LE(integral, 1.0 + 1e-3) << c.m.name << " θo=" << c.thetaDegrees;
        if (c.m.type == MaterialType::Lambertian) {
            EXPECT_NEAR(integral, 1.0, 1e-3);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Energy: directional albedo ρ(wo) = ∫ f(wo, wi) |cos θi| dωi, estimated with the BSDF's own
// sampling (the estimator f |cos θi| / pdf, 0 when no direction is produced).

struct Estimate {
    Spectrum mean{0.0f};
    Spectrum sigma{0.0f};  // standard error of the mean
};

// Sums in double: in float, 20000 weights of 0.9 already add up 2e-4 away from 0.9 · 20000.
Estimate directionalAlbedo(const Material& m, Vec3 wo, TransportMode mode, int n, Rng& rng) {
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const auto s = drawBsdfSample(m, wo, rng, mode);
        if (!s) continue;
        const Spectrum w = s->f * (std::abs(s->wi.z) / s->pdf);
        for (int c = 0; c < 3; ++c) {
            sum[c] += w[c];
            sum2[c] += double(w[c]) * w[c];
        }
    }
    Estimate e;
    for (int c = 0; c < 3; ++c) {
        const double mean = sum[c] / n;
        e.mean[c] = static_cast<float>(mean);
        e.sigma[c] = static_cast<float>(std::sqrt(std::max(0.0, sum2[c] / n - mean * mean) / n));
    }
    return e;
}

const std::vector<float> kAlbedoAngles = {0.0f, 30.0f, 60.0f, 80.0f, 89.0f, 120.0f};

TEST(Bsdf, DirectionalAlbedoAtMostOne) {
    std::vector<Material> materials = nonDeltaMaterials();
    materials.push_back(makeMaterial(MaterialType::Mirror, Spectrum(1.0f)));
    materials.push_back(makeMaterial(MaterialType::SmoothConductor, Spectrum(0.9f), 0.0f));
    materials.push_back(makeMaterial(MaterialType::Dielectric, Spectrum(1.0f), 0.0f, 1.5f));
    materials.push_back(makeMaterial(MaterialType::Plastic, Spectrum(1.0f), 0.15f, 3.0f));
    int k = 0;
    for (const Material& m : materials)
        for (float theta : kAlbedoAngles) {
            // Radiance-mode glass concentrates radiance when leaving the glass (weight η² > 1),
            // which is physics, not a gain of energy: check importance there (its albedo is 1).
            const bool glass = m.type == MaterialType::Dielectric || transmits(m);
            const bool leavingGlass = glass && theta > 90;
            const TransportMode mode = leavingGlass ? TransportMode::Importance : TransportMode::Radiance;
            Rng rng = testRng(300 + k++);
            const Estimate e = directionalAlbedo(m, directionAtAngle(theta), mode, 50000, rng);
            for (int c = 0; c < 3; ++c)
                EXPECT_LE(e.mean[c], 1.0f + 4 * e.sigma[c] + 1e-5f) << m.name << " θo=" << theta;
        }
}

TEST(Bsdf, LambertianAlbedoIsExact) {
    const Spectrum a(0.7f, 0.5f, 0.2f);
    const Material m = makeMaterial(MaterialType::Lambertian, a);
    Rng rng = testRng(400);
    for (float theta : kAlbedoAngles) {
        const Vec3 wo = directionAtAngle(theta);
        for (int i = 0; i < 2000; ++i) {
            // Cosine-weighted sampling is perfect importance sampling: every weight equals a.
            const auto s = drawBsdfSample(m, wo, rng, TransportMode::Radiance);
            ASSERT_TRUE(s.has_value());
            const Spectrum w = s->f * (std::abs(s->wi.z) / s->pdf);
            for (int c = 0; c < 3; ++c) ASSERT_NEAR(w[c], a[c], 1e-5f);
        }
    }
}

// The weight f |cos θi| / pdf of a material's sample at wo, which must be a delta reflection
// about the normal (0 when it is not, with the failure reported).
Spectrum deltaReflectionWeight(const Material& m, Vec3 wo) {
    const auto s = sampleBsdf(m, wo, {0.3f, 0.6f}, 0.2f, TransportMode::Radiance);
    EXPECT_TRUE(s.has_value() && s->delta && s->wi == Vec3(-wo.x, -wo.y, wo.z)) << m.name;
    return s ? s->f * (std::abs(s->wi.z) / s->pdf) : Spectrum(0.0f);
}

TEST(Bsdf, MirrorReflectsWithItsAlbedo) {
    const Spectrum a(0.9f, 0.8f, 0.3f);
    const Material m = makeMaterial(MaterialType::Mirror, a);
    for (float theta : kAlbedoAngles) {
        const Spectrum w = deltaReflectionWeight(m, directionAtAngle(theta));
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(w[c], a[c], 1e-6f);
    }
}

// glTF's metallic 1, roughness 0 is the rough conductor's limit: a delta reflection of Schlick's
// F0 + (1 − F0)(1 − cos θ)⁵, written out here (F0 = 0.5 reads 0.694 at 80°, not 0.5). And the same
// limit reached through a texture (MetallicRoughness, metallic 1, roughness 0: the GGX path at its
// smallest α) reflects as much, its directional albedo within 1 % of the delta's at 0°–85°, so
// that a file's factor and its texture render alike. Catches a constant-reflectance mirror (28 %
// too dark at 80°), Fresnel taken at the wrong cosine, or a factor path that differs from the
// texture path.
TEST(Bsdf, SmoothConductorIsTheRoughOnesLimitWithSchlicksFresnel) {
    const Spectrum f0(0.5f, 0.8f, 0.2f);
    const Material smooth = makeMaterial(MaterialType::SmoothConductor, f0, 0.0f);
    EXPECT_TRUE(isDelta(smooth));
    const Material textured = metallicRoughness(f0, 1.0f, 0.0f);
    int k = 0;
    for (float theta : {0.0f, 30.0f, 60.0f, 80.0f, 85.0f}) {
        const Vec3 wo = directionAtAngle(theta);
        const Spectrum w = deltaReflectionWeight(smooth, wo);
        const double c = std::cos(double(theta) * std::numbers::pi / 180);
        Rng rng = testRng(2600 + k++);
        const Estimate e = directionalAlbedo(textured, wo, TransportMode::Radiance, 20000, rng);
        for (int ch = 0; ch < 3; ++ch) {
            const double schlick = f0[ch] + (1 - f0[ch]) * std::pow(1 - c, 5);
            EXPECT_NEAR(w[ch], schlick, 1e-5) << "θ=" << theta << " channel " << ch;
            EXPECT_NEAR(e.mean[ch], schlick, 0.01 * schlick + 4 * e.sigma[ch]) << "θ=" << theta << " channel " << ch;
        }
    }
}

// Reference Fresnel reflectance for the glass tests, from the amplitude coefficients in terms of
// the indices themselves (Hecht, Optics, eqs. 4.42-4.43), in double precision.
double referenceFresnel(double cosI, double etaI, double etaT) {
    const double sinT = etaI / etaT * std::sqrt(std::max(0.0, 1 - cosI * cosI));
    if (sinT >= 1) return 1;
    const double cosT = std::sqrt(1 - sinT * sinT);
    const double rs = (etaI * cosI - etaT * cosT) / (etaI * cosI + etaT * cosT);
    const double rp = (etaT * cosI - etaI * cosT) / (etaT * cosI + etaI * cosT);
    return 0.5 * (rs * rs + rp * rp);
}

// Every glass sample has the exact weight its lobe predicts, goes where the law of reflection or
// Snell's law says, and reflection is chosen with probability F.
TEST(Bsdf, DielectricFollowsFresnelAndSnell) {
    const float ior = 1.5f;
    const Spectrum tint(0.9f, 0.7f, 0.5f);
    const Material m = makeMaterial(MaterialType::Dielectric, tint, 0.0f, ior);
    const int n = 40000;
    for (float theta : {0.0f, 30.0f, 70.0f, 89.0f, 150.0f, 135.0f, 110.0f}) {
        const Vec3 wo = directionAtAngle(theta);
        const bool outside = wo.z > 0;
        const double etaO = outside ? 1.0 : ior, etaI = outside ? ior : 1.0;  // wo side, wi side
        const double fr = referenceFresnel(std::abs(wo.z), etaO, etaI);
        for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
            Rng rng = testRng(500);
            int reflected = 0;
            for (int i = 0; i < n; ++i) {
                const auto s = drawBsdfSample(m, wo, rng, mode);
                ASSERT_TRUE(s.has_value());
                ASSERT_TRUE(s->delta);
                const Spectrum w = s->f * (std::abs(s->wi.z) / s->pdf);
                if (s->wi.z * wo.z > 0) {
                    ++reflected;
                    ASSERT_EQ(s->wi, Vec3(-wo.x, -wo.y, wo.z));
                    ASSERT_NEAR(s->pdf, fr, 1e-5);
                    for (int c = 0; c < 3; ++c) ASSERT_NEAR(w[c], 1.0f, 1e-5f);  // white reflection
                } else {
                    ASSERT_NEAR(s->pdf, 1 - fr, 1e-5);
                    // Snell: η_o sin θo = η_i sin θi, tangential direction reversed.
                    const double sinO = std::hypot(wo.x, wo.y), sinI = std::hypot(s->wi.x, s->wi.y);
                    ASSERT_NEAR(etaO * sinO, etaI * sinI, 1e-5);
                    ASSERT_LE(s->wi.x * wo.x + s->wi.y * wo.y, 1e-6f);
                    // Radiance: (η_o/η_i)² (Veach 1997 §5.2); importance: 1 (the adjoint BTDF).
                    const double scale =
                        mode == TransportMode::Radiance ? (etaO * etaO) / (etaI * etaI) : 1.0;
                    for (int c = 0; c < 3; ++c) ASSERT_NEAR(w[c], tint[c] * scale, 1e-5 * scale);
                }
            }
            const double sigma = std::sqrt(std::max(fr * (1 - fr), 1e-12) / n);
            EXPECT_NEAR(static_cast<double>(reflected) / n, fr, 4 * sigma + 1e-6) << "θo=" << theta;
        }
    }
}

// Clear glass: in importance mode every sample has weight exactly 1, so the albedo is 1; in
// radiance mode it is F + (1 − F)/η², matched by the estimate within its standard error.
TEST(Bsdf, ClearGlassAlbedo) {
    const float ior = 1.5f;
    const Material m = makeMaterial(MaterialType::Dielectric, Spectrum(1.0f), 0.0f, ior);
    int k = 0;
    for (float theta : {10.0f, 45.0f, 80.0f, 170.0f, 140.0f, 130.0f}) {
        const Vec3 wo = directionAtAngle(theta);
        const double etaO = wo.z > 0 ? 1.0 : ior, etaI = wo.z > 0 ? ior : 1.0;
        const double fr = referenceFresnel(std::abs(wo.z), etaO, etaI);
        Rng rng = testRng(600 + k++);
        const Estimate imp = directionalAlbedo(m, wo, TransportMode::Importance, 20000, rng);
        EXPECT_NEAR(imp.mean.x, 1.0f, 1e-5f) << "θo=" << theta;
        const Estimate rad = directionalAlbedo(m, wo, TransportMode::Radiance, 20000, rng);
        const double expected = fr + (1 - fr) * (etaO * etaO) / (etaI * etaI);
        EXPECT_NEAR(rad.mean.x, expected, 4 * rad.sigma.x + 1e-5) << "θo=" << theta;
    }
}

// A mirror and a smooth dielectric scatter into the mirror and refraction directions alone, with
// the energy of closed forms: the mirror its albedo a; glass F + (1 − F) · tint · s (s = (η_o/η_i)²
// for radiance, 1 for importance). Sampling carries all of it (MirrorReflectsWithItsAlbedo,
// DielectricFollowsFresnelAndSnell), so anything evalBsdf returns elsewhere on the sphere -- which
// connections through the vertex would gather -- is energy the surface does not have: the sampled
// albedo plus ∫ f |cos θi| dωi of the evaluable part must equal the closed form. In the same way, ∫ pdfBsdf dω is the probability of a sample
// off the delta lobes, 0 here; MIS would otherwise weigh connections against a lobe that does not
// exist. Catches a delta material evaluated like a diffuse or glossy one (evalBsdf's or pdfBsdf's
// early return gone, with a fallback lobe for the other types), and a sample not flagged delta.
TEST(Bsdf, DeltaMaterialsScatterOnlyIntoTheirSampledDirections) {
    const Spectrum albedo(0.9f, 0.7f, 0.4f);
    const float ior = 1.5f;
    const SphereBins bins;
    int k = 0;
    const std::vector<Material> materials = {makeMaterial(MaterialType::Mirror, albedo),
                                             makeMaterial(MaterialType::Dielectric, albedo, 0.0f, ior)};
    for (const Material& m : materials) {
        EXPECT_TRUE(isDelta(m)) << m.name;
        for (float theta : {0.0f, 30.0f, 60.0f, 89.0f, 120.0f, 150.0f})
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                const Vec3 wo = directionAtAngle(theta);
                const std::string what = m.name + " θo=" + std::to_string(theta);
                Spectrum expected = albedo;
                if (m.type == MaterialType::Dielectric) {
                    const double etaO = wo.z > 0 ? 1.0 : ior, etaI = wo.z > 0 ? ior : 1.0;
                    const double fr = referenceFresnel(std::abs(wo.z), etaO, etaI);
                    const double s = mode == TransportMode::Radiance ? (etaO * etaO) / (etaI * etaI) : 1.0;
                    for (int c = 0; c < 3; ++c) expected[c] = static_cast<float>(fr + (1 - fr) * albedo[c] * s);
                }
                Rng rng = testRng(800 + k++);
                for (int i = 0; i < 200; ++i) {
                    const auto sample = drawBsdfSample(m, wo, rng, mode);
                    ASSERT_TRUE(sample && sample->delta) << what;
                }
                const Estimate sampled = directionalAlbedo(m, wo, mode, 20000, rng);
                for (int c = 0; c < 3; ++c) {
                    const double evaluated =
                        bins.integral([&](Vec3 wi) { return evalBsdf(m, wo, wi, mode)[c] * std::abs(wi.z); });
                    EXPECT_NEAR(sampled.mean[c] + evaluated, expected[c], 4 * sampled.sigma[c] + 1e-4)
                        << what << " channel " << c << ": sampled " << sampled.mean[c] << ", evaluated " << evaluated;
                }
                EXPECT_LT(bins.integral([&](Vec3 wi) { return pdfBsdf(m, wo, wi); }), 1e-4) << what;
            }
    }
    for (const Material& m : nonDeltaMaterials()) EXPECT_FALSE(isDelta(m)) << m.name;
}

TEST(Bsdf, DielectricTotalInternalReflection) {
    const float ior = 1.5f;
    const Material m = makeMaterial(MaterialType::Dielectric, Spectrum(1.0f), 0.0f, ior);
    const float critical = std::asin(1.0f / ior) * 180.0f / kPi;  // ≈ 41.8°
    Rng rng = testRng(700);
    for (float beyond : {0.5f, 10.0f, 40.0f}) {
        const Vec3 wo = directionAtAngle(180.0f - (critical + beyond));  // inside the glass
        for (int i = 0; i < 1000; ++i) {
            const auto s = drawBsdfSample(m, wo, rng, TransportMode::Radiance);
            ASSERT_TRUE(s.has_value());
            EXPECT_EQ(s->wi, Vec3(-wo.x, -wo.y, wo.z));
            EXPECT_FLOAT_EQ(s->pdf, 1.0f);
            EXPECT_NEAR(s->f.x * std::abs(s->wi.z), 1.0f, 1e-5f);
        }
    }
}

// Rough glass tends to smooth glass: at roughness 0.05 (α = 0.0025) the fraction of importance
// reflected is Fresnel's F(θ), the transmitted weight tint × (1 − F) (radiance: times
// (η_o/η_i)²), and the transmitted directions gather at Snell's; beyond the critical angle all of
// it reflects. The expectations are the closed forms (referenceFresnel, Snell's law), not the
// lobe's code. Catches a refraction half-vector of the wrong sign or index ratio, a Jacobian
// with η on the wrong side, Fresnel at the wrong cosine, and the radiance and importance
// factors swapped.
TEST(Bsdf, RoughGlassTendsToSmoothGlass) {
    const float ior = 1.5f;
    const Spectrum tint(0.9f, 0.7f, 0.5f);
    const Material m = makeMaterial(MaterialType::RoughDielectric, tint, 0.05f, ior);
    const int n = 40000;
    int k = 0;
    for (float theta : {0.0f, 30.0f, 60.0f, 75.0f, 150.0f, 120.0f})
        for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
            const Vec3 wo = directionAtAngle(theta);
            const double etaO = wo.z > 0 ? 1.0 : ior, etaI = wo.z > 0 ? ior : 1.0;
            const double fr = referenceFresnel(std::abs(wo.z), etaO, etaI);
            const double scale = mode == TransportMode::Radiance ? (etaO * etaO) / (etaI * etaI) : 1.0;
            // Snell's direction: tangential part reversed and scaled by η_o/η_i, on the other side.
            const double sinO = std::hypot(wo.x, wo.y), sinI = etaO / etaI * sinO;
            Rng rng = testRng(2700 + k++);
            double reflected = 0, transmitted[3] = {0, 0, 0}, farFromSnell = 0;
            for (int i = 0; i < n; ++i) {
                const auto s = drawBsdfSample(m, wo, rng, mode);
                if (!s) continue;
                const Spectrum w = s->f * (std::abs(s->wi.z) / s->pdf);
                if (s->wi.z * wo.z > 0) {
                    reflected += w.x;
                    continue;
                }
                for (int c = 0; c < 3; ++c) transmitted[c] += w[c];
                const Vec3 snell(float(-wo.x / sinO * sinI), float(-wo.y / sinO * sinI),
                                 float((wo.z > 0 ? -1 : 1) * std::sqrt(std::max(0.0, 1 - sinI * sinI))));
                if (sinO > 0 && dot(s->wi, snell) < 0.99f) ++farFromSnell;
            }
            const std::string what = "θo=" + std::to_string(theta) + (scale == 1.0 ? " importance" : " radiance");
            EXPECT_NEAR(reflected / n, fr, 0.005 + 4 * std::sqrt(fr * (1 - fr) / n)) << what;
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(transmitted[c] / n, tint[c] * (1 - fr) * scale, (0.005 + 4 * std::sqrt(fr / n)) * scale)
                    << what << " channel " << c;
            EXPECT_LT(farFromSnell, 0.002 * n) << what;
        }
}

// An interface of index 1 is no interface: light goes straight on, all of it (tinted), whatever
// the roughness (TransmissionRoughnessTest's "air" row). A glTF mix reaches it where a texture
// lowers the metallic of a material of ior 1; the lobe refracts with index 1.001 there, turning
// light by (1 − 1/η) tan θ' at a facet met at θ', so only samples through facets met within 3.3°
// of grazing (under 0.5 % of them at roughness 1) land over a degree off straight on. What it
// carries is the tint less Smith's masking of the facets: within 3 % at roughness 0.3; at
// roughness 1 the masking takes up to a third at grazing angles (docs/gltf.md), which this test
// does not hold. Catches the lobe evaluated at index 1, where its refraction normal vanishes and
// samples come back with an arbitrary pdf or none.
TEST(Bsdf, RoughGlassOfIndexOneLetsLightStraightThrough) {
    const Spectrum tint(0.9f, 0.7f, 0.5f);
    int k = 0;
    for (float roughness : {0.3f, 1.0f}) {
        Material m = transmissiveMix(tint, 0.0f, roughness, 1.0f);
        m.ior = 1.0f;
        for (float theta : {0.0f, 45.0f, 70.0f, 135.0f}) {
            const Vec3 wo = directionAtAngle(theta);
            Rng rng = testRng(2800 + k++);
            const int n = 20000;
            int produced = 0, bent = 0;
            for (int i = 0; i < n; ++i) {
                const auto s = drawBsdfSample(m, wo, rng, TransportMode::Importance);
                if (!s) continue;
                ++produced;
                if (dot(s->wi, -wo) < std::cos(kPi / 180)) ++bent;
            }
            const std::string what = "r=" + std::to_string(roughness) + " θo=" + std::to_string(theta);
            EXPECT_GT(produced, 0.97 * n) << what;
            EXPECT_LT(bent, 0.005 * n) << what;
            Rng again = testRng(2900 + k);
            const Estimate e = directionalAlbedo(m, wo, TransportMode::Importance, n, again);
            if (roughness < 1)
                for (int c = 0; c < 3; ++c) EXPECT_NEAR(e.mean[c], tint[c], 0.03 * tint[c] + 4 * e.sigma[c]) << what;
        }
    }
}

// KHR_materials_transmission's mix is linear: the directional albedo at metallic m and
// transmission T is m × the conductor's + (1 − m) × ((1 − T) × the plastic's + T × rough
// glass's), each estimated with its own sampler, on both sides of the surface. A lobe choice that
// disagreed with the mixture pdf, or the factor applied to the wrong half, moves it off.
TEST(Bsdf, TransmissionMixesPlasticAndRoughGlassLinearly) {
    int k = 0;
    const Spectrum base(0.9f, 0.5f, 0.2f);
    const TransportMode mode = TransportMode::Importance;
    for (float roughness : {0.2f, 0.7f})
        for (auto [metallic, transmission] : {std::pair{0.0f, 0.5f}, {0.3f, 0.8f}, {0.6f, 0.3f}})
            for (float theta : {0.0f, 60.0f, 85.0f, 130.0f}) {
                const Vec3 wo = directionAtAngle(theta);
                const int n = 40000;
                Rng r1 = testRng(5000 + k), r2 = testRng(6000 + k), r3 = testRng(7000 + k), r4 = testRng(8000 + k);
                ++k;
                const Material mixed = transmissiveMix(base, metallic, roughness, transmission);
                const Estimate e = directionalAlbedo(mixed, wo, mode, n, r1);
                const Estimate metal = directionalAlbedo(makeMaterial(MaterialType::Conductor, base, roughness), wo, mode, n, r2);
                const Estimate plastic = directionalAlbedo(makeMaterial(MaterialType::Plastic, base, roughness), wo, mode, n, r3);
                const Estimate glass =
                    directionalAlbedo(makeMaterial(MaterialType::RoughDielectric, base, roughness), wo, mode, n, r4);
                const float wm = metallic, wp = (1 - metallic) * (1 - transmission), wg = (1 - metallic) * transmission;
                for (int c = 0; c < 3; ++c) {
                    const float expected = wm * metal.mean[c] + wp * plastic.mean[c] + wg * glass.mean[c];
                    const float sigma = std::sqrt(e.sigma[c] * e.sigma[c] + std::pow(wm * metal.sigma[c], 2.0f) +
                                                  std::pow(wp * plastic.sigma[c], 2.0f) + std::pow(wg * glass.sigma[c], 2.0f));
                    EXPECT_NEAR(e.mean[c], expected, 4 * sigma + 1e-4f) << mixed.name << " θo=" << theta << " c=" << c;
                }
            }
}

// The ends of the transmission factor are exactly the opaque mix and rough glass, value and pdf.
TEST(Bsdf, TransmissionEndsAreTheOpaqueMixAndRoughGlass) {
    Rng rng = testRng(4100);
    const Spectrum base(0.8f, 0.4f, 0.3f);
    const Material glass = makeMaterial(MaterialType::RoughDielectric, base, 0.3f);
    const Material opaque = metallicRoughness(base, 0.4f, 0.3f);
    const Material allGlass = transmissiveMix(base, 0.0f, 0.3f, 1.0f), noGlass = transmissiveMix(base, 0.4f, 0.3f, 0.0f);
    for (int i = 0; i < 2000; ++i) {
        const auto [wo, wi] = randomPair(rng, i);
        for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance})
            for (int c = 0; c < 3; ++c) {
                EXPECT_FLOAT_EQ(evalBsdf(allGlass, wo, wi, mode)[c], evalBsdf(glass, wo, wi, mode)[c]);
                EXPECT_FLOAT_EQ(evalBsdf(noGlass, wo, wi, mode)[c], evalBsdf(opaque, wo, wi, mode)[c]);
            }
        EXPECT_FLOAT_EQ(pdfBsdf(allGlass, wo, wi), pdfBsdf(glass, wo, wi));
        EXPECT_FLOAT_EQ(pdfBsdf(noGlass, wo, wi), pdfBsdf(opaque, wo, wi));
    }
}

// White furnace for a perfect conductor (F0 = 1): only Smith masking loses energy, so the albedo
// is ≤ 1 everywhere and ≈ 1 for smooth surfaces away from grazing.
TEST(Bsdf, ConductorWhiteFurnace) {
    int k = 0;
    for (float roughness : {0.0f, 0.05f, 0.2f, 0.5f, 1.0f})
        for (float theta : kAlbedoAngles) {
            const Material m = makeMaterial(MaterialType::Conductor, Spectrum(1.0f), roughness);
            Rng rng = testRng(800 + k++);
            const Estimate e =
                directionalAlbedo(m, directionAtAngle(theta), TransportMode::Radiance, 40000, rng);
            EXPECT_LE(e.mean.x, 1.0f + 4 * e.sigma.x + 1e-5f) << "r=" << roughness << " θo=" << theta;
            const bool smoothAndNotGrazing =
                roughness <= 0.2f && std::abs(std::cos(theta * kPi / 180)) > 0.4f;
            if (smoothAndNotGrazing) {
                EXPECT_GT(e.mean.x, 0.98f) << "r=" << roughness << " θo=" << theta;
            }
            if (roughness == 1.0f) {
                EXPECT_GT(e.mean.x, 0.3f) << "θo=" << theta;  // lossy, but not absurdly so
            }
        }
}

// Plastic: by construction (Kelemen & Szirmay-Kalos 2001) the albedo is E(μo) + a (1 − E(μo)).
// With a white base that is 1 up to the coat table's conservative margin; with a black base it
// is just the coat, which for normal incidence on a smooth coat is Schlick's F0.
TEST(Bsdf, PlasticWhiteFurnaceAndCoat) {
    int k = 0;
    for (float roughness : {0.0f, 0.1f, 0.4f, 1.0f})
        for (float ior : {1.33f, 1.5f, 2.5f})
            for (float theta : kAlbedoAngles) {
                const Vec3 wo = directionAtAngle(theta);
                const Material white = makeMaterial(MaterialType::Plastic, Spectrum(1.0f), roughness, ior);
                Rng rng = testRng(900 + k++);
                const Estimate e = directionalAlbedo(white, wo, TransportMode::Radiance, 20000, rng);
                EXPECT_LE(e.mean.x, 1.0f + 4 * e.sigma.x + 1e-5f) << white.name << " θo=" << theta;
                EXPECT_GT(e.mean.x, 0.985f - 4 * e.sigma.x) << white.name << " θo=" << theta;
            }
    const float ior = 1.5f, f0 = (ior - 1) * (ior - 1) / ((ior + 1) * (ior + 1));
    const Material black = makeMaterial(MaterialType::Plastic, Spectrum(0.0f), 0.0f, ior);
    Rng rng = testRng(999);
    const Estimate coat = directionalAlbedo(black, directionAtAngle(0), TransportMode::Radiance, 20000, rng);
    EXPECT_NEAR(coat.mean.x, f0, 4 * coat.sigma.x + 1e-3f);
}

// Metallic-roughness is linear in metallic: its directional albedo at metallic m is m times the
// conductor's plus 1 − m times the plastic's, each estimated with its own sampler. A mixture pdf
// that disagreed with the sampler's lobe choice, or a mix weighted the wrong way round, would
// move the estimate off that line.
TEST(Bsdf, MetallicRoughnessMixesConductorAndPlasticLinearly) {
    int k = 0;
    const Spectrum base(0.9f, 0.5f, 0.2f);
    for (float roughness : {0.1f, 0.5f, 1.0f})
        for (float metallic : {0.25f, 0.5f, 0.9f})
            for (float theta : {0.0f, 60.0f, 85.0f}) {
                const Vec3 wo = directionAtAngle(theta);
                const int n = 40000;
                Rng r1 = testRng(1000 + k), r2 = testRng(2000 + k), r3 = testRng(3000 + k);
                ++k;
                const Material mixed = metallicRoughness(base, metallic, roughness);
                const Estimate e = directionalAlbedo(mixed, wo, TransportMode::Radiance, n, r1);
                const Estimate metal = directionalAlbedo(makeMaterial(MaterialType::Conductor, base, roughness), wo,
                                                         TransportMode::Radiance, n, r2);
                const Estimate plastic = directionalAlbedo(makeMaterial(MaterialType::Plastic, base, roughness), wo,
                                                           TransportMode::Radiance, n, r3);
                for (int c = 0; c < 3; ++c) {
                    const float expected = metallic * metal.mean[c] + (1 - metallic) * plastic.mean[c];
                    const float sigma = std::sqrt(e.sigma[c] * e.sigma[c] + std::pow(metallic * metal.sigma[c], 2.0f) +
                                                  std::pow((1 - metallic) * plastic.sigma[c], 2.0f));
                    EXPECT_NEAR(e.mean[c], expected, 4 * sigma + 1e-4f) << mixed.name << " θo=" << theta << " c=" << c;
                }
            }
}

// The end points of the mix are exactly the conductor and the plastic, value and pdf.
TEST(Bsdf, MetallicRoughnessEndsAreConductorAndPlastic) {
    Rng rng = testRng(4000);
    const Spectrum base(0.8f, 0.4f, 0.3f);
    for (int i = 0; i < 2000; ++i) {
        const auto [wo, wi] = randomPair(rng, i);
        const Material metal = makeMaterial(MaterialType::Conductor, base, 0.3f);
        const Material plastic = makeMaterial(MaterialType::Plastic, base, 0.3f);
        const Material m1 = metallicRoughness(base, 1.0f, 0.3f), m0 = metallicRoughness(base, 0.0f, 0.3f);
        const TransportMode mode = TransportMode::Radiance;
        for (int c = 0; c < 3; ++c) {
            EXPECT_FLOAT_EQ(evalBsdf(m1, wo, wi, mode)[c], evalBsdf(metal, wo, wi, mode)[c]);
            EXPECT_FLOAT_EQ(evalBsdf(m0, wo, wi, mode)[c], evalBsdf(plastic, wo, wi, mode)[c]);
        }
        EXPECT_FLOAT_EQ(pdfBsdf(m1, wo, wi), pdfBsdf(metal, wo, wi));
        EXPECT_FLOAT_EQ(pdfBsdf(m0, wo, wi), pdfBsdf(plastic, wo, wi));
    }
}

// ---------------------------------------------------------------------------------------------
// Robustness: finite, non-negative values for degenerate inputs

TEST(Bsdf, FiniteForDegenerateDirections) {
    const float tiny = 1e-8f, denormal = 1e-40f;
    const std::vector<Vec3> dirs = {
        {0, 0, 1},
        {0, 0, -1},
        {1, 0, 0},
        {0.6f, 0.8f, 0},
        normalize(Vec3(1, 0, tiny)),
        normalize(Vec3(1, 0, -tiny)),
        Vec3(1, 0, denormal),
        Vec3(0, 1, -denormal),
        normalize(Vec3(1, 1, 1)),
        normalize(Vec3(-1, 1, 1)),
        normalize(Vec3(-1, -1, -1e-3f)),
    };
    std::vector<Material> materials = nonDeltaMaterials();
    materials.push_back(makeMaterial(MaterialType::Mirror, Spectrum(1.0f)));
    materials.push_back(makeMaterial(MaterialType::SmoothConductor, Spectrum(0.5f), 0.0f));
    materials.push_back(makeMaterial(MaterialType::Dielectric, Spectrum(1.0f), 0.0f, 1.5f));
    materials.push_back(makeMaterial(MaterialType::Dielectric, Spectrum(1.0f), 0.0f, 1.0f));
    materials.push_back(makeMaterial(MaterialType::Plastic, Spectrum(1.0f), 0.5f, 1.0f));
    materials.push_back(makeMaterial(MaterialType::Plastic, Spectrum(1.0f), 0.5f, 1e4f));
    materials.push_back(metallicRoughness(Spectrum(1.0f), 0.5f, 0.0f));
    materials.push_back(makeMaterial(MaterialType::RoughDielectric, Spectrum(1.0f), 0.5f, 1.0f));
    materials.push_back(makeMaterial(MaterialType::RoughDielectric, Spectrum(1.0f), 0.0f, 1e4f));
    const std::vector<Vec2> us = {
        {0, 0}, {0.99999994f, 0.99999994f}, {0.5f, 0.25f}, {0.99999994f, 0}, {0, 0.5f}};
    for (const Material& m : materials)
        for (Vec3 wo : dirs) {
            for (Vec3 wi : dirs)
                for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                    const Spectrum f = evalBsdf(m, wo, wi, mode);
                    const float pdf = pdfBsdf(m, wo, wi);
                    ASSERT_TRUE(isFinite(f) && std::isfinite(pdf)) << m.name;
                    ASSERT_GE(std::min({f.x, f.y, f.z, pdf}), 0.0f) << m.name;
                }
            for (Vec2 u : us)
                for (float uc : {0.0f, 0.5f, 0.99999994f})
                    for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                        const auto s = sampleBsdf(m, wo, u, uc, mode);
                        if (!s) continue;
                        ASSERT_TRUE(isFinite(s->f) && isFinite(s->wi) && std::isfinite(s->pdf)) << m.name;
                        ASSERT_GT(s->pdf, 0.0f) << m.name;
                        ASSERT_GE(std::min({s->f.x, s->f.y, s->f.z}), 0.0f) << m.name;
                        ASSERT_NEAR(length(s->wi), 1.0f, 1e-3f) << m.name;
                    }
        }
}

// ---------------------------------------------------------------------------------------------
// Parameter validation

TEST(Bsdf, ValidateAcceptsSensibleMaterials) {
    for (const Material& m : nonDeltaMaterials()) EXPECT_EQ(validateMaterial(m), "") << m.name;
    EXPECT_EQ(validateMaterial(makeMaterial(MaterialType::Dielectric, Spectrum(1.0f), 0.0f, 1.0f)), "");
    Material emitter = makeMaterial(MaterialType::Lambertian, Spectrum(0.0f));
    emitter.emission = Spectrum(17.0f, 12.0f, 4.0f);
    EXPECT_EQ(validateMaterial(emitter), "");
}

TEST(Bsdf, ValidateRejectsBadParameters) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float inf = std::numeric_limits<float>::infinity();
    auto rejects = [](Material m, const std::string& why) {
        const std::string msg = validateMaterial(m);
        EXPECT_FALSE(msg.empty()) << why;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << why;
    };
    for (MaterialType t : {MaterialType::Lambertian, MaterialType::Mirror, MaterialType::SmoothConductor,
                           MaterialType::Dielectric, MaterialType::Conductor, MaterialType::Plastic,
                           MaterialType::MetallicRoughness}) {
        const Material ok = makeMaterial(t, Spectrum(0.5f), 0.5f, 1.5f);
        Material m = ok;
        m.albedo.y = nan;
        rejects(m, "NaN albedo");
        m = ok;
        m.albedo.z = -0.1f;
        rejects(m, "negative albedo");
        m = ok;
        m.albedo.x = 1.2f;
        rejects(m, "albedo > 1");
        m = ok;
        m.emission = Spectrum(1.0f, inf, 1.0f);
        rejects(m, "infinite emission");
        m = ok;
        m.emission = Spectrum(-1.0f);
        rejects(m, "negative emission");
        for (float r : {nan, -0.1f, 1.5f}) {
            m = ok;
            m.roughness = r;
            rejects(m, "roughness " + std::to_string(r));
        }
        for (float metallic : {nan, -0.1f, 1.5f}) {
            m = ok;
            m.metallic = metallic;
            rejects(m, "metallic " + std::to_string(metallic));
        }
        m = ok;
        m.ior = nan;
        rejects(m, "NaN ior");
    }
    for (MaterialType t : {MaterialType::Dielectric, MaterialType::RoughDielectric, MaterialType::Plastic,
                           MaterialType::MetallicRoughness})
        for (float ior : {0.5f, 0.0f, -1.5f, std::numeric_limits<float>::infinity()})
            rejects(makeMaterial(t, Spectrum(0.5f), 0.5f, ior), "ior " + std::to_string(ior));
    for (float transmission : {std::numeric_limits<float>::quiet_NaN(), -0.1f, 1.5f})
        rejects(transmissiveMix(Spectrum(0.5f), 0.2f, 0.5f, transmission), "transmission " + std::to_string(transmission));
    EXPECT_NE(validateMaterial(makeMaterial(MaterialType::Lambertian, Spectrum(-1.0f))).find("negative"),
              std::string::npos);
}

}  // namespace
}  // namespace tripath
