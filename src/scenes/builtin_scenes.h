// The built-in scenes, by name: no file needed. Each one exists because a test or a benchmark
// needs it (docs/design.md §3); all are listed in builtin_scenes.cpp and defined there top to bottom,
// the failure scenes in failure_scenes.cpp.
#pragma once
#include <string>
#include <vector>

#include "geometry/scene_desc.h"

namespace tripath {

struct BuiltinInfo {
    std::string name;
    std::string description;
};

const std::vector<BuiltinInfo>& builtinScenes();
bool isBuiltinScene(const std::string& name);
// Throws InputError for an unknown name.
SceneDesc builtinScene(const std::string& name);

// A closed sphere of uniform Lambertian albedo a emitting Le on its inside, camera at its centre:
// radiance is Le / (1 − a) everywhere (the white furnace). Two-sided so no face is dark.
SceneDesc furnaceScene(float albedo, float emittedRadiance);
// The Cornell box with `triangles` ≥ 36 triangles: the boxes replaced by a finely tessellated
// sphere when more are asked for (benchmarks of how cost grows with the scene).
SceneDesc cornellTessellated(size_t triangles);

}  // namespace tripath
