#include "geometry/environment.h"

#include <algorithm>
#include <cmath>

namespace tripath {

Environment::Environment(int width, int height, std::vector<Spectrum> texels)
    : width_(width), height_(height), texels_(std::move(texels)), cosTheta_(size_t(height) + 1) {
    for (int r = 0; r <= height_; ++r) cosTheta_[size_t(r)] = std::cos(kPi * float(r) / float(height_));
    cosTheta_.front() = 1.0f;
    cosTheta_.back() = -1.0f;
    std::vector<double> rowWeights(static_cast<size_t>(height_));
    std::vector<double> texelWeights(static_cast<size_t>(width_));
    columns_.reserve(size_t(height_));
    for (int r = 0; r < height_; ++r) {
        double sum = 0;
        for (int c = 0; c < width_; ++c) {
            texelWeights[size_t(c)] = luminance(texels_[size_t(r) * size_t(width_) + size_t(c)]);
            sum += texelWeights[size_t(c)];
        }
        columns_.emplace_back(texelWeights);
        rowWeights[size_t(r)] = sum * texelSolidAngle(r);
        integral_ += rowWeights[size_t(r)];
    }
    rows_ = Distribution1D(rowWeights);
}

double Environment::texelSolidAngle(int row) const {
    return 2.0 * kPi / width_ * (double(cosTheta_[size_t(row)]) - double(cosTheta_[size_t(row) + 1]));
}

Vec2 Environment::uvOf(Vec3 d) {
    const float u = 0.5f + std::atan2(d.x, -d.z) * (0.5f * kInvPi);
    const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) * kInvPi;
    return {u, v};
}

Vec3 Environment::directionOf(Vec2 uv) {
    const float phi = 2.0f * kPi * (uv.x - 0.5f), theta = kPi * uv.y;
    return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

int Environment::texelOf(Vec3 d) const {
    const Vec2 uv = uvOf(d);
    const int c = std::clamp(static_cast<int>(uv.x * float(width_)), 0, width_ - 1);
    const int r = std::clamp(static_cast<int>(uv.y * float(height_)), 0, height_ - 1);
    return r * width_ + c;
}

EnvironmentSample Environment::sample(Vec2 u) const {
    float inRow = 0, inColumn = 0;
    const size_t r = rows_.sample(u.y, inRow);
    const size_t c = columns_[r].sample(u.x, inColumn);
    const float phi = 2.0f * kPi * ((float(c) + inColumn) / float(width_) - 0.5f);
    const float cosTheta = cosTheta_[r] + inRow * (cosTheta_[r + 1] - cosTheta_[r]);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    EnvironmentSample s;
    s.direction = {sinTheta * std::sin(phi), cosTheta, -sinTheta * std::cos(phi)};
    s.pdf = float(double(rows_.probability(r)) * columns_[r].probability(c) / texelSolidAngle(int(r)));
    return s;
}

float Environment::pdf(Vec3 d) const {
    const int texel = texelOf(d);
    const int r = texel / width_, c = texel % width_;
    return float(double(rows_.probability(size_t(r))) * columns_[size_t(r)].probability(size_t(c)) / texelSolidAngle(r));
}

size_t Environment::bytes() const {
    size_t n = texels_.capacity() * sizeof(Spectrum) + cosTheta_.capacity() * sizeof(float) + rows_.bytes();
    for (const Distribution1D& row : columns_) n += sizeof(row) + row.bytes();
    return n;
}

}  // namespace tripath
