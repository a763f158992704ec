// Where a scene comes from: a built-in name or a glTF 2.0 file.
#pragma once
#include <string>

#include "io/gltf_loader.h"
#include "geometry/scene_desc.h"
#include "core/warnings.h"

namespace tripath {

// A built-in scene by name, else a .gltf/.glb file. Throws InputError for an unknown name that
// is not a file either, or for a bad file (`gltf` says which files a glTF file may read). The
// loader's warnings go to `warn`. Its sources are the files read (loadGltf), or the built-in's
// name.
SceneDesc loadSceneDesc(const std::string& nameOrPath, const GltfOptions& gltf = {}, const WarningSink& warn = printWarning);

}  // namespace tripath
