// Typed reads of a glTF model's accessors, as the loader needs them: float VEC3 and VEC4 data
// (POSITION, NORMAL, the instancing TRS), float or normalized VEC2 to VEC4 data (TEXCOORD_n,
// COLOR_0) and unsigned byte, short or int indices. Every accessor, bufferView and buffer index,
// the stride and the whole byte range are checked before a byte is read, so a hostile file fails
// with a message instead of reading out of bounds. Sparse accessors and accessors without a
// bufferView are refused. A header of the io library's own (the loader's interface is
// gltf_loader.h).
#pragma once
#include <tiny_gltf.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/gltf_checks.h"
#include "core/vec.h"

namespace tripath::gltf {

class Accessors {
public:
    Accessors(const tinygltf::Model& model, const Report& report) : model_(model), report_(report) {}

    // The elements of float VEC3 accessor `index`; `what` names the attribute in messages.
    std::vector<Vec3> readVec3(int index, const std::string& what) const;
    // The elements of accessor `index`, `components` components each (VEC2, VEC3 or VEC4),
    // flattened: float, or where `normalizedToo` also normalized unsigned byte or short scaled to
    // [0, 1] (TEXCOORD_n's other types).
    std::vector<float> readFloats(int index, int components, const std::string& what, bool normalizedToo = false) const;
    // The elements of COLOR_n accessor `index` as RGBA: float, or normalized unsigned byte or short
    // scaled to [0, 1]; VEC3 or VEC4, alpha 1 for VEC3.
    std::vector<std::array<float, 4>> readColours(int index, const std::string& what) const;
    // The elements of unsigned byte, short or int SCALAR accessor `index`, widened; `what` names
    // the primitive in messages.
    std::vector<uint32_t> readIndices(int index, const std::string& what) const;

private:
    // The bytes of an accessor's first element and the distance between elements.
    struct Bytes {
        const unsigned char* first = nullptr;
        size_t stride = 0;
        size_t count = 0;
    };

    const tinygltf::Accessor& accessor(int index, const std::string& what) const;
    Bytes accessorBytes(int index, size_t elementSize) const;

    const tinygltf::Model& model_;
    const Report& report_;
};

}  // namespace tripath::gltf
