// SceneDesc → glTF 2.0 with one buffer: a .glb (JSON and BIN chunks), or a .gltf with the buffer in
// a .bin beside it or embedded as base64 (gltf_model.h writes each): the inverse of gltf_loader,
// so that a built-in scene can be shipped as a file and loaded like any user's (scenes/*.gltf,
// embedded) and a loaded one written back about as small as it came.
// The scene becomes a tinygltf::Model, which tinygltf writes (gltf_model.h).
//
// Materials are written so that the loader's mapping (the table atop gltf_materials.cpp) gives them back:
//   Lambertian  metallic 0, roughness 1
//   Plastic     metallic 0, roughness r (< 0.99), KHR_materials_ior when ior ≠ 1.5
//   Mirror      metallic 1, roughness 0, extras {"tripath": {"bsdf": "mirror"}} (mirrorMarker)
//   SmoothConductor  metallic 1, roughness 0
//   Conductor   metallic 1, roughness r (> 0)
//   Dielectric  metallic 0, roughness 0, KHR_materials_transmission 1, KHR_materials_ior
//   MetallicRoughness  metallic m, roughness r, KHR_materials_ior when ior ≠ 1.5
// Textures are not written (a warning names each textured material): its factors are.
// Emission is emissiveFactor × KHR_materials_emissive_strength with the strength a power of two,
// so the factor (≤ 1, as glTF requires) times the strength gives the radiance back exactly; point
// lights likewise split into KHR_lights_punctual colour × intensity. Positions, normals and vertex
// colours (COLOR_0, float RGBA) go into the buffer as the floats they are, one node per mesh with
// no transform, so triangles and their colours come back bit for bit; indices as unsigned shorts where they fit, else unsigned ints; other numbers as
// the shortest decimals that read back as the same floats. An array written once is not written
// again: a later one with the same type, count and bytes reuses its accessor (the vertices of
// meshes that share them in the file and differ in material). A mesh with instances is written
// once: consecutive meshes placed alike (one glTF mesh's primitives) as one mesh, and each
// placement as a node with the transform's matrix, or as one node with EXT_mesh_gpu_instancing
// where the scene kept the TRS it came as. The
// camera becomes a perspective camera on a node whose matrix maps glTF's −z/+y view to the
// scene's forward/up.
#pragma once
#include <string>

#include "geometry/scene_desc.h"
#include "core/warnings.h"
#include "io/gltf_model.h"

namespace tripath {

// Writes the scene to `path` through writeGltfModel (gltf_model.h: .glb or .gltf, a .gltf's buffer
// as `buffer` says; a temporary file renamed over each file; InputError, one line naming the path,
// when it cannot write or the name ends in neither). Warns (once per material) where
// the file cannot say exactly what the scene holds: a Conductor of roughness 0 (it would load as
// a SmoothConductor) or a Plastic rougher than 0.99 (it would load as Lambertian). Throws InputError for
// non-finite values, which JSON cannot hold.
void writeGltf(const SceneDesc& scene, const std::string& path, const WarningSink& warn,
               GltfBuffer buffer = GltfBuffer::Beside);

}  // namespace tripath
