// glTF textures → Texture (geometry/texture.h): the images read with OpenImageIO from the buffer
// views, data: URIs or files (in the scene's folder, as for buffers: external_files.h) they come
// from, decoded to linear RGBA floats, with their samplers and KHR_texture_transform. A header of
// the io library's own.
#pragma once
#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry/texture.h"
#include "io/gltf_checks.h"

namespace tripath::gltf {

// The largest image read: a side of 16384 texels and 2^26 texels in all (1 GiB as RGBA floats).
// A header claiming more is refused before any texel is allocated.
constexpr int kMaxTextureSide = 16384;
constexpr long long kMaxTexturePixels = 1LL << 26;

class TextureReader {
public:
    // `folder`: the scene's folder (absolute, symlinks resolved); allowOutside as GltfOptions'.
    TextureReader(const tinygltf::Model& model, std::filesystem::path folder, bool allowOutside, Report& report);
    // The slot a material's textureInfo describes (index ≥ 0): the texture, read once for each
    // colour space it is read in (sRGB colour, or linear data), its texCoord and transform.
    TextureSlot slot(int index, int texCoord, const tinygltf::ExtensionMap& extensions, bool srgb,
                     const std::string& context);

private:
    std::shared_ptr<const Texture> texture(int index, bool srgb, const std::string& context);
    std::string imageBytes(const tinygltf::Image& image, const std::string& what) const;
    // The texels of an image file's bytes as floats, `channels` (at most 4) a texel; its header
    // checked against the size limits before any texel is allocated.
    std::vector<float> decode(const std::string& bytes, const std::string& name, const std::string& what, int& width,
                              int& height, int& channels) const;

    const tinygltf::Model& model_;
    std::filesystem::path folder_;
    bool allowOutside_;
    Report& report_;
    std::map<std::pair<int, bool>, std::shared_ptr<const Texture>> cache_;
};

}  // namespace tripath::gltf
