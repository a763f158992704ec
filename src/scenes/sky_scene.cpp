#include "scenes/sky_scene.h"

#include <algorithm>
#include <cmath>

#include "geometry/environment.h"
#include "geometry/texture.h"
#include "scenes/scene_builder.h"

namespace tripath {

EnvironmentDesc sunAndSky() {
    constexpr int kWidth = 256, kHeight = 128;
    constexpr float kSunRadius = 1.5f * kPi / 180.0f, kSunElevation = 40.0f * kPi / 180.0f;
    const Vec3 sun = normalize(Vec3(0.6f * std::cos(kSunElevation), std::sin(kSunElevation), -0.8f * std::cos(kSunElevation)));
    EnvironmentDesc e;
    e.width = kWidth;
    e.height = kHeight;
    e.source = "built-in sun and sky";
    for (int r = 0; r < kHeight; ++r)
        for (int c = 0; c < kWidth; ++c) {
            const Vec3 d = Environment::directionOf({(c + 0.5f) / kWidth, (r + 0.5f) / kHeight});  // the texel's centre
            Spectrum L;
            if (d.y < 0) {
                L = Spectrum(0.12f, 0.1f, 0.08f);
            } else {
                const float toHorizon = 1.0f - d.y;  // 0 at the zenith, 1 at the horizon
                L = Spectrum(0.25f, 0.45f, 1.0f) * (0.6f + 0.8f * toHorizon * toHorizon);
            }
            if (std::acos(std::clamp(dot(d, sun), -1.0f, 1.0f)) < kSunRadius) L = Spectrum(5000.0f, 4600.0f, 3800.0f);
            e.texels.push_back(L);
        }
    return e;
}

namespace {

// A grey checkerboard of 2 × 2 texels, repeated: the ground's base colour texture (a built-in that
// reads a texture, for the determinism and compiler checks, without an image file).
std::shared_ptr<const MaterialTextures> checkerboard() {
    const Texel dark{0.25f, 0.25f, 0.25f, 1.0f}, light{0.6f, 0.6f, 0.6f, 1.0f};
    auto textures = std::make_shared<MaterialTextures>();
    textures->baseColor.texture = std::make_shared<const Texture>(2, 2, std::vector<Texel>{dark, light, light, dark},
                                                                  TextureWrap::Repeat, TextureWrap::Repeat,
                                                                  TextureFilter::Nearest);
    return textures;
}

}  // namespace

SceneDesc skyScene() {
    using namespace build;
    SceneDesc s;
    s.name = "sky";
    Material ground = lambertian("ground", Spectrum(1.0f));
    ground.textures = checkerboard();
    addSquare(s, "ground", addMaterial(s, ground), {0, 0, 0}, {0, 1, 0}, 6.0f);
    s.meshes.back().texCoords[0] = {{0, 0}, {12, 0}, {12, 12}, {0, 12}};  // a texel a metre
    const int clay = addMaterial(s, lambertian("clay", Spectrum(0.7f, 0.35f, 0.2f)));
    addBox(s, "box", clay, {-1.6f, 0, -0.6f}, {-0.6f, 1.0f, 0.4f}, 0.4f, {-1.1f, 0, -0.1f});
    Material metal;
    metal.name = "rough metal";
    metal.type = MaterialType::Conductor;
    metal.albedo = Spectrum(0.95f, 0.8f, 0.55f);
    metal.roughness = 0.3f;
    addSphere(s, "metal sphere", addMaterial(s, metal), {0.3f, 0.6f, -0.3f}, 0.6f, 48);
    addSphere(s, "glass sphere", addMaterial(s, glass("glass")), {1.4f, 0.4f, 0.6f}, 0.4f, 48);
    s.environment = sunAndSky();
    s.camera = lookAt({0.5f, 1.6f, 4.5f}, {0.1f, 0.45f, 0}, 0.6f);
    return s;
}

}  // namespace tripath
