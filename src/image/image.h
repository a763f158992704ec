// Float RGB images and their file I/O (OpenEXR for data, PNG for previews).
// OpenImageIO stays private to image.cpp (and text.cpp) so that the rest of the renderer
// does not pay its compile cost or inherit its headers.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/atomic_file.h"
#include "core/srgb.h"  // checkWritable, which callers of the writers below ask first

namespace tripath {

// Linear RGB, row-major, origin top-left (the same convention as EXR and PNG,
// so no flipping happens on I/O).
struct Image {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 * width * height

    Image() = default;
    Image(int w, int h);  // zero-filled; throws InputError on negative sizes

    float* at(int x, int y) { return rgb.data() + index(x, y); }
    const float* at(int x, int y) const { return rgb.data() + index(x, y); }

    std::size_t pixelCount() const { return std::size_t(width) * std::size_t(height); }

private:
    std::size_t index(int x, int y) const {
        return 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
    }
};

// Written as EXR string attributes, e.g. {"tripath:integrator", "bdpt"}.
using Metadata = std::vector<std::pair<std::string, std::string>>;

// A channel of an EXR beside R, G and B: one value per pixel, row by row, under a name such as
// "auto.merge" (OpenEXR's convention: a layer's name, a dot, the channel's).
struct ExrChannel {
    std::string name;
    std::vector<float> values;
};

// All writers are atomic: the image goes to a temporary file in the target's
// directory which is then renamed over the target, so an interrupted or
// failed write never leaves a truncated file under the real name.
// Every failure throws InputError with one line naming the path.

// 32-bit float RGB, ZIP compression, plus `meta` as string attributes and `channels` after R, G, B
// (each of the image's size, named neither empty nor R, G or B).
void writeExr(const std::string& path, const Image& img, const Metadata& meta = {},
              const std::vector<ExrChannel>& channels = {});

// Preview: scale by 2^exposureStops, clamp to [0, 1], apply the sRGB OETF (OpenImageIO's colour
// conversion), round to 8 bits.
void writePng(const std::string& path, const Image& img, float exposureStops = 0);
// The 8-bit RGB values, row by row, that writePng writes (exposed at 0 stops): what a figure that
// embeds the image shows, so that it matches the image's PNG byte for byte.
std::vector<unsigned char> previewBytes(const Image& img);

// The readers take regular files only (symlinks to them too): a directory, device, FIFO or socket
// is refused, unopened, with InputError.

// Reads the first three channels of an OpenEXR file (a one- or two-channel
// file is read as grey). If `meta` is given it receives the string attributes
// whose names start with "tripath:", sorted by name (OpenEXR keeps header
// attributes in a sorted map, so the order they were written in is lost). If `channels` is given
// it receives the channels after R, G and B (A included), in the file's order: sorted by name.
Image readExr(const std::string& path, Metadata* meta = nullptr, std::vector<ExrChannel>* channels = nullptr);

// Reads any format OpenImageIO understands as float RGB, without colour
// conversion: an 8-bit PNG value v comes back as v / 255. A header that claims more than
// `maxPixels` pixels is refused before anything is allocated.
Image readImage(const std::string& path, std::size_t maxPixels = SIZE_MAX);

// srgbDecode (core/srgb.h) of an 8-bit code c (as in CSS "#rrggbb") is srgbDecode(c / 255.0f),
// which writePng writes back as c.

}  // namespace tripath
