// PNG files written byte for byte by the tests themselves (ISO/IEC 15948): the signature, IHDR,
// one IDAT of a zlib stream made of stored (uncompressed) deflate blocks, and IEND, each chunk
// with its CRC-32. The texture tests write their images so, rather than through the library the
// loader reads them with, so that what the file holds is exactly what a test says it holds: a
// reader that changes the stored values (associating alpha with colour, say) cannot be masked by
// a writer that made the inverse change.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace tripath::test {

namespace png_detail {

inline uint32_t crc32(const std::string& bytes) {
    static const std::array<uint32_t, 256> table = [] {
        std::array<uint32_t, 256> t{};
        for (uint32_t n = 0; n < 256; ++n) {
            uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
    return c ^ 0xFFFFFFFFu;
}

inline uint32_t adler32(const std::string& bytes) {
    uint32_t a = 1, b = 0;
    for (unsigned char x : bytes) {
        a = (a + x) % 65521;
        b = (b + a) % 65521;
    }
    return (b << 16) | a;
}

inline void bigEndian(std::string& out, uint32_t v, int bytes = 4) {
    for (int k = bytes - 1; k >= 0; --k) out += char((v >> (8 * k)) & 0xFF);
}

inline void littleEndian16(std::string& out, uint32_t v) {
    out += char(v & 0xFF);
    out += char((v >> 8) & 0xFF);
}

inline std::string chunk(const char* type, const std::string& data) {
    std::string body = std::string(type, 4) + data;
    std::string out;
    bigEndian(out, uint32_t(data.size()));
    out += body;
    bigEndian(out, crc32(body));
    return out;
}

// A zlib stream (RFC 1950) of stored deflate blocks (RFC 1951 §3.2.4) holding `raw`.
inline std::string storedZlib(const std::string& raw) {
    std::string out("\x78\x01", 2);
    size_t at = 0;
    do {
        const size_t n = std::min<size_t>(raw.size() - at, 65535);
        out += char(at + n == raw.size() ? 1 : 0);  // BFINAL on the last block, BTYPE 00
        littleEndian16(out, uint32_t(n));
        littleEndian16(out, uint32_t(~n & 0xFFFF));
        out.append(raw, at, n);
        at += n;
    } while (at < raw.size());
    bigEndian(out, adler32(raw));
    return out;
}

}  // namespace png_detail

// The bytes of a PNG of width × height texels with `channels` channels (grey, grey + alpha, RGB
// or RGBA), row by row from the top, of 8-bit (uint8_t) or 16-bit (uint16_t) values as given.
template <class T>
std::string pngBytes(int width, int height, int channels, const std::vector<T>& values) {
    using namespace png_detail;
    static constexpr unsigned char kColourType[] = {0, 0, 4, 2, 6};  // by channel count
    std::string header;
    bigEndian(header, uint32_t(width));
    bigEndian(header, uint32_t(height));
    header += char(8 * sizeof(T));
    header += char(kColourType[channels]);
    header += std::string(3, '\0');  // deflate, adaptive filtering, no interlace
    std::string raw;
    const size_t row = size_t(width) * size_t(channels);
    for (int y = 0; y < height; ++y) {
        raw += '\0';  // filter type None
        for (size_t i = 0; i < row; ++i) bigEndian(raw, uint32_t(values[size_t(y) * row + i]), int(sizeof(T)));
    }
    return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) + chunk("IDAT", storedZlib(raw)) +
           chunk("IEND", "");
}

template <class T>
void writePng(const std::filesystem::path& file, int width, int height, int channels, const std::vector<T>& values) {
    std::ofstream(file, std::ios::binary) << pngBytes(width, height, channels, values);
}

}  // namespace tripath::test
