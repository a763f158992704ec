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

}  // namespace tripath
