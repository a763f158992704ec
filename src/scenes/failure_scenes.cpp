// The failure scenes of failure_scenes.h, top to bottom, from the blocks of scene_builder.h.
#include "scenes/failure_scenes.h"

#include <cmath>

#include "scenes/scene_builder.h"

namespace tripath {

namespace {

using namespace build;

// ---- caustics ---------------------------------------------------------------------------------
// Ball of radius 0.5 and index 1.5: focal length n r / (2 (n − 1)) = 0.75 from its centre. With
// the light 3.4 m away the image forms 0.96 m behind the centre; the floor is 0.85 m away along
// the axis, a little before the focus, so the caustic is a bright spot ~0.2 m across.

const Vec3 kBallCentre(0.0f, 0.6f, 0.0f);
constexpr float kBallRadius = 0.5f;
const Vec3 kCausticLight(-2.4f, 3.0f, 0.0f);
constexpr float kCausticLightHalf = 0.05f;       // a 10 cm square
constexpr float kCausticRadiance = 5000.0f;      // the floor under the light reads about 1
const Spectrum kFloorAlbedo(0.7f);

// The parts the four caustic scenes share: floor, back wall, ball and camera; no light.
SceneDesc causticStage() {
    SceneDesc s;
    const int floor = addMaterial(s, lambertian("floor", kFloorAlbedo));
    addQuad(s, "floor", floor, {-4, 0, 4}, {4, 0, 4}, {4, 0, -4}, {-4, 0, -4});
    const int wall = addMaterial(s, lambertian("back wall", Spectrum(0.5f)));
    addQuad(s, "back wall", wall, {-4, 0, -2}, {4, 0, -2}, {4, 4, -2}, {-4, 4, -2});
    addSphere(s, "glass ball", addMaterial(s, glass("glass")), kBallCentre, kBallRadius, 24);
    s.camera = lookAt({0.9f, 1.5f, 2.8f}, {0.2f, 0.3f, 0.0f}, 0.75f);
    return s;
}

void addSmallLight(SceneDesc& s) {
    const int light = addMaterial(s, emitter("small light", Spectrum(kCausticRadiance)));
    addSquare(s, "small light", light, kCausticLight, normalize(kBallCentre - kCausticLight), kCausticLightHalf);
}

// The same intensity toward the ball as the square light: I = L · A along its normal.
void addCausticPointLight(SceneDesc& s) {
    const float area = 4.0f * kCausticLightHalf * kCausticLightHalf;
    s.lights.push_back({kCausticLight, Spectrum(kCausticRadiance * area)});
}

}  // namespace

Vec3 causticCentre() {
    const Vec3 d = kBallCentre - kCausticLight;
    return kCausticLight + d * (kCausticLight.y / -d.y);
}

SceneDesc causticScene() {
    SceneDesc s = causticStage();
    addSmallLight(s);
    return s;
}

SceneDesc causticPointScene() {
    SceneDesc s = causticStage();
    addCausticPointLight(s);
    return s;
}

// ---- specular-diffuse-specular ---------------------------------------------------------------

namespace {

// A 2 cm glass pane standing between the camera and the caustic (and clear of the light's
// way to the ball), as a closed box so that rays enter and leave it.
void addPane(SceneDesc& s) {
    const int pane = addMaterial(s, glass("pane"));
    const Vec3 c = causticCentre();
    addBox(s, "glass pane", pane, {c.x - 0.45f, 0.0f, 0.8f}, {c.x + 0.55f, 0.7f, 0.82f});
}

}  // namespace

SceneDesc sdsScene() {
    SceneDesc s = causticStage();
    addSmallLight(s);
    addPane(s);
    return s;
}

SceneDesc sdsPointScene() {
    SceneDesc s = causticStage();
    addCausticPointLight(s);
    addPane(s);
    return s;
}

// ---- an analytic specular-diffuse-specular path ------------------------------------------------

SceneDesc sdsMirrorsScene() {
    const SdsMirrorsLayout& k = kSdsMirrors;
    SceneDesc s;
    // The hood, black so that it sends nothing on. Its walls reach 1 cm past the corners and past
    // the top, so that no ray from the light slips through a crack where two quads meet; the
    // walls' bottom edges bound the opening.
    const int black = addMaterial(s, lambertian("black hood", Spectrum(0.0f)));
    const float hx = k.hoodHalfX, hz = k.hoodHalfZ, lo = k.hoodBottom, top = k.hoodTop, o = 0.01f;
    addQuad(s, "hood top", black, {-hx - o, top, -hz - o}, {hx + o, top, -hz - o}, {hx + o, top, hz + o},
            {-hx - o, top, hz + o});
    addQuad(s, "hood -x", black, {-hx, lo, -hz - o}, {-hx, lo, hz + o}, {-hx, top + o, hz + o}, {-hx, top + o, -hz - o});
    addQuad(s, "hood +x", black, {hx, lo, hz + o}, {hx, lo, -hz - o}, {hx, top + o, -hz - o}, {hx, top + o, hz + o});
    addQuad(s, "hood -z", black, {hx + o, lo, -hz}, {-hx - o, lo, -hz}, {-hx - o, top + o, -hz}, {hx + o, top + o, -hz});
    addQuad(s, "hood +z", black, {-hx - o, lo, hz}, {hx + o, lo, hz}, {hx + o, top + o, hz}, {-hx - o, top + o, hz});
    s.lights.push_back({k.light, Spectrum(k.intensity)});

    Material floorMirror;
    floorMirror.name = "floor mirror";
    floorMirror.type = MaterialType::Mirror;
    floorMirror.albedo = Spectrum(k.floorReflectance);
    const float fz = k.floorHalfZ;
    addQuad(s, "floor mirror", addMaterial(s, floorMirror), {k.floorX0, 0, fz}, {k.floorX1, 0, fz},
            {k.floorX1, 0, -fz}, {k.floorX0, 0, -fz});

    const int panel = addMaterial(s, lambertian("panel", Spectrum(k.panelAlbedo)));
    const float px = k.panelX, pz = k.panelHalfZ;
    addQuad(s, "panel", panel, {px, k.panelY0, -pz}, {px, k.panelY0, pz}, {px, k.panelY1, pz}, {px, k.panelY1, -pz});

    Material wallMirror;
    wallMirror.name = "wall mirror";
    wallMirror.type = MaterialType::Mirror;
    wallMirror.albedo = Spectrum(k.wallReflectance);
    addQuad(s, "wall mirror", addMaterial(s, wallMirror), {k.wallX0, k.wallY0, k.wallZ}, {k.wallX1, k.wallY0, k.wallZ},
            {k.wallX1, k.wallY1, k.wallZ}, {k.wallX0, k.wallY1, k.wallZ});

    s.camera = lookAt(k.camera, k.cameraTarget, k.cameraYfov);
    return s;
}

// ---- visibility ----------------------------------------------------------------------------
// Room A (camera): x ∈ [-4, 0]; room B (light): x ∈ [0.1, 4]; both y ∈ [0, 2.5], z ∈ [-2, 2].
// The shared wall x ∈ [0, 0.1] has a doorway z ∈ [-0.5, 0.5], y ∈ [0, 2]; the door (1 × 2 m,
// 4 cm thick) hangs on a hinge at the room-B face of the wall and stands open 4° into room B,
// leaving a wedge that is 7 cm wide at its free edge: the only way from one room to the other.

SceneDesc doorAjarScene() {
    SceneDesc s;
    const int white = addMaterial(s, lambertian("walls", Spectrum(0.75f)));
    const int floorA = addMaterial(s, lambertian("floor A", Spectrum(0.6f, 0.5f, 0.4f)));
    const int door = addMaterial(s, lambertian("door", Spectrum(0.5f, 0.3f, 0.2f)));
    // The outer shell, seen from inside (materials are two-sided: one quad per face suffices).
    addQuad(s, "floor", floorA, {-4, 0, 2}, {4, 0, 2}, {4, 0, -2}, {-4, 0, -2});
    addQuad(s, "ceiling", white, {-4, 2.5f, -2}, {4, 2.5f, -2}, {4, 2.5f, 2}, {-4, 2.5f, 2});
    addQuad(s, "back", white, {-4, 0, -2}, {4, 0, -2}, {4, 2.5f, -2}, {-4, 2.5f, -2});
    addQuad(s, "front", white, {4, 0, 2}, {-4, 0, 2}, {-4, 2.5f, 2}, {4, 2.5f, 2});
    addQuad(s, "left", white, {-4, 0, 2}, {-4, 0, -2}, {-4, 2.5f, -2}, {-4, 2.5f, 2});
    addQuad(s, "right", white, {4, 0, -2}, {4, 0, 2}, {4, 2.5f, 2}, {4, 2.5f, -2});
    // The dividing wall around the doorway: two side pieces and the lintel.
    addBox(s, "wall south", white, {0, 0, -2}, {0.1f, 2.5f, -0.5f});
    addBox(s, "wall north", white, {0, 0, 0.5f}, {0.1f, 2.5f, 2});
    addBox(s, "lintel", white, {0, 2.0f, -0.5f}, {0.1f, 2.5f, 0.5f});
    // The door: closed, it would cover the doorway from the room-B side; turning it by 4° about
    // the hinge at (0.1, -0.5) swings its free edge 7 cm into room B.
    const Vec3 hinge(0.1f, 0.0f, -0.5f);
    addBox(s, "door", door, {0.1f, 0.0f, -0.5f}, {0.14f, 2.0f, 0.5f}, 4.0f * kPi / 180.0f, hinge);
    // The light: on room B's ceiling, far from the door, facing down.
    const int light = addMaterial(s, emitter("light", Spectrum(4000.0f)));  // room A reads ~0.3
    addSquare(s, "light", light, {3.0f, 2.49f, 0.0f}, {0, -1, 0}, 0.5f);
    s.camera = lookAt({-3.6f, 1.7f, 1.6f}, {0.0f, 0.7f, -0.3f}, 1.0f);
    return s;
}

// ---- geometry where surfaces meet ---------------------------------------------------------

SceneDesc contactScene() {
    SceneDesc s;
    const int white = addMaterial(s, lambertian("white", Spectrum(0.725f, 0.71f, 0.68f)));
    const int red = addMaterial(s, lambertian("red", Spectrum(0.63f, 0.065f, 0.05f)));
    const int green = addMaterial(s, lambertian("green", Spectrum(0.14f, 0.45f, 0.091f)));
    const int grey = addMaterial(s, lambertian("boxes", Spectrum(0.5f)));
    addQuad(s, "floor", white, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1});
    addQuad(s, "ceiling", white, {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1});
    addQuad(s, "back", white, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1});
    addQuad(s, "left", red, {-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1});
    addQuad(s, "right", green, {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1});
    const int light = addMaterial(s, emitter("light", Spectrum(17.0f, 12.0f, 4.0f)));
    addSquare(s, "light", light, {0, 1.99f, 0}, {0, -1, 0}, 0.235f);
    // In the back-left corner: faces exactly in the left wall, the back wall and the floor.
    addBox(s, "corner box", grey, {-1, 0, -1}, {-0.4f, 1.0f, -0.4f});
    // Against the right wall: one face in the wall, one in the floor.
    addBox(s, "wall box", grey, {0.5f, 0, -0.2f}, {1, 0.5f, 0.3f});
    // A 1 cm slab whose underside floats 1e-4 above the floor.
    addBox(s, "thin slab", white, {-0.6f, 1e-4f, 0.2f}, {0.2f, 0.0101f, 0.8f});
    s.camera = CameraDesc{true, {0, 1, 3.9f}, {0, 0, -1}, {0, 1, 0}, 0.6911f};
    return s;
}

// ---- grazing angles --------------------------------------------------------------------------
// Camera and light 0.5 m above the plane, 573 m apart: the reflection point midway sees each at
// an elevation of atan(0.5 / 286.5) = 0.1°, i.e. 89.9° from the normal. A 1° field of view
// keeps every camera ray within half a degree of that.

SceneDesc grazingScene() {
    SceneDesc s;
    constexpr float h = 0.5f, half = 286.5f;
    Material metal;
    metal.name = "glossy metal";
    metal.type = MaterialType::Conductor;
    metal.albedo = Spectrum(0.95f, 0.8f, 0.5f);
    metal.roughness = 0.1f;
    const int plane = addMaterial(s, metal);
    addQuad(s, "plane", plane, {-100, 0, 50}, {100, 0, 50}, {100, 0, -2 * half - 50}, {-100, 0, -2 * half - 50});
    const Vec3 reflection(0, 0, -half), lightPos(0, h, -2 * half);
    const int light = addMaterial(s, emitter("light", Spectrum(2000.0f)));
    addSquare(s, "light", light, lightPos, normalize(reflection - lightPos), 0.25f);
    s.camera = lookAt({0, h, 0}, reflection, 1.0f * kPi / 180.0f);
    return s;
}

// ---- degenerate input ------------------------------------------------------------------------

SceneDesc degenerateScene() {
    SceneDesc s;
    // Albedo exactly 1: a walk's weight never drops, so only Russian roulette's cap (and the
    // open front) end it.
    const int white = addMaterial(s, lambertian("albedo one", Spectrum(1.0f)));
    const int blue = addMaterial(s, lambertian("blue", Spectrum(0.1f, 0.2f, 0.8f)));
    addQuad(s, "floor", white, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1});
    addQuad(s, "ceiling", white, {-1, 2, -1}, {1, 2, -1}, {1, 2, 1}, {-1, 2, 1});
    addQuad(s, "back", white, {-1, 0, -1}, {1, 0, -1}, {1, 2, -1}, {-1, 2, -1});
    addQuad(s, "left", white, {-1, 0, 1}, {-1, 0, -1}, {-1, 2, -1}, {-1, 2, 1});
    addQuad(s, "right", white, {1, 0, -1}, {1, 0, 1}, {1, 2, 1}, {1, 2, -1});
    const int light = addMaterial(s, emitter("light", Spectrum(5.0f)));
    addSquare(s, "light", light, {0, 1.99f, 0}, {0, -1, 0}, 0.235f);

    // Zero-area triangles: collinear corners, a repeated vertex, all three corners equal.
    s.meshes.push_back(MeshDesc{"zero-area triangles",
                                {{-0.5f, 0.5f, 0}, {0, 0.5f, 0}, {0.5f, 0.5f, 0}, {0.2f, 1.0f, 0.1f}},
                                {},
                                {0, 1, 2, 0, 3, 3, 1, 1, 1},
                                blue});
    // An emitter of zero area (collinear corners): it must be dropped, not sampled with pdf 1/0.
    const int zeroLight = addMaterial(s, emitter("zero-area light", Spectrum(1000.0f)));
    s.meshes.push_back(MeshDesc{"zero-area light", {{-0.3f, 1.5f, 0}, {0, 1.5f, 0}, {0.3f, 1.5f, 0}}, {}, {0, 1, 2}, zeroLight});
    // Needles: 1.5 m long, 2e-5 m wide at the base, an apex angle of 1.3e-5 rad (above the glTF
    // loader's degeneracy threshold of 1e-6, so they survive a round trip through a file).
    MeshDesc needles{"needles", {}, {}, {}, blue};
    for (int i = 0; i < 8; ++i) {
        const float x = -0.7f + 0.2f * i, z = -0.3f + 0.05f * i;
        const uint32_t b = static_cast<uint32_t>(needles.positions.size());
        needles.positions.insert(needles.positions.end(), {{x, 0.1f, z}, {x + 2e-5f, 0.1f, z}, {x + 0.3f, 1.6f, z}});
        needles.indices.insert(needles.indices.end(), {b, b + 1, b + 2});
    }
    s.meshes.push_back(std::move(needles));
    // An emissive needle (area 1.5e-5 m²): its power share is ~1e-5, so it is sampled rarely,
    // but when it is, pdfA = p / area must stay finite.
    const int needleLight = addMaterial(s, emitter("needle light", Spectrum(50.0f)));
    s.meshes.push_back(MeshDesc{"needle light", {{-0.8f, 1.9f, -0.5f}, {0.8f, 1.9f, -0.5f}, {0.8f, 1.9f + 2e-5f, -0.5f}},
                                {}, {0, 1, 2}, needleLight});
    s.camera = CameraDesc{true, {0, 1, 3.9f}, {0, 0, -1}, {0, 1, 0}, 0.6911f};
    return s;
}

SceneDesc degenerateTinyScene() {
    SceneDesc s;
    const int ground = addMaterial(s, lambertian("ground", Spectrum(0.5f)));
    const int cube = addMaterial(s, lambertian("cube", Spectrum(0.8f, 0.3f, 0.1f)));
    addQuad(s, "ground", ground, {-5000, 0, 5000}, {5000, 0, 5000}, {5000, 0, -5000}, {-5000, 0, -5000});
    // Distant walls make the scene's extent 10 km in every direction, as the BVH sees it.
    addQuad(s, "far wall", ground, {-5000, 0, -5000}, {5000, 0, -5000}, {5000, 1000, -5000}, {-5000, 1000, -5000});
    addBox(s, "1 mm cube", cube, {-0.0005f, 0, -0.0005f}, {0.0005f, 0.001f, 0.0005f});
    const int light = addMaterial(s, emitter("light", Spectrum(100.0f)));
    const Vec3 lightPos(-2, 4, 3);
    addSquare(s, "light", light, lightPos, normalize(Vec3(0) - lightPos), 0.5f);
    s.camera = lookAt({0.0025f, 0.002f, 0.003f}, {0, 0.0004f, 0}, 0.6f);
    return s;
}

SceneDesc degenerateFarScene() {
    SceneDesc s;
    const Vec3 o(1e6f, 1e6f, 1e6f);
    constexpr float k = 500.0f;
    auto at = [&](float x, float y, float z) { return o + Vec3(x, y, z) * k; };
    const int white = addMaterial(s, lambertian("white", Spectrum(0.725f, 0.71f, 0.68f)));
    const int red = addMaterial(s, lambertian("red", Spectrum(0.63f, 0.065f, 0.05f)));
    const int green = addMaterial(s, lambertian("green", Spectrum(0.14f, 0.45f, 0.091f)));
    addQuad(s, "floor", white, at(-1, 0, 1), at(1, 0, 1), at(1, 0, -1), at(-1, 0, -1));
    addQuad(s, "ceiling", white, at(-1, 2, -1), at(1, 2, -1), at(1, 2, 1), at(-1, 2, 1));
    addQuad(s, "back", white, at(-1, 0, -1), at(1, 0, -1), at(1, 2, -1), at(-1, 2, -1));
    addQuad(s, "left", red, at(-1, 0, 1), at(-1, 0, -1), at(-1, 2, -1), at(-1, 2, 1));
    addQuad(s, "right", green, at(1, 0, -1), at(1, 0, 1), at(1, 2, 1), at(1, 2, -1));
    const int light = addMaterial(s, emitter("light", Spectrum(17.0f, 12.0f, 4.0f)));
    addSquare(s, "light", light, at(0, 1.99f, 0), {0, -1, 0}, 0.235f * k);
    const int box = addMaterial(s, lambertian("box", Spectrum(0.725f, 0.71f, 0.68f)));
    addBox(s, "box", box, at(-0.6f, 0, -0.6f), at(0, 1.2f, 0));
    s.camera = CameraDesc{true, at(0, 1, 3.77f), {0, 0, -1}, {0, 1, 0}, 0.6911f};  // the Cornell box's view
    return s;
}

}  // namespace tripath
