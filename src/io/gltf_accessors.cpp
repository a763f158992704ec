// Reading glTF accessors with their bounds checked (gltf_accessors.h): the only place that turns
// the file's buffer bytes into numbers.
#include "io/gltf_accessors.h"

#include <cstring>

namespace tripath::gltf {

const tinygltf::Accessor& Accessors::accessor(int index, const std::string& what) const {
    if (index < 0 || size_t(index) >= model_.accessors.size())
        report_.fail(what + " references accessor " + std::to_string(index) + ", which does not exist");
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    if (a.sparse.isSparse) report_.fail("accessor " + std::to_string(index) + " is sparse (not supported)");
    return a;
}

// Validates the bufferView and buffer indices and that every element lies inside both.
Accessors::Bytes Accessors::accessorBytes(int index, size_t elementSize) const {
    const tinygltf::Accessor& a = model_.accessors[size_t(index)];
    const std::string name = "accessor " + std::to_string(index);
    if (a.bufferView < 0) report_.fail(name + " has no bufferView (not supported)");
    if (size_t(a.bufferView) >= model_.bufferViews.size())
        report_.fail(name + " references bufferView " + std::to_string(a.bufferView) + ", which does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(a.bufferView)];
    const std::string viewName = "bufferView " + std::to_string(a.bufferView);
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
        report_.fail(viewName + " references buffer " + std::to_string(view.buffer) + ", which does not exist");
    const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
    const std::string bufferName = "buffer " + std::to_string(view.buffer);
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        report_.fail(viewName + " reads past the end of " + bufferName);
    const size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize) report_.fail(viewName + " byteStride is smaller than the elements of " + name);
    if (a.count > 0) {
        const size_t available = view.byteLength;
        if (a.byteOffset > available || elementSize > available - a.byteOffset ||
            (a.count - 1) > (available - a.byteOffset - elementSize) / stride)
            report_.fail(name + " reads past the end of " + viewName + " in " + bufferName);
    }
    return {data.data() + view.byteOffset + a.byteOffset, stride, a.count};
}

std::vector<Vec3> Accessors::readVec3(int index, const std::string& what) const {
    const std::vector<float> v = readFloats(index, 3, what);
    std::vector<Vec3> out(v.size() / 3);
    for (size_t i = 0; i < out.size(); ++i) out[i] = {v[3 * i], v[3 * i + 1], v[3 * i + 2]};
    return out;
}

std::vector<float> Accessors::readFloats(int index, int components, const std::string& what, bool normalizedToo) const {
    const tinygltf::Accessor& a = accessor(index, what);
    const int type = components == 2 ? TINYGLTF_TYPE_VEC2 : components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_VEC4;
    size_t size = 0;
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT) size = 4;
    if (normalizedToo && a.normalized && a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) size = 1;
    if (normalizedToo && a.normalized && a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) size = 2;
    if (size == 0 || a.type != type)
        report_.fail(what + " accessor " + std::to_string(index) + " is not float" +
                     (normalizedToo ? " or normalized unsigned" : "") + " VEC" + std::to_string(components));
    const Bytes bytes = accessorBytes(index, size * size_t(components));
    std::vector<float> out(bytes.count * size_t(components));
    for (size_t i = 0; i < bytes.count; ++i)
        for (size_t c = 0; c < size_t(components); ++c) {
            const unsigned char* p = bytes.first + i * bytes.stride + c * size;
            float& x = out[i * size_t(components) + c];
            if (size == 4) {
                std::memcpy(&x, p, 4);
            } else if (size == 2) {
                uint16_t v;
                std::memcpy(&v, p, 2);
                x = float(v) / 65535.0f;
            } else {
                x = float(p[0]) / 255.0f;
            }
        }
    return out;
}

std::vector<std::array<float, 4>> Accessors::readColours(int index, const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, what);
    if (a.type != TINYGLTF_TYPE_VEC3 && a.type != TINYGLTF_TYPE_VEC4)
        report_.fail(what + " accessor " + std::to_string(index) + " is not float or normalized unsigned VEC3 or VEC4");
    const size_t components = a.type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    const std::vector<float> v = readFloats(index, int(components), what, true);
    std::vector<std::array<float, 4>> out(v.size() / components, {1, 1, 1, 1});
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t c = 0; c < components; ++c) out[i][c] = v[i * components + c];
    return out;
}

std::vector<uint32_t> Accessors::readIndices(int index, const std::string& what) const {
    const tinygltf::Accessor& a = accessor(index, what + " indices");
    size_t size = 0;
    switch (a.componentType) {
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
        default: break;
    }
    if (size == 0 || a.type != TINYGLTF_TYPE_SCALAR)
        report_.fail(what + " indices accessor " + std::to_string(index) +
                     " is not unsigned byte, short or int scalars");
    const Bytes bytes = accessorBytes(index, size);
    std::vector<uint32_t> out(bytes.count);
    for (size_t i = 0; i < bytes.count; ++i) {
        const unsigned char* p = bytes.first + i * bytes.stride;
        if (size == 1) {
            out[i] = p[0];
        } else if (size == 2) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            out[i] = v;
        } else {
            std::memcpy(&out[i], p, 4);
        }
    }
    return out;
}

}  // namespace tripath::gltf
