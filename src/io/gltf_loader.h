// glTF 2.0 loading (.gltf with embedded or external buffers, and .glb) into a plain SceneDesc.
// What each glTF feature becomes, and what is ignored, is listed in docs/gltf.md and in the
// comments at the top of gltf_loader.cpp and gltf_materials.cpp.
#pragma once
#include <string>

#include "geometry/scene_desc.h"
#include "core/warnings.h"

namespace tripath {

struct GltfOptions {
    // Lets buffer and image URIs name files outside the scene's folder (absolute paths, `..`,
    // symlinks that leave it). Off: only regular files in the folder and its subfolders
    // (external_files.h).
    bool allowExternalFiles = false;
};

// Loads the default scene of a glTF 2.0 file (chosen as .glb or .gltf by its magic bytes).
// Throws InputError with one line "<path>: <problem>" for any bad input: missing or unreadable
// file, broken JSON or GLB, out-of-range indices or reads, non-finite or collapsing transforms,
// invalid materials or lights, unsupported required extensions, a scene without triangles, a
// buffer or image URI that names a file the options do not allow, or a texture image that cannot
// be read or claims more texels than are read (gltf_textures.h).
SceneDesc loadGltf(const std::string& path, WarningSink warn = printWarning, const GltfOptions& options = {});

}  // namespace tripath
