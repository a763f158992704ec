// glTF materials → the scene's Materials: which of the renderer's few BSDFs each glTF material
// becomes, from its pbrMetallicRoughness factors, textures and a few KHR_materials extensions (the table
// at the top of gltf_materials.cpp; docs/gltf.md for users). A header of the io library's
// own (the loader's interface is gltf_loader.h).
#pragma once
#include <tiny_gltf.h>

#include <vector>

#include "io/gltf_checks.h"
#include "io/gltf_textures.h"
#include "geometry/material.h"

namespace tripath::gltf {

// The model's materials, in order, with the textures they use read through `textures`; warns once
// about each kind of feature they lose (naming the materials), fails on a factor out of range, a
// texture that cannot be read or a material validateMaterial refuses.
std::vector<Material> convertMaterials(const tinygltf::Model& model, TextureReader& textures, Report& report);

// The material of primitives that name none.
Material defaultMaterial();

// The extras {"tripath": {"bsdf": "mirror"}} that mark a metallic 1, roughness 0 material as the
// renderer's Mirror (reflectance the base colour at every angle), which glTF's BRDF cannot say:
// without it such a material is the BRDF's smooth limit, a SmoothConductor. Exported built-in
// scenes carry it; other files need not.
tinygltf::Value mirrorMarker();

}  // namespace tripath::gltf
