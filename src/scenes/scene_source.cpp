#include "scenes/scene_source.h"

#include <filesystem>

#include "scenes/builtin_scenes.h"
#include "core/error.h"
#include "core/fnv1a.h"
#include "io/gltf_loader.h"

namespace tripath {

SceneDesc loadSceneDesc(const std::string& nameOrPath, const GltfOptions& gltf, const WarningSink& warn) {
    if (isBuiltinScene(nameOrPath)) {
        SceneDesc desc = builtinScene(nameOrPath);
        desc.sources = {{nameOrPath, fnv1a(nameOrPath)}};  // a built-in is what its name says
        return desc;
    }
    const std::filesystem::path path(nameOrPath);
    const std::string ext = path.extension().string();
    if (ext != ".gltf" && ext != ".glb" && !std::filesystem::exists(path))
        throw InputError("unknown scene '" + nameOrPath + "': not a built-in (see `tripath scenes`) nor a .gltf/.glb file");
    return loadGltf(nameOrPath, warn, gltf);
}

}  // namespace tripath
