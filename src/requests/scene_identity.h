// A scene as checkpoints and references know it: by the content of what it was built from
// (Scene::sources: the glTF file, the buffer and image files it read, the environment; a
// built-in's name), recorded as the metadata value tripath:scene-files, "x.gltf 0123456789abcdef;
// x.bin fedcba9876543210; sky.exr ...". Two records are one scene when their hashes agree one
// for one, whatever the names: x.gltf named ./x.gltf or by its absolute path is the same scene,
// x.gltf edited is another.
#pragma once
#include <string>
#include <vector>

#include "geometry/scene_desc.h"

namespace tripath {

inline constexpr const char* kSceneFilesKey = "tripath:scene-files";

// The record of `sources`: each one's name (at most an excerpt, a ';' or control character in it
// as '?') and hash (16 hex digits), in order, separated by "; ".
std::string sceneFilesText(const std::vector<SourceFile>& sources);

// What differs between a recorded scene and this run's, for a one-line refusal: "x.gltf changed",
// "cornell is now veach-mis", "sky.exr is new", "sky.exr is gone" (the first difference); empty
// when every hash agrees.
std::string sceneFilesDifference(const std::string& recorded, const std::string& current);

}  // namespace tripath
