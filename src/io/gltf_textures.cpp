// glTF textures read with OpenImageIO (gltf_textures.h).
//
// An image's bytes come from its bufferView, its data: URI or the file its URI names (refused
// unless resolveExternalFile lets it through, as buffer files are), and OpenImageIO reads them
// from memory (an IOMemReader), as PNG or JPEG by their magic bytes. The header is checked before
// any texel is read, so a file claiming 100000 × 100000 texels costs nothing. The texels are read
// straight into the stored RGBA array, 8 or 16 bits a channel as the file has them (grey
// replicated, a missing alpha set to its largest value), so what the reader holds beyond them is
// the compressed file and OpenImageIO's own buffer. Whether colour is sRGB (base colour,
// emission) or data (metallic-roughness, normals) is the slot's to say, when it is read. Alpha is
// read unassociated, as stored. Samplers: wrapS/wrapT as given, the magnification filter for
// every lookup (no mipmaps: a minification filter's mipmap part reads as its base filter), linear
// when the sampler names none.
#include "io/gltf_textures.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>

#include "core/fnv1a.h"
#include "io/external_files.h"

namespace tripath::gltf {

namespace {

// Files larger than this are refused before they are read (an image of the largest accepted
// size, compressed, is far smaller).
constexpr uintmax_t kMaxImageFileBytes = uintmax_t(1) << 30;

// Reads the open image's first `channels` channels (at most 4) straight into RGBA texels of type
// T, then fills in the rest: grey replicated into green and blue, a missing alpha opaque.
template <class T>
TexelArray<T> readTexels(OIIO::ImageInput& input, int channels, const std::string& what, const Report& report) {
    const OIIO::ImageSpec& spec = input.spec();
    TexelArray<T> texels(size_t(spec.width) * size_t(spec.height));
    if (!input.read_image(0, 0, 0, channels, OIIO::BaseTypeFromC<T>::value, texels.data(), sizeof(texels[0])))
        report.fail(what + ": cannot decode its image: " + quoted(input.geterror()));
    constexpr T opaque = std::numeric_limits<T>::max();
    for (std::array<T, 4>& t : texels) {
        if (channels < 3) t = {t[0], t[0], t[0], channels == 2 ? t[1] : opaque};
        else if (channels == 3) t[3] = opaque;
    }
    return texels;
}

TextureWrap wrapMode(int gl) {
    switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::MirroredRepeat;
    default: return TextureWrap::Repeat;
    }
}

TextureFilter filterMode(int gl) {
    return gl == TINYGLTF_TEXTURE_FILTER_NEAREST ? TextureFilter::Nearest : TextureFilter::Linear;
}

// Keeps what libpng and libjpeg print on stderr (OpenImageIO lets them, then returns the same
// message as its error) off the terminal while it lives: the error is reported once, as the
// scene's one-line failure. Scenes load before any rendering thread starts, so nothing else is
// writing to stderr meanwhile.
class QuietStderr {
public:
    QuietStderr() {
        std::fflush(stderr);
        saved_ = dup(STDERR_FILENO);
        const int null = open("/dev/null", O_WRONLY | O_CLOEXEC);
        if (saved_ >= 0 && null >= 0) dup2(null, STDERR_FILENO);
        if (null >= 0) close(null);
    }
    ~QuietStderr() {
        if (saved_ < 0) return;
        dup2(saved_, STDERR_FILENO);
        close(saved_);
    }
    QuietStderr(const QuietStderr&) = delete;
    QuietStderr& operator=(const QuietStderr&) = delete;

private:
    int saved_ = -1;
};

// The file name whose extension makes OpenImageIO pick the reader, from the magic bytes.
std::string formatName(const std::string& bytes) {
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0) return "image.png";
    if (bytes.size() >= 3 && std::memcmp(bytes.data(), "\xFF\xD8\xFF", 3) == 0) return "image.jpg";
    return {};
}

// The 2 × 3 affine map of KHR_texture_transform: translation · rotation · scale, the rotation
// turning the coordinates counter-clockwise as drawn in glTF's uv space, whose v runs down (the
// image turns clockwise): u' = cos·sx·u + sin·sy·v + ox, v' = −sin·sx·u + cos·sy·v + oy. The
// README's GLSL listing has the transpose, a y-up rotation; Khronos glTF issue #1563, the
// extension's own example (offset [0, 1], rotation π/2, scale 0.5 reads the lower-left quadrant)
// and the TextureTransformTest sample model agree on this sign.
std::array<float, 6> transformMatrix(const tinygltf::Value& t, const std::string& what, const Report& report) {
    auto pair = [&](const char* key, float fallback, float out[2]) {
        out[0] = out[1] = fallback;
        if (!t.Has(key)) return;
        const tinygltf::Value& v = t.Get(key);
        if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
            report.fail(what + ": KHR_texture_transform." + key + " is not two numbers");
        for (int i = 0; i < 2; ++i) out[i] = float(v.Get(i).GetNumberAsDouble());
    };
    float offset[2], scale[2];
    pair("offset", 0.0f, offset);
    pair("scale", 1.0f, scale);
    float rotation = 0;
    if (t.Has("rotation")) {
        if (!t.Get("rotation").IsNumber()) report.fail(what + ": KHR_texture_transform.rotation is not a number");
        rotation = float(t.Get("rotation").GetNumberAsDouble());
    }
    const float c = std::cos(rotation), s = std::sin(rotation);
    const std::array<float, 6> m{c * scale[0], s * scale[1], offset[0], -s * scale[0], c * scale[1], offset[1]};
    for (float x : m)
        if (!std::isfinite(x)) report.fail(what + ": KHR_texture_transform is not finite");
    return m;
}

}  // namespace

TextureReader::TextureReader(const tinygltf::Model& model, std::filesystem::path folder, bool allowOutside,
                             Report& report, std::vector<SourceFile>& sources)
    : model_(model), folder_(std::move(folder)), allowOutside_(allowOutside), report_(report), sources_(sources) {}

TextureSlot TextureReader::slot(int index, int texCoord, const tinygltf::ExtensionMap& extensions, ColourSpace space,
                                const std::string& context) {
    TextureSlot s;
    const std::string what = context + "texture " + std::to_string(index);
    s.texture = texture(index, what);
    s.texCoord = texCoord;
    s.colourSpace = space;
    const auto it = extensions.find("KHR_texture_transform");
    if (it != extensions.end() && it->second.IsObject()) {
        s.transform = transformMatrix(it->second, what, report_);
        if (it->second.Has("texCoord") && it->second.Get("texCoord").IsInt())
            s.texCoord = it->second.Get("texCoord").GetNumberAsInt();
    }
    if (s.texCoord < 0 || s.texCoord > 1)
        report_.fail(what + ": texCoord " + std::to_string(s.texCoord) + " (only TEXCOORD_0 and _1 are read)");
    return s;
}

std::string TextureReader::embeddedBytes(const tinygltf::Image& image, const std::string& what) const {
    if (image.bufferView < 0)  // a data: URI's bytes (gltf_file.cpp)
        return std::string(image.image.begin(), image.image.end());
    if (size_t(image.bufferView) >= model_.bufferViews.size()) report_.fail(what + ": its bufferView does not exist");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(image.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size())
        report_.fail(what + ": its buffer does not exist");
    const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        report_.fail(what + ": its bufferView runs past the end of its buffer");
    return std::string(reinterpret_cast<const char*>(data.data()) + view.byteOffset, view.byteLength);
}

std::filesystem::path TextureReader::imageFile(const tinygltf::Image& image, const std::string& what) const {
    if (image.uri.empty()) report_.fail(what + ": its image has no data");
    if (!uriScheme(image.uri).empty())
        report_.fail(what + ": uri " + quoted(image.uri) +
                     " has a URI scheme (only data: URIs and file paths are read)");
    const ExternalFile file = resolveExternalFile(folder_, decodeUriPath(image.uri), allowOutside_);
    if (!file.problem.empty())  // as a buffer's refusal says it (gltf_file.cpp)
        report_.fail(what + ": uri " + quoted(image.uri) + " names " +
                     quoted(file.path.string(), folder_.string().size() + kExcerptLength) + ", " + file.problem);
    return file.path;
}

std::shared_ptr<const TextureImage> TextureReader::decode(const std::string& bytes, const std::string& what) const {
    const std::string name = formatName(bytes);
    if (name.empty()) report_.fail(what + ": its image is not a PNG or JPEG file");
    const QuietStderr quiet;
    OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
    // The texels as stored: glTF's colour and alpha are independent (its alpha is coverage for
    // MASK, and normal or metallic-roughness maps may carry any fourth channel), while PNG readers
    // multiply colour by alpha unless told otherwise.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    void* proxy = &memory;
    config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto input = OIIO::ImageInput::open(name, &config, &memory);
    if (!input) report_.fail(what + ": cannot read its image: " + quoted(OIIO::geterror()));
    const OIIO::ImageSpec& spec = input->spec();
    const long long pixels = (long long)spec.width * spec.height;
    if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxTextureSide || spec.height > kMaxTextureSide ||
        pixels > kMaxTexturePixels || spec.nchannels < 1)
        report_.fail(what + ": its image claims " + std::to_string(spec.width) + " x " + std::to_string(spec.height) +
                     " texels (at most 16384 a side and 2^26 in all are read)");
    const int channels = std::min(spec.nchannels, 4);
    // PNG stores 1, 2, 4, 8 or 16 bits a channel (those below 8 are read as bytes), JPEG 8.
    if (spec.format.size() <= 1)
        return std::make_shared<const TextureImage>(spec.width, spec.height,
                                                    readTexels<uint8_t>(*input, channels, what, report_));
    return std::make_shared<const TextureImage>(spec.width, spec.height,
                                                readTexels<uint16_t>(*input, channels, what, report_));
}

std::shared_ptr<const TextureImage> TextureReader::image(int index, const std::string& what) {
    if (auto it = images_.find(index); it != images_.end()) return it->second;
    const tinygltf::Image& source = model_.images[size_t(index)];
    std::shared_ptr<const TextureImage> decoded;
    if (source.bufferView >= 0 || !source.image.empty()) {
        decoded = decode(embeddedBytes(source, what), what);
    } else {
        const std::filesystem::path file = imageFile(source, what);
        if (auto it = files_.find(file); it != files_.end()) {
            decoded = it->second;
        } else {
            std::error_code ec;
            const uintmax_t size = std::filesystem::file_size(file, ec);
            if (ec || size > kMaxImageFileBytes)
                report_.fail(what + ": " + quoted(source.uri) + " is unreadable or over 1 GiB");
            std::string bytes(size_t(size), '\0');
            std::ifstream in(file, std::ios::binary);
            if (!in || !in.read(bytes.data(), std::streamsize(bytes.size())))
                report_.fail(what + ": cannot read " + quoted(source.uri));
            sources_.push_back({decodeUriPath(source.uri), fnv1a(bytes)});
            decoded = files_[file] = decode(bytes, what);
        }
    }
    images_[index] = decoded;
    return decoded;
}

std::shared_ptr<const Texture> TextureReader::texture(int index, const std::string& what) {
    if (index < 0 || size_t(index) >= model_.textures.size()) report_.fail(what + " does not exist");
    if (auto it = textures_.find(index); it != textures_.end()) return it->second;
    const tinygltf::Texture& tex = model_.textures[size_t(index)];
    if (tex.source < 0 || size_t(tex.source) >= model_.images.size())
        report_.fail(what + " has no PNG or JPEG source image (extension images are not read)");
    TextureWrap wrapU = TextureWrap::Repeat, wrapV = TextureWrap::Repeat;
    TextureFilter filter = TextureFilter::Linear;
    if (tex.sampler >= 0 && size_t(tex.sampler) < model_.samplers.size()) {
        const tinygltf::Sampler& sampler = model_.samplers[size_t(tex.sampler)];
        wrapU = wrapMode(sampler.wrapS);
        wrapV = wrapMode(sampler.wrapT);
        filter = filterMode(sampler.magFilter);
    }
    auto texture = std::make_shared<const Texture>(image(tex.source, what), wrapU, wrapV, filter);
    textures_[index] = texture;
    return texture;
}

}  // namespace tripath::gltf
