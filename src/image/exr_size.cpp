// The fewest bytes an OpenEXR file can take (exr_size.h).
#include "image/exr_size.h"

#include <algorithm>

namespace tripath {

namespace {

uint64_t ceilDiv(uint64_t a, uint64_t b) { return (a + b - 1) / b; }

// Scan lines per chunk, by compression (OpenEXR's table); an unknown one as the most, which
// bounds the file the least.
uint64_t linesPerChunk(const std::string& compression) {
    if (compression == "none" || compression == "rle" || compression == "zips") return 1;
    if (compression == "zip" || compression == "pxr24") return 16;
    if (compression == "piz" || compression == "b44" || compression == "b44a" || compression == "dwaa") return 32;
    return 256;
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

uint64_t leastExrBytes(const ExrLayout& layout) {
    const bool tiled = layout.tileWidth > 0 && layout.tileHeight > 0;
    const uint64_t chunks = tiled ? ceilDiv(layout.width, layout.tileWidth) * ceilDiv(layout.height, layout.tileHeight)
                                  : ceilDiv(layout.height, linesPerChunk(layout.compression));
    const uint64_t perChunk = 8 + (tiled ? 20 : 8);
    const uint64_t ratio = largestRatio(layout.compression);
    using Wide = unsigned __int128;  // claimed sizes overflow 64 bits
    const Wide raw = Wide(layout.width) * layout.height * layout.pixelBytes;
    const Wide data = ratio == 0 ? Wide(chunks) : std::max(Wide(chunks), raw / ratio);
    const Wide least = Wide(chunks) * perChunk + data;
    return least > UINT64_MAX ? UINT64_MAX : uint64_t(least);
}

}  // namespace tripath
