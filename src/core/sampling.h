// Warps from the unit square to the domains the path core samples, each with its pdf.
#pragma once
#include <cmath>
#include <vector>

#include "core/vec.h"

namespace tripath {

// Cosine-weighted direction on the hemisphere around +z (Malley's method); pdf = cos θ / π.
inline Vec3 sampleCosineHemisphere(Vec2 u) {
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u.x))};
}
inline float cosineHemispherePdf(float cosTheta) { return std::max(cosTheta, 0.0f) * kInvPi; }

// Uniform direction on the unit sphere; pdf = 1 / 4π.
inline Vec3 sampleUniformSphere(Vec2 u) {
    const float z = 1.0f - 2.0f * u.x;
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
constexpr float kUniformSpherePdf = 1.0f / (4.0f * kPi);

// Uniform direction in the cone of directions within θ_max of +z; pdf = 1 / (2π (1 − cos θ_max)).
inline Vec3 sampleUniformCone(Vec2 u, float cosThetaMax) {
    const float z = 1.0f - u.x * (1.0f - cosThetaMax);
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    const float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniformConePdf(float cosThetaMax) { return 1.0f / (2.0f * kPi * (1.0f - cosThetaMax)); }

// Uniform point on the unit disc (polar, area-preserving); pdf = 1 / π.
inline Vec2 sampleUniformDisc(Vec2 u) {
    const float r = std::sqrt(u.x);
    const float phi = 2.0f * kPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi)};
}

// Uniform barycentrics on a triangle (the square-root parameterisation); pdf = 1 / area.
inline Vec2 sampleUniformTriangle(Vec2 u) {
    const float su = std::sqrt(u.x);
    return {1.0f - su, u.y * su};
}

// Discrete distribution by a cumulative table: sample an index in proportion to its weight.
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(const std::vector<double>& weights);
    bool empty() const { return cdf_.size() < 2; }
    size_t size() const { return cdf_.size() - 1; }
    // Index with probability weight[i] / total; u in [0, 1).
    size_t sample(float u) const;
    // The same index, and where u fell inside its cell, rescaled to [0, 1): a second uniform
    // number for placing a point inside the chosen cell (a piecewise-constant density).
    size_t sample(float u, float& within) const;
    float probability(size_t i) const { return static_cast<float>(cdf_[i + 1] - cdf_[i]); }
    double total() const { return total_; }
    // The memory its table takes.
    size_t bytes() const { return cdf_.capacity() * sizeof(double); }

private:
    std::vector<double> cdf_;
    double total_ = 0;
};

}  // namespace tripath
