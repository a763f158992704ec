// Pinhole sensor: the camera end of every path (docs/design.md §1).
//
// The sensor is a point (a delta in position), so no path can hit it by chance: light subpaths
// reach it only by connection (strategy t=1). Its importance for pixel j is
//     W_j(ω) = N / (A cos⁴θ)   for ω through pixel j,  0 otherwise,
// where A is the image-plane area at unit distance and N the number of pixels: the cos⁴ is the
// familiar pinhole falloff (one cos for the sensor's cosine, which the last ρ or ε carries, and
// cos³ from mapping image-plane area to solid angle). ∫ W_j cos θ dω = 1 over pixel j, so a pixel
// measures the average radiance arriving through it.
#pragma once
#include <optional>

#include "geometry/scene_desc.h"
#include "core/vec.h"

namespace tripath {

class Camera {
public:
    Camera(const CameraDesc& desc, int width, int height);

    int width() const { return width_; }
    int height() const { return height_; }
    Vec3 position() const { return position_; }
    Vec3 forward() const { return forward_; }

    // Unit direction through raster position (x, y) in [0,width)×[0,height), origin top-left.
    Vec3 direction(Vec2 raster) const;
    // Raster position where direction `d` (unit) crosses the image, if it does.
    std::optional<Vec2> raster(Vec3 d) const;
    // |cos θ| between the optical axis and unit direction d: the sensor's cosine factor.
    float cosTheta(Vec3 d) const { return std::abs(dot(d, forward_)); }

    // Per-pixel importance W_j(ω) for the pixel that d passes through (zero outside the image).
    float importance(Vec3 d) const;
    // The same formula, N / (A cos⁴θ), without asking whether d crosses the image (see imageDensity).
    float importanceDensity(Vec3 d) const;
    // Solid-angle density of a direction sampled uniformly over the whole image, 1 / (A cos³θ);
    // over one pixel it is N times that. Zero outside the image.
    float imagePdf(Vec3 d) const;
    // The same formula for any d in front of the camera, without asking whether d crosses the
    // image: for directions the camera generated, which rounding may put just outside it.
    float imageDensity(Vec3 d) const;
    // The density of d when the camera samples a point of one pixel uniformly (as it does for
    // every camera subpath): the whole image's density times the pixel count N, unchecked as above.
    float pixelDensity(Vec3 d) const { return float(width_) * float(height_) * imageDensity(d); }

private:
    int width_, height_;
    Vec3 position_, forward_, right_, up_;
    float tanHalfY_, tanHalfX_;  // image-plane half extents at unit distance
    float area_;                  // image-plane area at unit distance, A
};

// Inline: every connection to the sensor asks these (store forwarding: docs/performance-notes.md).
inline std::optional<Vec2> Camera::raster(Vec3 d) const {
    const float c = dot(d, forward_);
    if (c <= 0) return std::nullopt;
    const float sx = dot(d, right_) / c, sy = dot(d, up_) / c;
    const Vec2 r{(sx / tanHalfX_ + 1.0f) * 0.5f * width_, (1.0f - sy / tanHalfY_) * 0.5f * height_};
    if (!(r.x >= 0 && r.x < width_ && r.y >= 0 && r.y < height_)) return std::nullopt;
    return r;
}

inline float Camera::importance(Vec3 d) const { return raster(d) ? importanceDensity(d) : 0.0f; }

inline float Camera::importanceDensity(Vec3 d) const {
    const float c = dot(d, forward_);
    return static_cast<float>(width_) * height_ / (area_ * c * c * c * c);
}

inline float Camera::imagePdf(Vec3 d) const { return raster(d) ? imageDensity(d) : 0.0f; }

inline float Camera::imageDensity(Vec3 d) const {
    const float c = dot(d, forward_);
    return 1.0f / (area_ * c * c * c);
}

}  // namespace tripath
