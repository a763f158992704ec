// Building blocks for scenes written in code (builtin_scenes.cpp, failure_scenes.cpp): materials
// by kind, quads, boxes, spheres and a look-at camera, appended to a SceneDesc.
#pragma once
#include "geometry/scene_desc.h"

namespace tripath::build {

// Appends a material; returns its index.
int addMaterial(SceneDesc& s, Material m);
Material lambertian(const char* name, Spectrum albedo);
// A black Lambertian surface that emits radiance Le from its front face.
Material emitter(const char* name, Spectrum radiance);
// Clear glass of index 1.5.
Material glass(const char* name);

// Quad a b c d, counter-clockwise seen from its front (the side its normal points to).
void addQuad(SceneDesc& s, const char* name, int material, Vec3 a, Vec3 b, Vec3 c, Vec3 d);
// A square of half-size `half` centred at c, facing along unit n.
void addSquare(SceneDesc& s, const char* name, int material, Vec3 c, Vec3 n, float half);
// Box with corners lo and hi (exact coordinates, so faces can lie exactly in other surfaces),
// rotated by `angle` about the vertical axis through `pivot`; faces outward.
void addBox(SceneDesc& s, const char* name, int material, Vec3 lo, Vec3 hi, float angle = 0, Vec3 pivot = {});
// UV sphere, with smooth shading normals unless `flat`; `inward` turns its front faces inside.
// The zero-area triangles at the poles are left out.
void addSphere(SceneDesc& s, const char* name, int material, Vec3 centre, float radius, int rings,
               bool inward = false, bool flat = false);

CameraDesc lookAt(Vec3 from, Vec3 to, float yfov);

}  // namespace tripath::build
