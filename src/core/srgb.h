// The sRGB transfer function's inverse (IEC 61966-2-1): the linear value of an encoded one in
// [0, 1]. glTF colour textures are decoded with it, and 8-bit colours named in code ("#rrggbb").
#pragma once
#include <cmath>

namespace tripath {

inline float srgbDecode(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

}  // namespace tripath
