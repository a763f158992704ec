#include "image/image.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <string_view>
#include <system_error>

#include "core/atomic_file.h"
#include "core/error.h"
#include "image/exr_header.h"
#include "image/least_file_size.h"

namespace tripath {

namespace fs = std::filesystem;

Image::Image(int w, int h) : width(w), height(h) {
    if (w < 0 || h < 0) throw InputError(fmt::format("invalid image size {}x{}", w, h));
    rgb.assign(3 * pixelCount(), 0.0f);
}

namespace {

// OIIO messages can span several lines (e.g. one per plugin it tried); the
// user sees a single line, so collapse line breaks and trim the ends.
std::string oneLine(std::string_view msg) {
    std::string out;
    out.reserve(msg.size());
    bool pendingBreak = false;
    for (char c : msg) {
        if (c == '\n' || c == '\r') {
            pendingBreak = true;
            continue;
        }
        if (pendingBreak && !out.empty()) out += "; ";
        pendingBreak = false;
        out += c;
    }
    while (!out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
    return out.empty() ? std::string("unknown OpenImageIO error") : out;
}

// Errors may sit on the object or, when no object could be created, in
// OIIO's global slot. Always drain both: OIIO complains on stderr at exit
// about errors nobody retrieved.
template <class T>
std::string oiioError(const T* obj) {
    std::string msg = obj ? obj->geterror() : std::string();
    std::string global = OIIO::geterror();
    if (msg.empty()) msg = global;
    return oneLine(msg);
}

void checkImage(const std::string& path, const Image& img) {
    if (img.width <= 0 || img.height <= 0)
        throw InputError(fmt::format("cannot write '{}': image is empty ({}x{})", path, img.width, img.height));
    if (img.rgb.size() != 3 * img.pixelCount())
        throw InputError(fmt::format("cannot write '{}': image has {} floats, expected {} for {}x{} RGB", path,
                                     img.rgb.size(), 3 * img.pixelCount(), img.width, img.height));
}

// Writes through core/atomic_file.h's temporary file, with OpenImageIO's writer for `format`.
void atomicWrite(const std::string& path, std::string_view format, std::string_view ext,
                 const std::function<void(OIIO::ImageOutput&, const std::string&)>& write) {
    replaceAtomically(path, std::string(ext), [&](const std::string& tmp) {
        // Create by format name, not by the target's extension, so that
        // "out.EXR" or an extension-less target still gets the right format.
        auto out = OIIO::ImageOutput::create(format);
        if (!out)
            throw InputError(fmt::format("cannot write '{}': no {} writer: {}", path, format,
                                         oiioError<OIIO::ImageOutput>(nullptr)));
        write(*out, tmp);
        if (!out->close()) throw InputError(fmt::format("cannot write '{}': {}", path, oiioError(out.get())));
    });
}

void openAndWrite(OIIO::ImageOutput& out, const std::string& tmp, const std::string& path,
                  const OIIO::ImageSpec& spec, const void* pixels) {
    if (!out.open(tmp, spec)) throw InputError(fmt::format("cannot write '{}': {}", path, oiioError(&out)));
    if (!out.write_image(spec.format, pixels))
        throw InputError(fmt::format("cannot write '{}': {}", path, oiioError(&out)));
}

// Refuses a PNG or Radiance HDR file too small to hold the pixels its header claims
// (least_file_size.h); OpenEXR files are checked before they are opened (checkExrHeaders).
void checkFileSize(const std::string& path, const OIIO::ImageInput& in) {
    const std::string_view format = in.format_name();
    const OIIO::ImageSpec& spec = in.spec();
    uint64_t least = 0;
    if (format == "png") {
        std::string start(29, '\0');
        std::ifstream file(path, std::ios::binary);
        file.read(start.data(), std::streamsize(start.size()));
        least = leastPngBytes(std::string_view(start.data(), size_t(file.gcount())));
    } else if (format == "hdr") {
        least = leastHdrBytes(uint64_t(spec.width), uint64_t(spec.height));
    }
    std::error_code ec;
    const uintmax_t size = fs::file_size(path, ec);
    if (!ec && size < least)
        throw InputError(fmt::format("cannot read '{}': its header claims {}x{} pixels, which take at least {} bytes, "
                                     "and the file has {}",
                                     path, spec.width, spec.height, least, size));
}

// Refuses, unopened, an OpenEXR file (known by its content, not its name: OpenImageIO tries every
// reader on a file the one its name gives cannot open) shorter than what its headers claim or than
// its parts' pixels need (least_file_size.h), or whose first part OpenEXR would decode in chunks
// larger than the bytes of `maxPixels` RGB floats, the largest image the caller takes
// (exr_header.h).
void checkExrHeaders(const std::string& path, std::size_t maxPixels) {
    std::ifstream file(path, std::ios::binary);
    const std::optional<ExrHeaders> headers = readExrHeaders(file);
    std::error_code ec;
    const uintmax_t size = fs::file_size(path, ec);
    if (!headers || ec) return;
    if (size < headers->end)
        throw InputError(fmt::format("cannot read '{}': its OpenEXR header claims {} bytes, and the file has {}", path,
                                     headers->end, size));
    if (headers->parts.empty()) return;
    uint64_t least = headers->end;
    for (const ExrLayout& part : headers->parts) least += std::min(leastExrBytes(part), UINT64_MAX - least);
    const ExrLayout& first = headers->parts.front();
    if (size < least)
        throw InputError(fmt::format("cannot read '{}': its header claims {}x{} pixels (compression: {}), which take "
                                     "at least {} bytes, and the file has {}",
                                     path, first.width, first.height, first.compression, least, size));
    const uint64_t chunk = exrChunkBytes(first);
    const uint64_t budget = maxPixels > UINT64_MAX / 12 ? UINT64_MAX : 12 * uint64_t(maxPixels);
    if (chunk > budget)
        throw InputError(fmt::format("cannot read '{}': OpenEXR would decode it in chunks of {} bytes, more than the "
                                     "{} of the largest image read here ({} pixels)",
                                     path, chunk, budget, maxPixels));
}

Image readAny(const std::string& path, bool requireExr, Metadata* meta, std::size_t maxPixels = SIZE_MAX,
              std::vector<ExrChannel>* channels = nullptr) {
    std::error_code ec;
    if (!fs::exists(path, ec)) throw InputError(fmt::format("cannot read '{}': file does not exist", path));
    if (fs::is_directory(path, ec)) throw InputError(fmt::format("cannot read '{}': it is a directory", path));
    // A device or FIFO would never end (/dev/zero) or block until a writer comes.
    if (!fs::is_regular_file(path, ec)) throw InputError(fmt::format("cannot read '{}': not a regular file", path));

    // By default OIIO premultiplies colour by alpha on read; we want the
    // stored colour values untouched.
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    checkExrHeaders(path, maxPixels);
    auto in = OIIO::ImageInput::open(path, &config);
    if (!in) throw InputError(fmt::format("cannot read '{}': {}", path, oiioError<OIIO::ImageInput>(nullptr)));

    if (requireExr && std::string_view(in->format_name()) != "openexr")
        throw InputError(fmt::format("cannot read '{}': not an OpenEXR file (looks like {})", path, in->format_name()));

    // Copy: the reference returned by spec() is only valid while `in` lives.
    const OIIO::ImageSpec spec = in->spec();
    if (spec.deep) throw InputError(fmt::format("cannot read '{}': deep images are not supported", path));
    if (spec.depth > 1) throw InputError(fmt::format("cannot read '{}': volume images are not supported", path));
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
        throw InputError(fmt::format("cannot read '{}': image has no pixels", path));
    if (std::size_t(spec.width) * std::size_t(spec.height) > maxPixels)
        throw InputError(fmt::format("cannot read '{}': {}x{} pixels is more than the {} allowed", path, spec.width,
                                     spec.height, maxPixels));
    checkFileSize(path, *in);

    // Only the data window is read; an EXR whose data window is offset from
    // its display window is taken as-is (tripath never writes one).
    Image img(spec.width, spec.height);
    bool ok;
    if (spec.nchannels >= 3) {
        // EXR channels come back sorted R, G, B, (A, ...), so 0..3 is RGB.
        ok = in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, img.rgb.data());
    } else {
        // Grey (or grey + alpha): replicate the first channel.
        std::vector<float> grey(img.pixelCount());
        ok = in->read_image(0, 0, 0, 1, OIIO::TypeDesc::FLOAT, grey.data());
        for (std::size_t i = 0; ok && i < grey.size(); ++i)
            img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = grey[i];
    }
    if (!ok) throw InputError(fmt::format("cannot read '{}': {}", path, oiioError(in.get())));
    if (channels) {
        channels->clear();
        for (int c = 3; c < spec.nchannels; ++c) {
            ExrChannel channel{spec.channelnames[size_t(c)], std::vector<float>(img.pixelCount())};
            if (!in->read_image(0, 0, c, c + 1, OIIO::TypeDesc::FLOAT, channel.values.data()))
                throw InputError(fmt::format("cannot read '{}': {}", path, oiioError(in.get())));
            channels->push_back(std::move(channel));
        }
    }

    if (meta) {
        meta->clear();
        for (const OIIO::ParamValue& p : spec.extra_attribs) {
            if (p.type() != OIIO::TypeDesc::STRING) continue;
            std::string_view name(p.name().data(), p.name().size());
            if (name.substr(0, 8) != "tripath:") continue;
            meta->emplace_back(std::string(name), p.get_string());
        }
    }
    in->close();
    return img;
}

}  // namespace

void writeExr(const std::string& path, const Image& img, const Metadata& meta, const std::vector<ExrChannel>& channels) {
    checkImage(path, img);
    for (const auto& [key, value] : meta)
        if (key.empty()) throw InputError(fmt::format("cannot write '{}': metadata with an empty name", path));
    for (const ExrChannel& c : channels) {
        if (c.name.empty() || c.name == "R" || c.name == "G" || c.name == "B")
            throw InputError(fmt::format("cannot write '{}': a channel beside R, G, B named '{}'", path, c.name.substr(0, 20)));
        if (c.values.size() != img.pixelCount())
            throw InputError(fmt::format("cannot write '{}': channel {} has {} values for {} pixels", path,
                                         c.name.substr(0, 20), c.values.size(), img.pixelCount()));
    }

    // R, G, B and the channels, interleaved pixel by pixel as OpenImageIO writes them.
    const size_t n = 3 + channels.size();
    std::vector<float> pixels;
    if (!channels.empty()) {
        pixels.resize(n * img.pixelCount());
        for (size_t i = 0; i < img.pixelCount(); ++i) {
            std::copy_n(img.rgb.data() + 3 * i, 3, pixels.data() + n * i);
            for (size_t c = 0; c < channels.size(); ++c) pixels[n * i + 3 + c] = channels[c].values[i];
        }
    }
    atomicWrite(path, "openexr", ".exr", [&](OIIO::ImageOutput& out, const std::string& tmp) {
        OIIO::ImageSpec spec(img.width, img.height, int(n), OIIO::TypeDesc::FLOAT);
        for (size_t c = 0; c < channels.size(); ++c) spec.channelnames[3 + c] = channels[c].name;
        spec.attribute("compression", "zip");
#ifdef TRIPATH_VERSION
        spec.attribute("Software", "tripath " TRIPATH_VERSION);
#endif
        for (const auto& [key, value] : meta) spec.attribute(key, value);
        openAndWrite(out, tmp, path, spec, channels.empty() ? img.rgb.data() : pixels.data());
    });
}

namespace {

// Clamped to [0, 1] first (`!(v > 0)` also makes NaN black), then OpenImageIO's linear → sRGB
// transfer function, then rounded to 8 bits as OpenImageIO converts floats.
std::vector<unsigned char> srgbBytes(const std::string& path, const Image& img, float exposureStops) {
    const float scale = std::exp2(exposureStops);
    std::vector<float> clamped(img.rgb.size());
    for (std::size_t i = 0; i < clamped.size(); ++i) {
        const float v = img.rgb[i] * scale;
        clamped[i] = !(v > 0) ? 0.0f : std::min(v, 1.0f);
    }
    const OIIO::ImageBuf linear(OIIO::ImageSpec(img.width, img.height, 3, OIIO::TypeDesc::FLOAT), clamped.data());
    OIIO::ImageBuf srgb;
    if (!OIIO::ImageBufAlgo::colorconvert(srgb, linear, "linear", "sRGB"))
        throw InputError(fmt::format("cannot write '{}': sRGB conversion failed: {}", path, srgb.geterror()));
    std::vector<unsigned char> bytes(img.rgb.size());
    srgb.get_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, bytes.data());
    return bytes;
}

}  // namespace

std::vector<unsigned char> previewBytes(const Image& img) { return srgbBytes("a figure", img, 0); }

void writePng(const std::string& path, const Image& img, float exposureStops) {
    checkImage(path, img);
    const std::vector<unsigned char> bytes = srgbBytes(path, img, exposureStops);
    atomicWrite(path, "png", ".png", [&](OIIO::ImageOutput& out, const std::string& tmp) {
        OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
        // Tags the file as sRGB (an sRGB chunk) so viewers do not re-guess.
        spec.attribute("oiio:ColorSpace", "sRGB");
        openAndWrite(out, tmp, path, spec, bytes.data());
    });
}

Image readExr(const std::string& path, Metadata* meta, std::vector<ExrChannel>* channels) {
    return readAny(path, true, meta, SIZE_MAX, channels);
}

Image readImage(const std::string& path, std::size_t maxPixels) { return readAny(path, false, nullptr, maxPixels); }

}  // namespace tripath
