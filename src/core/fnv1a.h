// 64-bit FNV-1a over bytes added piece by piece: a fast hash with no cryptographic strength, which
// tells apart files and records that differ by accident or by an edit. A checkpoint's checksum
// (requests/checkpoint_file.h) and the content of the files a scene was built from (SourceFile,
// geometry/scene_desc.h) are this hash. About 1 GB/s: a byte a multiply.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace tripath {

class Fnv1a {
public:
    void add(const void* data, size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 0x100000001b3u;
    }
    void add(std::string_view text) { add(text.data(), text.size()); }
    uint64_t value() const { return hash_; }

private:
    uint64_t hash_ = 0xcbf29ce484222325u;
};

// The hash of one run of bytes.
inline uint64_t fnv1a(std::string_view bytes) {
    Fnv1a h;
    h.add(bytes);
    return h.value();
}

// A hash as records write it: 16 lower-case hex digits.
std::string hashText(uint64_t hash);

}  // namespace tripath
