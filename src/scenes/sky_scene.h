// The built-in outdoor scene: objects on a ground plane under a sky with a small bright sun, lit by
// the environment alone. What every integrator meets on a real glTF model given --environment, and
// where sampling the sky by importance matters (bench/README.md measures it here).
#pragma once
#include "geometry/scene_desc.h"

namespace tripath {

// A 256 × 128 latitude-longitude sky (geometry/environment.h): a blue gradient brighter toward the
// horizon, a dim ground below it, and a sun of 1.5° radius (a few texels) at 40°
// elevation whose irradiance on a surface facing it is several times the rest of the sky's.
EnvironmentDesc sunAndSky();

// A matte box, a rough metal sphere and a glass sphere on a checkered ground (a base colour
// texture) under sunAndSky().
SceneDesc skyScene();

}  // namespace tripath
