#include "geometry/camera.h"

#include <cmath>

namespace tripath {

Camera::Camera(const CameraDesc& desc, int width, int height)
    : width_(width), height_(height), position_(desc.position), forward_(normalize(desc.forward)) {
    right_ = normalize(cross(forward_, desc.up));
    up_ = cross(right_, forward_);
    tanHalfY_ = std::tan(0.5f * desc.yfov);
    tanHalfX_ = tanHalfY_ * static_cast<float>(width) / static_cast<float>(height);
    area_ = 4.0f * tanHalfX_ * tanHalfY_;
}

Vec3 Camera::direction(Vec2 raster) const {
    const float sx = (2.0f * raster.x / width_ - 1.0f) * tanHalfX_;
    const float sy = (1.0f - 2.0f * raster.y / height_) * tanHalfY_;
    return normalize(forward_ + right_ * sx + up_ * sy);
}

std::optional<Vec2> Camera::raster(Vec3 d) const {
    const float c = dot(d, forward_);
    if (c <= 0) return std::nullopt;
    const float sx = dot(d, right_) / c, sy = dot(d, up_) / c;
    const Vec2 r{(sx / tanHalfX_ + 1.0f) * 0.5f * width_, (1.0f - sy / tanHalfY_) * 0.5f * height_};
    if (!(r.x >= 0 && r.x < width_ && r.y >= 0 && r.y < height_)) return std::nullopt;
    return r;
}

float Camera::importance(Vec3 d) const { return raster(d) ? importanceDensity(d) : 0.0f; }

float Camera::importanceDensity(Vec3 d) const {
    const float c = dot(d, forward_);
    return static_cast<float>(width_) * height_ / (area_ * c * c * c * c);
}

float Camera::imagePdf(Vec3 d) const { return raster(d) ? imageDensity(d) : 0.0f; }

float Camera::imageDensity(Vec3 d) const {
    const float c = dot(d, forward_);
    return 1.0f / (area_ * c * c * c);
}

}  // namespace tripath
