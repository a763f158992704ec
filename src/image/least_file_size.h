// The fewest bytes an OpenEXR, PNG or Radiance HDR file can take, from what its header claims: so
// that a file far too small for its claimed size (a 131 KB file claiming 32768 × 16384 pixels) is
// refused before the pixels are allocated, not after gigabytes and a failed read. Bounds that every
// valid file meets, whatever its pixels: no valid file is refused, while a crafted one of at least
// the bound's size still costs its allocation (within the reader's pixel limit) before it fails.
//
// OpenEXR, for a part's full-resolution level: an offset-table entry (8 bytes) and a
// chunk header (8 bytes for scan lines, 20 for tiles) per chunk, and each chunk's data, which is
// at least its raw bytes over the compression's largest ratio: 1 uncompressed; 64 for RLE (runs
// of at most 128 bytes in 2); 1032 for ZIP and ZIPS (deflate spends at least 2 bits on 258
// bytes) and 1376 for PXR24 (deflate after storing floats in 24 bits); and no bound but 1 byte a
// chunk for PIZ, B44(A) and DWA(A/B), whose ratio for a constant image has none worth stating.
//
// PNG: the signature and the IHDR, IDAT and IEND chunks (57 bytes), and the deflated pixels, at
// least their bits (width × height × channels × bit depth, from the IHDR's colour type and depth:
// one channel for a palette image) over 8 × 1032.
//
// Radiance RGBE (.hdr), per scan line of w pixels: 4 bytes a pixel stored flat, or, where w is
// from 8 to 32767 and the line is run-length encoded, its 4-byte marker and each of the pixels' 4
// bytes in runs of at most 127 equal values, 2 bytes a run: 4 + 8 ⌈w / 127⌉ (the header's text
// lines are not counted).
//
// An OpenEXR file's headers, which give its parts' layouts, are read by tripath before OpenEXR
// opens the file (exr_header.h).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace tripath {

struct ExrLayout {
    uint64_t width = 0, height = 0;          // of the data window
    uint64_t tileWidth = 0, tileHeight = 0;  // 0 for a scan-line file
    uint64_t pixelBytes = 0;                 // all channels of one pixel, as stored
    std::string compression;                 // as OpenImageIO names it: "none", "rle", "zip", "piz", ...
};

// The OpenEXR bound above, UINT64_MAX when it exceeds 64 bits.
uint64_t leastExrBytes(const ExrLayout& layout);

// Scan lines per chunk, by compression (OpenEXR's table); an unknown one as the most.
uint64_t exrLinesPerChunk(const std::string& compression);

// The Radiance HDR bound above for width × height pixels.
uint64_t leastHdrBytes(uint64_t width, uint64_t height);

// The PNG bound above for a file whose first bytes are `start` (its signature and the IHDR up to
// the colour type: 26 bytes); 0 when they are not those of a PNG file.
uint64_t leastPngBytes(std::string_view start);

}  // namespace tripath
