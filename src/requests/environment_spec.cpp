#include "requests/environment_spec.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <optional>

#include "core/error.h"
#include "core/fnv1a.h"
#include "image/image.h"
#include "io/gltf_checks.h"

namespace tripath {

namespace {

// "R,G,B" as three numbers, or nothing if `spec` is not three comma-separated numbers.
std::optional<Spectrum> constantRadiance(const std::string& spec) {
    float v[3];
    const char* p = spec.data();
    const char* end = p + spec.size();
    for (int i = 0; i < 3; ++i) {
        while (p < end && *p == ' ') ++p;
        const auto [stop, ec] = std::from_chars(p, end, v[i]);
        if (ec != std::errc{}) return std::nullopt;
        p = stop;
        while (p < end && *p == ' ') ++p;
        if (i < 2 && (p == end || *p++ != ',')) return std::nullopt;
    }
    if (p != end) return std::nullopt;
    return Spectrum(v[0], v[1], v[2]);
}

bool validRadiance(Spectrum c) { return isFinite(c) && c.x >= 0 && c.y >= 0 && c.z >= 0; }

}  // namespace

EnvironmentDesc loadEnvironment(const std::string& spec, float scale, const WarningSink& warn, size_t maxTexels) {
    if (!std::isfinite(scale) || scale < 0)
        throw InputError(fmt::format("the environment scale {} is not a finite non-negative number", scale));
    EnvironmentDesc d;
    d.source = spec;
    if (const auto c = constantRadiance(spec)) {
        if (!validRadiance(*c))
            throw InputError(fmt::format("the environment radiance {} is negative or not finite", gltf::excerpt(spec)));
        d.width = d.height = 1;
        const float values[3] = {c->x, c->y, c->z};
        d.hash = fnv1a({reinterpret_cast<const char*>(values), sizeof(values)});
        d.texels = {*c * scale};
        return d;
    }
    const Image map = readImage(spec, maxTexels);
    if (map.width != 2 * map.height)
        warn(fmt::format("environment '{}' is {}x{}, not twice as wide as high: it is stretched over the sphere",
                         gltf::excerpt(spec), map.width, map.height));
    d.width = map.width;
    d.height = map.height;
    d.hash = fnv1a({reinterpret_cast<const char*>(map.rgb.data()), map.rgb.size() * sizeof(float)});
    d.texels.reserve(map.pixelCount());
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) {
            const float* t = map.at(x, y);
            const Spectrum c(t[0], t[1], t[2]);
            if (!validRadiance(c))
                throw InputError(fmt::format("environment '{}': texel ({}, {}) is negative or not finite", gltf::excerpt(spec), x, y));
            d.texels.push_back(c * scale);
        }
    return d;
}

}  // namespace tripath
