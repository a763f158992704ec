// An OpenEXR file's headers as tripath reads them before OpenEXR does. Opening a file, OpenEXR
// allocates what its headers claim before it reads a pixel: each attribute's value at the size
// the header gives it, each part's table of chunk offsets, and a buffer for a whole chunk of the
// part read (a chunk's scan lines across the data window, or a tile, all channels). A file of a
// few hundred bytes could so cost gigabytes: a string attribute claiming 1.9 GB, or a data window
// 10 million pixels wide whose 32-line chunk takes 1.96 GB. The image reader (image.cpp) reads
// the headers first and refuses such a file unopened: shorter than its headers and their parts'
// least sizes (least_file_size.h), or with a chunk larger than the largest image it may read.
//
// The walk reads each attribute's name, type and size and skips its value, but for those that
// shape the pixels: dataWindow, compression, tiles, channels, and type (deep parts, which hold no
// pixels of a fixed size and are never read, are left out). Where a header leaves one out, the
// part has OpenEXR's default (a 64 × 64 window, ZIP); anything malformed ends the walk, and
// OpenEXR refuses the file itself.
#pragma once
#include <cstdint>
#include <istream>
#include <optional>
#include <vector>

#include "image/least_file_size.h"

namespace tripath {

struct ExrHeaders {
    uint64_t end = 0;              // the offset where the walk ended: the headers' bytes, as claimed
    std::vector<ExrLayout> parts;  // the parts, not deep, whose headers the walk read to their end
};

// The headers of the file `file` holds (read from its start); nothing if it does not start as an
// OpenEXR file.
std::optional<ExrHeaders> readExrHeaders(std::istream& file);

// The bytes OpenEXR decodes one chunk of the part into: its lines per chunk (by compression) or its
// tile, across the data window, all channels (UINT64_MAX beyond 64 bits).
uint64_t exrChunkBytes(const ExrLayout& part);

}  // namespace tripath
