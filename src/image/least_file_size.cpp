// The fewest bytes an OpenEXR, PNG or Radiance HDR file can take (least_file_size.h).
#include "image/least_file_size.h"

#include <algorithm>

namespace tripath {

namespace {

using Wide = unsigned __int128;  // claimed sizes overflow 64 bits

uint64_t ceilDiv(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

uint64_t saturated(Wide v) { return v > UINT64_MAX ? UINT64_MAX : uint64_t(v); }

uint32_t bigEndian32(const char* p) {
    return uint32_t(uint8_t(p[0])) << 24 | uint32_t(uint8_t(p[1])) << 16 | uint32_t(uint8_t(p[2])) << 8 | uint8_t(p[3]);
}

// The largest ratio of raw to stored bytes, 0 where none is stated.
uint64_t largestRatio(const std::string& compression) {
    if (compression == "none") return 1;
    if (compression == "rle") return 64;
    if (compression == "zip" || compression == "zips") return 1032;
    if (compression == "pxr24") return 1376;
    return 0;
}

}  // namespace

uint64_t exrLinesPerChunk(const std::string& compression) {
    if (compression == "none" || compression == "rle" || compression == "zips") return 1;
    if (compression == "zip" || compression == "pxr24") return 16;
    if (compression == "piz" || compression == "b44" || compression == "b44a" || compression == "dwaa") return 32;
    return 256;
}

uint64_t leastExrBytes(const ExrLayout& layout) {
    const bool tiled = layout.tileWidth > 0 && layout.tileHeight > 0;
    const uint64_t chunks = tiled ? ceilDiv(layout.width, layout.tileWidth) * ceilDiv(layout.height, layout.tileHeight)
                                  : ceilDiv(layout.height, exrLinesPerChunk(layout.compression));
    const uint64_t perChunk = 8 + (tiled ? 20 : 8);
    const uint64_t ratio = largestRatio(layout.compression);
    const Wide raw = Wide(layout.width) * layout.height * layout.pixelBytes;
    const Wide data = ratio == 0 ? Wide(chunks) : std::max(Wide(chunks), raw / ratio);
    return saturated(Wide(chunks) * perChunk + data);
}

uint64_t leastHdrBytes(uint64_t width, uint64_t height) {
    const uint64_t flat = 4 * width;
    const uint64_t line = width >= 8 && width <= 0x7fff ? std::min(flat, 4 + 8 * ceilDiv(width, 127)) : flat;
    return saturated(Wide(line) * height);
}

uint64_t leastPngBytes(std::string_view start) {
    // The signature (8 bytes), then the IHDR chunk: length, "IHDR", width, height, bit depth,
    // colour type, ...
    if (start.size() < 26 || start.substr(0, 8) != "\x89PNG\r\n\x1a\n" || start.substr(12, 4) != "IHDR") return 0;
    const uint64_t width = bigEndian32(start.data() + 16), height = bigEndian32(start.data() + 20);
    const auto depth = uint64_t(uint8_t(start[24]));
    uint64_t channels = 0;
    switch (uint8_t(start[25])) {
    case 0: case 3: channels = 1; break;  // grey; palette indices
    case 4: channels = 2; break;          // grey and alpha
    case 2: channels = 3; break;          // RGB
    case 6: channels = 4; break;          // RGBA
    default: return 0;
    }
    return saturated(57 + Wide(width) * height * channels * depth / (8 * 1032));
}

}  // namespace tripath
