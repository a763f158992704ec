// Built-in scenes where light-transport methods fail, each for a reason that is known in advance.
// They are registered with the other built-ins
// (builtin_scenes.cpp) and exported as scenes/<name>.gltf; tests/test_stability.cpp renders each
// with every integrator and checks what must hold (no NaN, bounded work, agreement where a method
// can sample the light, black where it provably cannot); docs/failures.md tabulates the errors.
//
// Each function's comment says what fails and why. Where a test needs a point of the scene (the
// centre of a caustic, say), the constant is exported here so the scene and the test agree.
#pragma once
#include "geometry/scene_desc.h"

namespace tripath {

// ---- caustics ---------------------------------------------------------------------------------
// A glass ball floating 10 cm above a diffuse floor, lit by a small light up and to the side:
// the ball focuses the light into a bright caustic inside its own shadow.

// Where the line from the light through the ball's centre meets the floor: inside the caustic.
Vec3 causticCentre();

// Small area light. PT: a floor point in the caustic is lit only along paths through the glass,
// which next-event estimation cannot use (the shadow ray hits the ball) and which BSDF sampling
// finds only when the refracted direction happens to hit the 10 cm light: very noisy.
// LT and BDPT trace light through the ball and connect the floor vertex to the camera: good.
SceneDesc causticScene();

// The same with a point light. PT cannot sample the caustic at all: no walk can hit a point,
// and the shadow ray from the floor is blocked by the glass. The caustic is black under PT,
// however many samples; LT and BDPT (strategy t = 1) see it.
SceneDesc causticPointScene();

// ---- specular-diffuse-specular ---------------------------------------------------------------
// The caustic seen through a glass pane standing between it and the camera: the light's path is
// L S S D S S E (ball in, ball out, floor, pane in, pane out, eye). A strategy joins two subpaths
// at a pair of adjacent non-delta vertices, and the only non-delta interior vertex is the floor,
// whose neighbours are both glass.

// Small area light: the emitter vertex is not delta, so s = 0 (the camera walk hits the light)
// samples the path: PT and BDPT see the caustic through the pane (noisily); LT sees nothing
// through the pane at all, since its connection to the pinhole is blocked by the glass.
SceneDesc sdsScene();

// Point light and pinhole: both ends are delta too, so no (s, t) of any integrator can sample
// the caustic seen through the pane. It is black under PT, LT and BDPT alike (a known limit
// of these methods, fixed only by regularisation or manifold walks, which tripath does not do).
SceneDesc sdsPointScene();

// ---- an analytic specular-diffuse-specular path ------------------------------------------------
// sds-mirrors: a point light, a floor mirror that reflects it onto a diffuse panel, and a wall
// mirror through which the camera sees the panel -- the path L S D S E, with a closed-form answer
// that the merging integrators are checked against. Three mutually perpendicular planes carry the
// three surfaces:
//
//   - the floor mirror M1 in y = 0 (reflectance R1 = 0.9, no Fresnel: MaterialType::Mirror
//     reflects exactly its albedo), facing up;
//   - the panel D in x = 0.4, facing −x (Lambertian, albedo ρ = 0.75), y ∈ [0.1, 0.6], |z| ≤ 0.25;
//   - the wall mirror M2 in z = −1 (reflectance R2 = 0.8), facing +z;
//
// and the point light L = (0, 0.1, 0) of intensity I = 3 W/sr sits in a black hood (albedo 0)
// open only at the bottom, 2 cm below it: a 10 × 6 cm opening, so light leaves the hood only
// downward, in a pyramid that lands wholly on M1. Reflected, it rises as if from L's image
// L' = (0, −0.1, 0), in a pyramid that covers the whole panel and passes beside the hood (its
// z-spread, |z| ≤ 1.5 (y + 0.1), keeps it off M2, whose top edge is at y = 0.5 < 0.567).
//
// The analytic value. The panel receives light from L' only: L itself is inside the hood; M2 is
// lit by nothing but the panel; reflections in the floor and the wall both keep the x-component
// of a direction, so light leaving the panel (towards −x) never comes back to the plane x = 0.4,
// and everything else is black. Hence, at a panel point x (normal n = −x̂),
//     E(x) = R1 · I · cos θ / |x − L'|² = R1 · I · 0.4 / |x − L'|³,
//     Lo(x) = ρ / π · E(x)      (Lambertian: the same in every direction),
// and a pixel that sees the panel through M2 reads R2 · ρ/π · E averaged over its footprint
// (0.945 at the panel's centre, y = 0.35, z = 0; from 2.31 at the middle of its bottom edge to
// 0.39 at the middle of its top edge).
// The camera looks into M2, which fills its view, at the panel's image: every pixel's ray meets
// M2 first; those that go on to the panel read the value above.
//
// Who can sample it. Every vertex of L S D S E but D is a delta (the light's position, two ideal
// mirrors, the pinhole), and D's two neighbours are mirrors: no connection (s, t) joins two
// adjacent non-delta vertices and no walk can hit a point, so PT, LT and BDPT give exactly 0 in
// every pixel that sees the panel through M2, however many samples. Seen directly (another
// camera), the panel is the caustic L S D E, which LT and BDPT sample through t = 1 and PT
// cannot (the shadow ray toward L hits the hood, and no walk hits a point). Vertex merging
// (vcm, bpm, ppm) samples L S D S E by merging at D, its only strategy there (MIS weight 1): for
// a merge radius r the expected pixel value is R2 ρ/π times the mean of E over the disc of radius
// r around each panel point (a bias of order r² on the panel, of order r within r of its edges),
// and it converges to the value above as r shrinks. tests/test_sds_analytic.cpp checks all this.
struct SdsMirrorsLayout {
    Vec3 light{0.0f, 0.1f, 0.0f};
    float intensity = 3.0f;                   // W/sr, grey
    // The hood: open bottom |x| ≤ hoodHalfX, |z| ≤ hoodHalfZ at y = hoodBottom, top at hoodTop.
    float hoodHalfX = 0.05f, hoodHalfZ = 0.03f, hoodBottom = 0.08f, hoodTop = 0.11f;
    // Floor mirror M1 (y = 0): x ∈ [floorX0, floorX1], |z| ≤ floorHalfZ.
    float floorReflectance = 0.9f;
    float floorX0 = -0.3f, floorX1 = 0.3f, floorHalfZ = 0.2f;
    // Diffuse panel D (x = panelX, facing −x): y ∈ [panelY0, panelY1], |z| ≤ panelHalfZ.
    float panelAlbedo = 0.75f;
    float panelX = 0.4f, panelY0 = 0.1f, panelY1 = 0.6f, panelHalfZ = 0.25f;
    // Wall mirror M2 (z = wallZ, facing +z): x ∈ [wallX0, wallX1], y ∈ [wallY0, wallY1].
    float wallReflectance = 0.8f;
    float wallZ = -1.0f, wallX0 = -1.6f, wallX1 = -0.6f, wallY0 = 0.0f, wallY1 = 0.5f;
    // The pinhole, aimed at the panel's image in M2.
    Vec3 camera{-1.5f, 0.35f, -0.8f};
    Vec3 cameraTarget{0.4f, 0.35f, -2.0f};
    float cameraYfov = 0.3f;
};
inline constexpr SdsMirrorsLayout kSdsMirrors{};

SceneDesc sdsMirrorsScene();

// ---- visibility ----------------------------------------------------------------------------
// Two rooms sharing a wall; the door between them is ajar by a few degrees and the only light
// is on the far room's ceiling. Every path from the light to the camera's room squeezes through
// the gap at the door's free edge. PT: next-event estimation from the camera's room is almost
// always blocked and BSDF sampling rarely finds the gap: very noisy. LT/BDPT: light subpaths
// go through the gap on their own, so the lit stripe and the room it brightens converge well.
SceneDesc doorAjarScene();

// ---- geometry where surfaces meet ---------------------------------------------------------
// The Cornell box with two boxes whose faces lie exactly in the walls and floor (coincident,
// coplanar triangles) and a thin slab floating 1e-4 above the floor. Ray origins must leave the
// right surface; a wrong offset shows as light leaking into corners or a black self-shadow, and
// a connection across a 1e-4 gap has g = cos cos / r² up to 1e8: fireflies unless MIS weighs it
// down (BDPT) — the test measures the largest single sample against the pixel mean.
SceneDesc contactScene();

// ---- grazing angles --------------------------------------------------------------------------
// A glossy metal plane (GGX, roughness 0.1) with the camera and a small light each at 89.9° to
// its normal, the light where the camera sees its reflection. Cosines of 1.7e-3, Smith masking
// near its limit and Fresnel near 1: any cancellation or division by a cosine shows as NaN,
// Inf or a bias between the integrators.
SceneDesc grazingScene();

// ---- degenerate input ------------------------------------------------------------------------

// A Cornell box whose walls have an albedo of exactly 1 (Russian roulette must still end the
// walks), with zero-area triangles (collinear corners, a repeated vertex, one point), needle
// triangles 2e-5 m wide and 1.5 m long, an emitter of zero area (dropped; it must not divide by
// its area) and an emissive needle of 3e-5 m² (chosen by power almost never, yet valid).
SceneDesc degenerateScene();

// A 1 mm cube on a 10 km ground, seen from 4 mm away. Hit points on the ground are computed
// from barycentrics of corners 5 km away, so they carry the float spacing there: errors of
// ~0.4 mm on average and up to 1.4 mm sideways, more than the cube's size (the contact shadow
// is jittered). Nothing may turn NaN, and PT and BDPT must still agree. LT practically fails:
// the camera sees 3 mm of the scene, where almost no light path lands.
SceneDesc degenerateTinyScene();

// The Cornell box scaled 500× and moved to coordinates near 1e6, where float spacing is 0.06 m
// and ray offsets (relative to the coordinates) are metres. Radiance is scale invariant, so the
// image should match the unit Cornell box up to leaks at the corners.
SceneDesc degenerateFarScene();

}  // namespace tripath
