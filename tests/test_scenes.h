// Scenes made for the tests, beside the built-in ones: the emitters and materials the glTF loader
// accepts that no built-in scene combines. Any material may emit (glTF puts emissiveFactor on
// every material), so an emitter can be a mirror, a pane of glass or a rough metal: a camera walk
// scatters off such a point, yet the same point is x0 of the path that ends there (mis.h).
#pragma once
#include "scenes/builtin_scenes.h"
#include "scenes/scene_builder.h"

namespace tripath::test {

// The Cornell box whose ceiling light is made of `type` (mirror, smooth conductor or glass:
// smooth; conductor: roughness 0.3), grey, still emitting the same radiance. The camera looks down at the floor and
// the boxes, so the emitter itself is never seen directly: light tracing can then estimate every
// pixel, and all three integrators must agree.
inline SceneDesc cornellEmissive(MaterialType type) {
    SceneDesc s = builtinScene("cornell");
    for (Material& m : s.materials) {
        if (m.name != "light") continue;
        m.type = type;
        m.albedo = Spectrum(type == MaterialType::Dielectric ? 1.0f : 0.5f);
        m.roughness = type == MaterialType::Conductor ? 0.3f : 0.0f;
    }
    s.camera = build::lookAt({0, 1.2f, 3.9f}, {0, 0.35f, 0}, 0.45f);
    s.name = std::string("cornell with an emissive ") + materialTypeName(type) + " light";
    return s;
}

// Every material type and every emitter kind in one box, for the oracles (brute-force MIS, f/p):
// Lambertian walls; the ceiling light an emissive mirror; an emissive, absorbing glass box; a two-sided
// emissive rough-metal panel; a coarse smooth-shaded plastic sphere (shading normals far from the
// geometric ones at its silhouette); a one-sided Lambertian emitter on the back wall; a point light.
inline SceneDesc everyEmitterKind() {
    using namespace build;
    SceneDesc s = cornellEmissive(MaterialType::Mirror);
    Material glassLight = glass("emissive glass");
    glassLight.emission = Spectrum(2.0f, 3.0f, 4.0f);
    glassLight.absorption = Spectrum(0.5f, 1.0f, 2.0f);  // light inside it fades (KHR_materials_volume)
    addBox(s, "glass box", addMaterial(s, glassLight), {0.2f, 0.0f, 0.1f}, {0.6f, 0.5f, 0.5f}, 0.4f, {0.4f, 0, 0.3f});
    Material metal;
    metal.name = "emissive metal";
    metal.type = MaterialType::Conductor;
    metal.albedo = Spectrum(0.9f, 0.6f, 0.3f);
    metal.roughness = 0.3f;
    metal.emission = Spectrum(3.0f);
    metal.twoSidedEmission = true;
    addSquare(s, "metal panel", addMaterial(s, metal), {0.95f, 1.2f, -0.4f}, normalize(Vec3(-1, 0, 0.3f)), 0.2f);
    Material plastic;
    plastic.name = "plastic";
    plastic.type = MaterialType::Plastic;
    plastic.albedo = Spectrum(0.2f, 0.5f, 0.8f);
    plastic.roughness = 0.4f;
    addSphere(s, "smooth sphere", addMaterial(s, plastic), {-0.45f, 0.35f, 0.1f}, 0.35f, 6);
    addSquare(s, "back light", addMaterial(s, emitter("back light", Spectrum(4.0f))), {-0.5f, 1.5f, -0.99f},
              {0, 0, 1}, 0.1f);
    s.lights.push_back({{0.3f, 1.6f, 0.4f}, Spectrum(0.5f)});
    s.camera = CameraDesc{true, {0, 1, 3.9f}, {0, 0, -1}, {0, 1, 0}, 0.6911f};
    s.name = "every emitter kind";
    return s;
}

// Rough glass in the Cornell box (Walter et al.'s BTDF, on every kind of surface the loader makes
// of KHR_materials_transmission): an emissive, absorbing frosted box (light refracted out of it,
// attenuated inside it, and x0 of paths that end on it); a coarse smooth-shaded rough glass
// sphere of another index (refraction about shading normals far from the geometric ones at its
// silhouette), rough enough (0.4) that a light tracer finds its lobes toward the pinhole without
// a heavy tail (at 0.15, lt's run-to-run error under it was 17 % of the mean at 256 spp); and a
// panel of glTF's mix, metallic 0.2 and transmission 0.6.
inline SceneDesc roughGlass() {
    using namespace build;
    SceneDesc s = builtinScene("cornell");
    Material frosted = glass("frosted box");
    frosted.type = MaterialType::RoughDielectric;
    frosted.roughness = 0.3f;
    frosted.albedo = Spectrum(0.9f, 0.8f, 0.6f);
    frosted.absorption = Spectrum(0.5f, 1.0f, 2.0f);
    frosted.emission = Spectrum(0.5f, 0.3f, 0.2f);
    addBox(s, "frosted box", addMaterial(s, frosted), {0.2f, 0.0f, 0.1f}, {0.6f, 0.5f, 0.5f}, 0.4f, {0.4f, 0, 0.3f});
    Material ball = glass("rough sphere");
    ball.type = MaterialType::RoughDielectric;
    ball.roughness = 0.4f;
    ball.ior = 1.33f;
    addSphere(s, "rough sphere", addMaterial(s, ball), {-0.45f, 0.35f, 0.1f}, 0.35f, 6);
    Material mix;
    mix.name = "partly transmissive panel";
    mix.type = MaterialType::MetallicRoughness;
    mix.albedo = Spectrum(0.8f, 0.6f, 0.4f);
    mix.roughness = 0.4f;
    mix.metallic = 0.2f;
    mix.transmission = 0.6f;
    addSquare(s, "mixed panel", addMaterial(s, mix), {0.6f, 1.2f, -0.4f}, normalize(Vec3(-1, 0, 0.3f)), 0.25f);
    s.name = "rough glass";
    return s;
}

// A wall whose shading normals lean 45° off its geometric normal (as at the silhouette of a
// coarse smooth mesh), seen from the front, with the only emitter behind it: the wall's front
// receives no light, so every pixel is exactly 0. Without a leak mask, directions toward the
// emitter lie above the shading plane though they pass through the wall, and light leaks.
inline SceneDesc lightBehindASmoothShadedWall() {
    using namespace build;
    SceneDesc s;
    const int white = addMaterial(s, lambertian("wall", Spectrum(0.8f)));
    const Vec3 ns = normalize(Vec3(1, 0, 1));
    s.meshes.push_back(MeshDesc{"wall", {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}}, {ns, ns, ns, ns},
                                {0, 1, 2, 0, 2, 3}, white});
    Material light = emitter("light behind", Spectrum(50.0f));
    light.twoSidedEmission = true;
    addSquare(s, "light behind", addMaterial(s, light), {1.5f, 0, -1.0f}, normalize(Vec3(-1, 0, 0.2f)), 0.5f);
    s.camera = lookAt({0, 0, 3}, {0, 0, 0}, 0.6f);
    s.name = "light behind a smooth-shaded wall";
    return s;
}

// A small sky for the tests: 16 × 8 texels of a colour that varies across the map (so that a
// flipped u or v changes what a surface receives), with one bright "sun" texel 400 times the rest,
// where importance sampling matters.
inline EnvironmentDesc testSky() {
    EnvironmentDesc e;
    e.width = 16;
    e.height = 8;
    for (int r = 0; r < e.height; ++r)
        for (int c = 0; c < e.width; ++c)
            e.texels.push_back(Spectrum(0.2f + 0.05f * float(c), 0.3f + 0.1f * float(r), 0.5f));
    e.texels[2 * 16 + 11] = Spectrum(200.0f, 180.0f, 150.0f);
    e.source = "test sky";
    return e;
}

// everyEmitterKind under the sky as well: the test sky, a directional light and a spot shining in
// through the box's open front, so that paths start or end at infinity and on every punctual kind.
inline SceneDesc everyEmitterKindUnderTheSky() {
    SceneDesc s = everyEmitterKind();
    s.environment = testSky();
    LightDesc sun;
    sun.kind = LightDesc::Kind::Directional;
    sun.direction = normalize(Vec3(0.2f, -0.5f, -1.0f));
    sun.intensity = Spectrum(1.5f, 1.4f, 1.2f);
    s.lights.push_back(sun);
    LightDesc spot;
    spot.kind = LightDesc::Kind::Spot;
    spot.position = {-0.4f, 1.7f, 0.3f};
    spot.direction = normalize(Vec3(0.3f, -1.0f, -0.2f));
    spot.intensity = Spectrum(2.0f);
    spot.innerConeAngle = 0.3f;
    spot.outerConeAngle = 0.7f;
    s.lights.push_back(spot);
    s.name = "every emitter kind under the sky";
    return s;
}

}  // namespace tripath::test
