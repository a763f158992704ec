// glTF textures → Texture (geometry/texture.h): the images read with OpenImageIO from the buffer
// views, data: URIs or files (in the scene's folder, as for buffers: external_files.h) they come
// from, stored as the file stores its texels (8 or 16 bits a channel), with their samplers and
// KHR_texture_transform. A header of the io library's own.
#pragma once
#include <tiny_gltf.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "geometry/scene_desc.h"
#include "geometry/texture.h"
#include "io/gltf_checks.h"

namespace tripath::gltf {

// The largest image read: a side of 16384 texels and 2^26 texels in all (256 MiB as 8-bit RGBA,
// 512 MiB as 16-bit). A header claiming more is refused before any texel is allocated.
constexpr int kMaxTextureSide = 16384;
constexpr long long kMaxTexturePixels = 1LL << 26;

class TextureReader {
public:
    // `folder`: the scene's folder (absolute, symlinks resolved); allowOutside as GltfOptions'. Each
    // image file read is added to `sources`, by its decoded URI, hashed from the bytes decoded.
    TextureReader(const tinygltf::Model& model, std::filesystem::path folder, bool allowOutside, Report& report,
                  std::vector<SourceFile>& sources);
    // The slot a material's textureInfo describes (index ≥ 0): the texture, its colour channels
    // read in colour space `space`, its texCoord and transform. Each texture is made once, and
    // each image decoded once, however many textures and colour spaces use it: by image index,
    // and by file for image files (two image entries naming one file share it).
    TextureSlot slot(int index, int texCoord, const tinygltf::ExtensionMap& extensions, ColourSpace space,
                     const std::string& context);

private:
    std::shared_ptr<const Texture> texture(int index, const std::string& what);
    std::shared_ptr<const TextureImage> image(int index, const std::string& what);
    // The bytes of an image held in the glTF itself (a bufferView or a data: URI).
    std::string embeddedBytes(const tinygltf::Image& image, const std::string& what) const;
    // The file an image's URI names, refused unless resolveExternalFile lets it through.
    std::filesystem::path imageFile(const tinygltf::Image& image, const std::string& what) const;
    // The texels of an image file's bytes, as many bits a channel as it stores; its header checked
    // against the size limits before any texel is allocated.
    std::shared_ptr<const TextureImage> decode(const std::string& bytes, const std::string& what) const;

    const tinygltf::Model& model_;
    std::filesystem::path folder_;
    bool allowOutside_;
    Report& report_;
    std::vector<SourceFile>& sources_;
    std::map<int, std::shared_ptr<const Texture>> textures_;         // by texture index
    std::map<int, std::shared_ptr<const TextureImage>> images_;      // by image index
    std::map<std::filesystem::path, std::shared_ptr<const TextureImage>> files_;  // by resolved path
};

}  // namespace tripath::gltf
