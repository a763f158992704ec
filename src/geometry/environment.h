// The environment: radiance arriving from infinitely far away, as an equirectangular
// (latitude-longitude) map of texels, piecewise constant over them. A constant sky is a 1 × 1 map.
//
// Convention. A unit direction d = (x, y, z) toward the sky, in glTF world space (+Y up), reads
//     column u = 0.5 + atan2(x, −z) / (2π),    row v = acos(y) / π,
// u and v in [0, 1) across the image, row 0 at the top (+Y). u = 0.5 is −Z, the direction an
// unrotated glTF camera looks along.
//
// Importance sampling draws a texel in proportion to its luminance times its solid angle (which
// carries the sin θ of the parameterisation: texels near the poles subtend less), then a direction
// uniformly in solid angle inside it: uniform in φ and in cos θ across the texel. The density is
// then constant over each texel, p(ω) = P(texel) / Ω(texel), so a texel's radiance over its
// density is the same wherever in the texel the direction falls.
#pragma once
#include <vector>

#include "core/sampling.h"
#include "core/vec.h"

namespace tripath {

struct EnvironmentSample {
    Vec3 direction;  // unit, toward the sky
    float pdf = 0;   // solid-angle density
};

class Environment {
public:
    // `texels`: width × height linear RGB radiances, row by row from the top; finite, non-negative.
    Environment(int width, int height, std::vector<Spectrum> texels);

    int width() const { return width_; }
    int height() const { return height_; }
    // L(d) for a unit direction d toward the sky.
    Spectrum radiance(Vec3 d) const { return texels_[texelOf(d)]; }
    // A direction in proportion to luminance × solid angle; u in [0, 1)².
    EnvironmentSample sample(Vec2 u) const;
    // The solid-angle density with which sample() produces unit direction d.
    float pdf(Vec3 d) const;
    // ∫ luminance(L(ω)) dω over the sphere, exactly (the map is piecewise constant).
    double luminanceIntegral() const { return integral_; }
    // The solid angle a texel row subtends, per texel.
    double texelSolidAngle(int row) const;
    // The map's (u, v) of a direction, each in [0, 1], and the unit direction of a (u, v).
    static Vec2 uvOf(Vec3 d);
    static Vec3 directionOf(Vec2 uv);
    // The memory its texels and sampling tables take.
    size_t bytes() const;

private:
    int texelOf(Vec3 d) const;

    int width_, height_;
    std::vector<Spectrum> texels_;
    std::vector<float> cosTheta_;          // cos θ at the top edge of each row, and at the bottom: height + 1
    Distribution1D rows_;                  // marginal: a row's luminance × solid angle
    std::vector<Distribution1D> columns_;  // per row: its texels' luminance
    double integral_ = 0;
};

}  // namespace tripath
