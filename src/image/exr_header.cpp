// An OpenEXR file's headers, read before OpenEXR reads them (exr_header.h).
#include "image/exr_header.h"

#include <array>
#include <string>
#include <string_view>

namespace tripath {

namespace {

using Wide = unsigned __int128;  // claimed sizes overflow 64 bits

// A little-endian 32-bit integer from 4 bytes.
uint32_t little32(const char* p) {
    return uint32_t(uint8_t(p[0])) | uint32_t(uint8_t(p[1])) << 8 | uint32_t(uint8_t(p[2])) << 16 |
           uint32_t(uint8_t(p[3])) << 24;
}

// OpenEXR's compressions by their code in the file, as OpenImageIO names them.
constexpr std::array<const char*, 10> kCompressions{"none", "rle",   "zips", "zip",  "piz",
                                                    "pxr24", "b44", "b44a", "dwaa", "dwab"};

// The stored bytes of one pixel over the channels of a chlist value: 2 for a half, 4 for a float
// or an unsigned int (subsampled channels counted at every pixel: an upper bound). Nothing if the
// list is malformed.
std::optional<uint64_t> pixelBytes(std::string_view list) {
    uint64_t bytes = 0;
    for (;;) {
        const size_t nameEnd = list.find('\0');
        if (nameEnd == std::string_view::npos) return std::nullopt;
        if (nameEnd == 0) return bytes;  // the list's end
        if (list.size() < nameEnd + 1 + 16) return std::nullopt;
        const uint32_t type = little32(list.data() + nameEnd + 1);  // then pLinear, 3 reserved, x and y sampling
        if (type > 2) return std::nullopt;
        bytes += type == 1 ? 2 : 4;
        list.remove_prefix(nameEnd + 1 + 16);
    }
}

// What the header has told of its part so far.
struct PartSoFar {
    ExrLayout layout{.width = 64, .height = 64, .compression = "zip"};  // OpenEXR's defaults
    bool deep = false;       // deep data: no pixels of a fixed size, and never read (image.cpp)
    bool malformed = false;  // OpenEXR refuses the file
};

// The attributes that shape a part's pixels, and whether it is deep.
bool shapesPixels(std::string_view name) {
    return name == "dataWindow" || name == "compression" || name == "tiles" || name == "channels" || name == "type";
}

// The part an attribute describes, updated by its value.
void describe(PartSoFar& so, std::string_view name, std::string_view type, std::string_view value) {
    ExrLayout& part = so.layout;
    bool& malformed = so.malformed;
    if (name == "type" && type == "string") {
        so.deep = value.starts_with("deep");
    } else if (name == "dataWindow" && type == "box2i" && value.size() == 16) {
        const auto xMin = int64_t(int32_t(little32(value.data()))), yMin = int64_t(int32_t(little32(value.data() + 4)));
        const auto xMax = int64_t(int32_t(little32(value.data() + 8))), yMax = int64_t(int32_t(little32(value.data() + 12)));
        malformed |= xMax < xMin || yMax < yMin;
        part.width = uint64_t(xMax - xMin + 1);
        part.height = uint64_t(yMax - yMin + 1);
    } else if (name == "compression" && type == "compression" && value.size() == 1) {
        const auto code = uint8_t(value[0]);
        malformed |= code >= kCompressions.size();
        if (code < kCompressions.size()) part.compression = kCompressions[code];
    } else if (name == "tiles" && type == "tiledesc" && value.size() == 9) {
        part.tileWidth = little32(value.data());
        part.tileHeight = little32(value.data() + 4);
    } else if (name == "channels" && type == "chlist") {
        const std::optional<uint64_t> bytes = pixelBytes(value);
        malformed |= !bytes;
        part.pixelBytes = bytes.value_or(0);
    }
}

}  // namespace

std::optional<ExrHeaders> readExrHeaders(std::istream& file) {
    char start[8];
    if (!file.read(start, 8) || std::string_view(start, 4) != "\x76\x2f\x31\x01") return std::nullopt;
    const bool multiPart = uint8_t(start[5]) & 0x10;  // bit 12 of the version field
    ExrHeaders headers{.end = 8, .parts = {}};
    // A name or a type: at most 255 characters and its terminating zero; nothing if there is none.
    auto word = [&]() -> std::optional<std::string> {
        std::string w;
        for (char c; w.size() < 256 && file.get(c);) {
            if (c == '\0') return w;
            w += c;
        }
        return std::nullopt;
    };
    for (;;) {  // each part's header
        PartSoFar part;
        for (;;) {  // each attribute
            const std::optional<std::string> name = word();
            if (!name) return headers;
            headers.end += name->size() + 1;
            if (name->empty()) break;  // the header's end
            const std::optional<std::string> type = word();
            char size[4];
            if (!type || !file.read(size, 4) || int32_t(little32(size)) < 0) return headers;
            const uint32_t bytes = little32(size);
            headers.end += type->size() + 1 + 4 + uint64_t(bytes);
            if (shapesPixels(*name)) {
                // Such a value is small (a list of thousands of channels is not 1 MB): one that
                // claims more ends the walk rather than be allocated.
                if (bytes > (1u << 20)) return headers;
                std::string value(bytes, '\0');
                if (!file.read(value.data(), std::streamsize(bytes))) return headers;
                describe(part, *name, *type, value);
            } else if (!file.seekg(bytes, std::ios::cur)) {
                return headers;
            }
        }
        if (part.malformed) return headers;
        if (!part.deep) headers.parts.push_back(part.layout);
        if (!multiPart || file.peek() == '\0' || !file) return headers;
    }
}

uint64_t exrChunkBytes(const ExrLayout& part) {
    const bool tiled = part.tileWidth > 0 && part.tileHeight > 0;
    const Wide pixels = tiled ? Wide(part.tileWidth) * part.tileHeight : Wide(part.width) * exrLinesPerChunk(part.compression);
    const Wide bytes = pixels * part.pixelBytes;
    return bytes > UINT64_MAX ? UINT64_MAX : uint64_t(bytes);
}

}  // namespace tripath
