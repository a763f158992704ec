#include "scenes/builtin_scenes.h"

#include <fmt/format.h>

#include <cmath>

#include "core/error.h"
#include "scenes/scene_builder.h"
#include "scenes/failure_scenes.h"
#include "scenes/sky_scene.h"

namespace tripath {

namespace {

using namespace build;

// ---- the Cornell box family -------------------------------------------------------------------
// A 2 m box: x ∈ [-1,1] (red left, green right), y ∈ [0,2], z ∈ [-1,1], open at z = +1 where
// the camera looks in. The light is a square just under the ceiling, facing down.

constexpr float kLightHalf = 0.235f;                 // 0.47 m square: the classic proportions
const Spectrum kLightRadiance(17.0f, 12.0f, 4.0f);   // the classic Cornell box light colour

void addCornellWalls(SceneDesc& s) {
    const int white = addMaterial(s, lambertian("white", Spectrum(0.725f, 0.71f, 0.68f)));
    const int red = addMaterial(s, lambertian("red", Spectrum(0.63f, 0.065f, 0.05f)));
    const int green = addMaterial(s, lambertian("green", Spectrum(0.14f, 0.45f, 0.091f)));
    addQuad(s, "floor", white, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1});
    addQuad(s, "ceiling", white, {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1});
    addQuad(s, "back", white, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1});
    addQuad(s, "left", red, {-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1});
    addQuad(s, "right", green, {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1});
    // 39.6° of vertical field (a 35 mm lens), from where the opening just fills it: 2.77 m in
    // front of it, tan(19.8°) · 2.77 = 0.999, so the walls reach every edge of a square image.
    s.camera = CameraDesc{true, {0, 1, 3.77f}, {0, 0, -1}, {0, 1, 0}, 0.6911f};
}

void addCeilingLight(SceneDesc& s, float half, Spectrum radiance) {
    const int light = addMaterial(s, emitter("light", radiance));
    const float y = 1.99f;
    addQuad(s, "light", light, {-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half});
}

void addCornellBoxes(SceneDesc& s) {
    const int white = addMaterial(s, lambertian("box", Spectrum(0.725f, 0.71f, 0.68f)));
    const Vec3 tall(-0.34f, 0.6f, -0.3f), shortBox(0.35f, 0.3f, 0.3f);
    addBox(s, "tall box", white, tall - Vec3(0.3f, 0.6f, 0.3f), tall + Vec3(0.3f, 0.6f, 0.3f), 0.3f, tall);
    addBox(s, "short box", white, shortBox - Vec3(0.3f), shortBox + Vec3(0.3f), -0.3f, shortBox);
}

SceneDesc cornell() {
    SceneDesc s;
    addCornellWalls(s);
    addCeilingLight(s, kLightHalf, kLightRadiance);
    addCornellBoxes(s);
    return s;
}

SceneDesc cornellSpheres() {
    SceneDesc s;
    addCornellWalls(s);
    addCeilingLight(s, kLightHalf, kLightRadiance);
    Material mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    mirror.albedo = Spectrum(0.95f);
    addSphere(s, "mirror sphere", addMaterial(s, mirror), {-0.45f, 0.4f, -0.35f}, 0.4f, 48);
    addSphere(s, "glass sphere", addMaterial(s, glass("glass")), {0.45f, 0.4f, 0.3f}, 0.4f, 48);
    return s;
}

// Same power from a light of 1% of the area: the side shrinks 10×, the radiance grows 100×.
SceneDesc cornellSmall() {
    SceneDesc s;
    addCornellWalls(s);
    addCeilingLight(s, kLightHalf / 10.0f, kLightRadiance * 100.0f);
    addCornellBoxes(s);
    return s;
}

// A point light of the same power as the area light: Φ = π A L = 4π I, so I = A L / 4.
SceneDesc cornellPoint() {
    SceneDesc s;
    addCornellWalls(s);
    addCornellBoxes(s);
    const float area = 4.0f * kLightHalf * kLightHalf;
    s.lights.push_back({{0, 1.9f, 0}, kLightRadiance * (area / 4.0f)});
    return s;
}

// ---- Veach's multiple-importance-sampling scene -----------------------------------------------
// Four metal plates of increasing roughness, each turned so the camera sees the row of four
// spherical lights reflected in it; the lights grow in radius and shrink in radiance so each
// emits the same power. Sampling the BSDF wins on sharp plates with big lights, sampling the
// light wins on rough plates with small lights; MIS must do well on all sixteen (Veach §9.2.1).

SceneDesc veachMis() {
    SceneDesc s;
    // A field of 42°: the row of lights, 9.3 m wide with the largest, 13 m away, fits in a square image.
    s.camera = lookAt({0, 2.5f, 10.0f}, Vec3(0, 2.5f, 10.0f) + Vec3(0, -0.36f, -1), 0.74f);
    const int backdrop = addMaterial(s, lambertian("backdrop", Spectrum(0.2f)));
    addQuad(s, "floor", backdrop, {-10, -3, 6}, {10, -3, 6}, {10, -3, -8}, {-10, -3, -8});
    addQuad(s, "wall", backdrop, {-10, -3, -8}, {10, -3, -8}, {10, 8, -8}, {-10, 8, -8});

    const Vec3 lightRow(0, 1.5f, -3.5f);
    const float radii[4] = {0.03f, 0.1f, 0.3f, 0.9f};
    for (int i = 0; i < 4; ++i) {
        const float le = 4.0f * (0.1f * 0.1f) / (radii[i] * radii[i]) * 25.0f;  // equal power: L ∝ 1/r²
        const int m = addMaterial(s, emitter(fmt::format("light {}", i).c_str(), Spectrum(le)));
        addSphere(s, "light sphere", m, lightRow + Vec3(-3.75f + 2.5f * i, 0, 0), radii[i], 16);
    }
    const float roughness[4] = {0.1f, 0.2f, 0.35f, 0.5f};
    const float plateY[4] = {-1.9f, -1.35f, -0.75f, -0.1f};
    const float plateZ[4] = {3.4f, 2.3f, 1.2f, 0.1f};
    for (int i = 0; i < 4; ++i) {
        Material metal;
        metal.name = fmt::format("plate {}", i);
        metal.type = MaterialType::Conductor;
        metal.albedo = Spectrum(0.9f);
        metal.roughness = roughness[i];
        const int m = addMaterial(s, metal);
        const Vec3 c(0, plateY[i], plateZ[i]);
        // The plate's normal bisects the directions to the camera and to the light row.
        const Vec3 n = normalize(normalize(s.camera.position - c) + normalize(lightRow - c));
        const Vec3 u(1, 0, 0), v = normalize(cross(n, u));
        const Vec3 a = u * 4.5f, b = v * 0.5f;
        addQuad(s, "plate", m, c - a - b, c + a - b, c + a + b, c - a + b);
    }
    return s;
}

// ---- SmallVCM's scene 5 -------------------------------------------------------------------------
// The scene we compare the bidirectional family against SmallVCM on (bench/peers-smallvcm.sh;
// bench/README.md, "Peers: SmallVCM"): its Cornell box with the light box under the ceiling and both
// small spheres, which SmallVCM builds from the flags kLightCeiling | kBothSmallSpheres. Rebuilt
// here from the numbers its scene description gives, in its own frame (z up, the camera looking
// along +y), so an image of ours and one of SmallVCM's line up pixel for pixel: right is
// forward × up and raster y grows downwards in both. Differences that cannot show in an image:
// SmallVCM's Lambertian walls are one-sided and ours two-sided, but the camera and every light
// path see only the inner faces (the box is open towards the camera only, and nothing outside it
// sends light back); its spheres are analytic and ours are 16k triangles each with smooth normals
// (the facets are at most 0.15 mm inside the true sphere).

SceneDesc smallVcm5() {
    SceneDesc s;
    const int white = addMaterial(s, lambertian("white", Spectrum(0.803922f)));
    const int green = addMaterial(s, lambertian("green", Spectrum(0.156863f, 0.803922f, 0.172549f)));
    const int red = addMaterial(s, lambertian("red", Spectrum(0.803922f, 0.152941f, 0.152941f)));

    // The box, open at y = y0 (towards the camera); every wall faces inwards.
    const float x0 = -1.27029f, x1 = 1.28975f, y0 = -1.25549f, y1 = 1.30455f, z0 = -1.28002f, z1 = 1.28002f;
    addQuad(s, "floor", white, {x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0});
    addQuad(s, "ceiling", white, {x0, y0, z1}, {x0, y1, z1}, {x1, y1, z1}, {x1, y0, z1});
    addQuad(s, "back", white, {x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1});
    addQuad(s, "left", green, {x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1});
    addQuad(s, "right", red, {x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0});

    // The light box: a 0.5 m square emitting downwards 2 cm under the ceiling, closed up to the
    // ceiling by four white sides that face outwards (its top is the room's ceiling).
    const float h = 0.25f, zl = 1.26002f;
    const int light = addMaterial(s, emitter("light", Spectrum(25.03329895614464f)));
    addQuad(s, "light", light, {-h, -h, zl}, {-h, h, zl}, {h, h, zl}, {h, -h, zl});
    addQuad(s, "light box back", white, {-h, h, zl}, {-h, h, z1}, {h, h, z1}, {h, h, zl});
    addQuad(s, "light box front", white, {-h, -h, zl}, {h, -h, zl}, {h, -h, z1}, {-h, -h, z1});
    addQuad(s, "light box left", white, {-h, -h, zl}, {-h, -h, z1}, {-h, h, z1}, {-h, h, zl});
    addQuad(s, "light box right", white, {h, -h, zl}, {h, h, zl}, {h, h, z1}, {h, -h, z1});

    // Spheres of radius 0.5 resting on the floor, midway between the front and back walls, their
    // centres 2/7 of the box's width in from the side walls: mirror left, glass right.
    const float r = 0.5f, inset = 2.0f * (x1 - x0) / 7.0f, yc = 0.5f * (y0 + y1), zc = z0 + r;
    Material mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    mirror.albedo = Spectrum(1.0f);
    Material glassBall = glass("glass");
    glassBall.ior = 1.6f;
    constexpr int kRings = 64;  // 16,128 triangles per sphere
    addSphere(s, "mirror sphere", addMaterial(s, mirror), {x0 + inset, yc, zc}, r, kRings);
    addSphere(s, "glass sphere", addMaterial(s, glassBall), {x1 - inset, yc, zc}, r, kRings);

    // The pinhole: SmallVCM's position, forward and up, made orthonormal the way it does it
    // (right = forward × up, then up = right × forward); 45 degrees across the (square) image.
    const Vec3 forward = normalize(Vec3(0.00688625f, 0.998505f, -0.0542161f));
    const Vec3 right = normalize(cross(forward, Vec3(3.73896e-4f, 0.0542148f, 0.998529f)));
    s.camera = CameraDesc{true, {-0.0439815f, -4.12529f, 0.222539f}, forward, cross(right, forward),
                          45.0f * kPi / 180.0f};
    return s;
}

struct Entry {
    BuiltinInfo info;
    SceneDesc (*make)();
};

SceneDesc furnaceDefault() { return furnaceScene(0.5f, 1.0f); }
SceneDesc furnaceHigh() { return furnaceScene(0.9f, 1.0f); }

const std::vector<Entry>& entries() {
    static const std::vector<Entry> all = {
        {{"cornell", "classic diffuse Cornell box: square light under the ceiling, a tall and a short box"}, cornell},
        {{"cornell-spheres", "Cornell box with a mirror and a glass sphere instead of the boxes (caustics)"}, cornellSpheres},
        {{"cornell-small", "Cornell box lit by a light of 1% of the area and the same power"}, cornellSmall},
        {{"cornell-point", "Cornell box lit by a point light of the same power"}, cornellPoint},
        {{"furnace", "white furnace: closed sphere, albedo 0.5, emission 1; radiance is 2 everywhere"}, furnaceDefault},
        {{"furnace-0.9", "white furnace with albedo 0.9, emission 1; radiance is 10 everywhere"}, furnaceHigh},
        {{"veach-mis", "four metal plates of increasing roughness, four spherical lights of equal power"}, veachMis},
        {{"sky", "a box, a metal and a glass sphere on a checkered ground under a sky with a small bright sun (environment only)"}, skyScene},
        {{"smallvcm-5", "SmallVCM's scene 5: its Cornell box with a light box, a mirror and a glass sphere (peer comparison)"}, smallVcm5},
        // Scenes where methods fail for known reasons (failure_scenes.h, docs/failures.md).
        {{"caustic", "glass ball focusing a small area light onto a diffuse floor (pt noisy; lt, bdpt good)"}, causticScene},
        {{"caustic-point", "the caustic lit by a point light: pt cannot sample it (black)"}, causticPointScene},
        {{"sds", "the caustic seen through a glass pane (specular-diffuse-specular); lt cannot see through it"}, sdsScene},
        {{"sds-point", "sds with a point light: no integrator can sample the caustic through the pane"}, sdsPointScene},
        {{"sds-mirrors", "point light, floor mirror, diffuse panel seen in a wall mirror: analytic; only vcm, bpm, ppm see it"}, sdsMirrorsScene},
        {{"door-ajar", "a room lit only through the gap of a door ajar from a light in the next room"}, doorAjarScene},
        {{"contact", "boxes with faces inside the walls, a thin slab 1e-4 above the floor"}, contactScene},
        {{"grazing", "camera and light at 89.9 degrees to a glossy metal plane"}, grazingScene},
        {{"degenerate", "albedo-1 walls, zero-area and needle triangles, zero-area and needle emitters"}, degenerateScene},
        {{"degenerate-tiny", "a 1 mm cube in a 10 km scene"}, degenerateTinyScene},
        {{"degenerate-far", "the Cornell box scaled 500x at coordinates near 1e6"}, degenerateFarScene},
    };
    return all;
}

}  // namespace

SceneDesc furnaceScene(float albedo, float emittedRadiance) {
    SceneDesc s;
    Material m = lambertian("furnace", Spectrum(albedo));
    m.emission = Spectrum(emittedRadiance);
    m.twoSidedEmission = true;
    // Flat facets: shading normals would bend the albedo away from a, and the identity
    // L = Le + a L holds for any closed shape, so the polyhedron is exact.
    addSphere(s, "sphere", addMaterial(s, m), {0, 0, 0}, 1.0f, 24, true, true);
    s.camera = CameraDesc{true, {0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1.2f};
    return s;
}

SceneDesc cornellTessellated(size_t triangles) {
    SceneDesc s = cornell();
    if (triangles <= 36) return s;
    s.meshes.resize(s.meshes.size() - 2);  // drop the two boxes (24 triangles) for one fine sphere
    const size_t remaining = triangles - 12 - 2;  // walls (10) and light (2)
    const int rings = std::max(2, static_cast<int>(std::lround(std::sqrt(remaining / 4.0))));
    addSphere(s, "tessellated sphere", 0, {0, 0.5f, 0}, 0.5f, rings);  // material 0: white
    s.name = fmt::format("cornell-{}tris", triangles);
    return s;
}

const std::vector<BuiltinInfo>& builtinScenes() {
    static const std::vector<BuiltinInfo> infos = [] {
        std::vector<BuiltinInfo> v;
        for (const Entry& e : entries()) v.push_back(e.info);
        return v;
    }();
    return infos;
}

bool isBuiltinScene(const std::string& name) {
    for (const Entry& e : entries())
        if (e.info.name == name) return true;
    return false;
}

SceneDesc builtinScene(const std::string& name) {
    for (const Entry& e : entries())
        if (e.info.name == name) {
            SceneDesc s = e.make();
            s.name = name;
            return s;
        }
    throw InputError(fmt::format("unknown built-in scene '{}' (see `tripath scenes`)", name));
}

}  // namespace tripath
