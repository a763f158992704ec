// Small textured glTF scenes that the tests write themselves: axis-aligned quads with texture
// coordinates and, if given, vertex colours (COLOR_0, in any of glTF's component types),
// materials as glTF JSON, PNG textures written byte for byte (png_bytes.h), a camera looking down
// −z. What the loader reads from them is what a user's file would give it.
#pragma once
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"
#include "png_bytes.h"

namespace tripath::test {

// sRGB-encoded byte → linear (IEC 61966-2-1), the decoding glTF prescribes for colour textures.
inline float srgbByteToLinear(uint8_t byte) {
    const double c = byte / 255.0;
    return float(c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4));
}

// The square [−h, h]² in the plane z, front face toward +z, its texture the whole image upright
// (the image's top row along +y): uv (0, 1) at (−h, −h), (1, 1) at (h, −h), (1, 0) at (h, h).
struct Quad {
    float z = 0, h = 1;
    int material = 0;
    bool facingDown = false;  // front face toward −z instead (the same uv seen from +z)
    float x = 0, y = 0;       // centre's x and y
    bool mirroredU = false;   // u runs toward −x instead (the image mirrored left to right)
    // COLOR_0 (RGBA) at the corners (−h, −h), (h, −h), (h, h), (−h, h): none, or four.
    std::vector<std::array<float, 4>> colours = {};
};

// How COLOR_0 is stored: glTF's component type (5126 float, 5121 unsigned byte or 5123 unsigned
// short, the integers normalized) and VEC3 or VEC4; each element padded to 4 bytes, as glTF asks
// of vertex attributes.
struct ColourFormat {
    int componentType = 5126;
    int components = 4;
};

class TexturedScene {
public:
    int addMaterial(nlohmann::json m) {
        doc_["materials"].push_back(std::move(m));
        return int(doc_["materials"].size()) - 1;
    }
    // A texture of image file `uri` (next to the scene), its sampler nearest or linear, clamped or
    // repeating.
    int addTexture(const std::string& uri, bool nearest = true, bool repeat = false) {
        return addImageTexture({{"uri", uri}}, nearest, repeat);
    }
    // A texture whose PNG file `png` is copied into the scene: into the buffer (a bufferView, as in
    // a .glb) or into a base64 data: URI.
    int addEmbeddedTexture(const std::filesystem::path& png, bool dataUri) {
        std::ifstream in(png, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (dataUri) return addImageTexture({{"uri", "data:image/png;base64," + base64(bytes)}}, true, false);
        embedded_.push_back({int(doc_["images"].size()), bytes});
        return addImageTexture({{"mimeType", "image/png"}}, true, false);
    }
    // A second texture over the image of texture `texture`, with a sampler of its own.
    int addTextureSharingImage(int texture, bool nearest, bool repeat = false) {
        return addSampledTexture(doc_["textures"][size_t(texture)]["source"].get<int>(), nearest, repeat);
    }
    void addQuad(const Quad& q) { quads_.push_back(q); }
    // An emissive box [−h, h]³ (albedo 0, emitting `radiance` from both faces) around everything.
    void addGlowingBox(float h, float radiance) {
        const int m = addMaterial({{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0},
                                                             {"roughnessFactor", 1}}},
                                   {"emissiveFactor", {1, 1, 1}},
                                   {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", radiance}}}}},
                                   {"doubleSided", true}});
        boxes_.push_back({h, m});
    }
    // Every vertex's TANGENT attribute (xyz and the bitangent's sign w), written when set.
    void setTangent(std::array<float, 4> tangent) { tangent_ = tangent; }
    // How the quads' vertex colours are stored (float VEC4 unless set).
    void setColourFormat(ColourFormat format) { colourFormat_ = format; }
    // The rotation (a unit quaternion x, y, z, w) of the node that places the quads and boxes.
    void setMeshRotation(std::array<float, 4> rotation) { meshRotation_ = rotation; }
    // A perspective camera at (0, 0, z) looking down −z whose view spans [−h, h]² at the plane 0.
    void setCamera(float z, float h = 1) {
        cameraZ_ = z;
        yfov_ = 2 * std::atan(h / z);
    }
    // A perspective camera at (0, 0, z) looking up (+z, with +y down the image), of field yfov.
    void setCameraLookingUp(float z, float yfov) {
        cameraZ_ = z;
        yfov_ = yfov;
        lookingUp_ = true;
    }
    // Writes the .gltf and its .bin beside it; returns the .gltf's path.
    std::string write(const std::filesystem::path& file) {
        std::vector<float> positions, uvs, tangents;
        std::vector<uint32_t> indices;
        std::string colours;  // COLOR_0 of every vertex, as colourFormat_ stores it (white where none is given)
        auto corner = [&](Vec3 p, Vec2 uv, std::array<float, 4> colour = {1, 1, 1, 1}) {
            positions.insert(positions.end(), {p.x, p.y, p.z});
            uvs.insert(uvs.end(), {uv.x, uv.y});
            if (tangent_) tangents.insert(tangents.end(), tangent_->begin(), tangent_->end());
            colours += storedColour(colour);
        };
        nlohmann::json primitives = nlohmann::json::array();
        std::vector<size_t> coloured;  // the primitives whose quads have colours
        for (const Quad& q : quads_) {
            const auto base = uint32_t(positions.size() / 3);
            const float u0 = q.mirroredU ? 1.0f : 0.0f, u1 = 1.0f - u0;
            const std::array<float, 4> white{1, 1, 1, 1};
            auto colour = [&](size_t k) { return q.colours.empty() ? white : q.colours.at(k); };
            corner({q.x - q.h, q.y - q.h, q.z}, {u0, 1}, colour(0));
            corner({q.x + q.h, q.y - q.h, q.z}, {u1, 1}, colour(1));
            corner({q.x + q.h, q.y + q.h, q.z}, {u1, 0}, colour(2));
            corner({q.x - q.h, q.y + q.h, q.z}, {u0, 0}, colour(3));
            const size_t first = indices.size();
            if (q.facingDown) indices.insert(indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
            else indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
            if (!q.colours.empty()) coloured.push_back(primitives.size());
            primitives.push_back(primitive(first, q.material));
        }
        for (const Box& b : boxes_) {
            const float h = b.h;
            const Vec3 c[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h},
                               {-h, -h, h},  {h, -h, h},  {h, h, h},  {-h, h, h}};
            const auto base = uint32_t(positions.size() / 3);
            for (const Vec3& p : c) corner(p, {0, 0});
            const size_t first = indices.size();
            for (uint32_t i : {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                               2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 3, 0, 4, 3, 4, 7})
                indices.push_back(base + i);
            primitives.push_back(primitive(first, b.material, 36));
        }
        const size_t vertices = positions.size() / 3;
        std::string bytes;
        auto append = [&](const void* data, size_t size) {
            const size_t offset = bytes.size();
            bytes.append(static_cast<const char*>(data), size);
            return offset;
        };
        const size_t pOffset = append(positions.data(), positions.size() * 4);
        const size_t uvOffset = append(uvs.data(), uvs.size() * 4);
        const size_t iOffset = append(indices.data(), indices.size() * 4);
        const size_t tOffset = append(tangents.data(), tangents.size() * 4);
        const size_t cOffset = append(colours.data(), colours.size());
        std::vector<std::pair<size_t, size_t>> imageViews;  // offset and length of each embedded image
        for (const auto& [image, png] : embedded_) imageViews.push_back({append(png.data(), png.size()), png.size()});
        std::ofstream(file.string() + ".bin", std::ios::binary) << bytes;
        doc_["asset"] = {{"version", "2.0"}};
        doc_["buffers"] = {{{"uri", file.filename().string() + ".bin"}, {"byteLength", bytes.size()}}};
        doc_["bufferViews"] = {{{"buffer", 0}, {"byteOffset", pOffset}, {"byteLength", positions.size() * 4}},
                               {{"buffer", 0}, {"byteOffset", uvOffset}, {"byteLength", uvs.size() * 4}},
                               {{"buffer", 0}, {"byteOffset", iOffset}, {"byteLength", indices.size() * 4}}};
        for (size_t k = 0; k < embedded_.size(); ++k) {
            doc_["images"][size_t(embedded_[k].first)]["bufferView"] = doc_["bufferViews"].size();
            doc_["bufferViews"].push_back(
                {{"buffer", 0}, {"byteOffset", imageViews[k].first}, {"byteLength", imageViews[k].second}});
        }
        doc_["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC3"}},
                             {{"bufferView", 1}, {"componentType", 5126}, {"count", vertices}, {"type", "VEC2"}}};
        for (const auto& [first, count] : ranges_)
            doc_["accessors"].push_back({{"bufferView", 2}, {"byteOffset", first * 4}, {"componentType", 5125},
                                         {"count", count}, {"type", "SCALAR"}});
        for (size_t k = 0; k < primitives.size(); ++k) primitives[k]["indices"] = 2 + k;
        if (tangent_) {
            doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", tOffset}, {"byteLength", tangents.size() * 4}});
            doc_["accessors"].push_back({{"bufferView", doc_["bufferViews"].size() - 1},
                                         {"componentType", 5126}, {"count", vertices}, {"type", "VEC4"}});
            for (auto& p : primitives) p["attributes"]["TANGENT"] = doc_["accessors"].size() - 1;
        }
        if (!coloured.empty()) {
            doc_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", cOffset}, {"byteLength", colours.size()},
                                           {"byteStride", colours.size() / vertices}});
            nlohmann::json accessor = {{"bufferView", doc_["bufferViews"].size() - 1},
                                       {"componentType", colourFormat_.componentType},
                                       {"count", vertices},
                                       {"type", colourFormat_.components == 3 ? "VEC3" : "VEC4"}};
            if (colourFormat_.componentType != 5126) accessor["normalized"] = true;
            doc_["accessors"].push_back(accessor);
            for (size_t k : coloured) primitives[k]["attributes"]["COLOR_0"] = doc_["accessors"].size() - 1;
        }
        doc_["meshes"] = {{{"primitives", primitives}}};
        doc_["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", yfov_}, {"znear", 0.01}}}}};
        doc_["nodes"] = {{{"mesh", 0}}, {{"camera", 0}, {"translation", {0, 0, cameraZ_}}}};
        if (meshRotation_) doc_["nodes"][0]["rotation"] = *meshRotation_;
        if (lookingUp_) doc_["nodes"][1]["rotation"] = {1, 0, 0, 0};  // half a turn about x
        doc_["scenes"] = {{{"nodes", {0, 1}}}};
        doc_["scene"] = 0;
        std::ofstream(file) << doc_.dump();
        return file.string();
    }

private:
    // One vertex's colour as colourFormat_ stores it: its components as floats or as normalized
    // integers (rounded), padded with zero bytes to a multiple of 4.
    std::string storedColour(const std::array<float, 4>& colour) const {
        std::string bytes;
        for (int c = 0; c < colourFormat_.components; ++c) {
            const float x = colour[size_t(c)];
            if (colourFormat_.componentType == 5126) {
                bytes.append(reinterpret_cast<const char*>(&x), 4);
            } else if (colourFormat_.componentType == 5121) {
                bytes += char(uint8_t(std::lround(x * 255)));
            } else {
                const auto v = uint16_t(std::lround(x * 65535));
                bytes.append(reinterpret_cast<const char*>(&v), 2);
            }
        }
        bytes.resize((bytes.size() + 3) / 4 * 4, '\0');
        return bytes;
    }
    int addImageTexture(nlohmann::json image, bool nearest, bool repeat) {
        doc_["images"].push_back(std::move(image));
        return addSampledTexture(int(doc_["images"].size()) - 1, nearest, repeat);
    }
    int addSampledTexture(int image, bool nearest, bool repeat) {
        const int filter = nearest ? 9728 : 9729, wrap = repeat ? 10497 : 33071;
        doc_["samplers"].push_back({{"magFilter", filter}, {"minFilter", filter}, {"wrapS", wrap}, {"wrapT", wrap}});
        doc_["textures"].push_back({{"source", image}, {"sampler", int(doc_["samplers"].size()) - 1}});
        return int(doc_["textures"].size()) - 1;
    }
    static std::string base64(const std::string& bytes) {
        static const char* const kDigits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        std::string out;
        for (size_t i = 0; i < bytes.size(); i += 3) {
            const size_t n = std::min<size_t>(3, bytes.size() - i);  // bytes in this group of three
            uint32_t group = 0;
            for (size_t k = 0; k < n; ++k) group |= uint32_t(uint8_t(bytes[i + k])) << (16 - 8 * k);
            for (size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(group >> (18 - 6 * k)) & 63] : '=';
        }
        return out;
    }
    struct Box {
        float h;
        int material;
    };
    nlohmann::json primitive(size_t first, int material, size_t count = 6) {
        ranges_.push_back({first, count});
        return {{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", material}};
    }
    nlohmann::json doc_ = nlohmann::json::object();
    std::vector<Quad> quads_;
    std::vector<Box> boxes_;
    std::vector<std::pair<size_t, size_t>> ranges_;
    std::vector<std::pair<int, std::string>> embedded_;  // image index, PNG bytes
    float cameraZ_ = 2, yfov_ = 1;
    bool lookingUp_ = false;
    std::optional<std::array<float, 4>> tangent_, meshRotation_;
    ColourFormat colourFormat_;
};

}  // namespace tripath::test
