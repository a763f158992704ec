// Amounts of memory as people write them: "8G" on the command line (--memory-limit), "3.07 GiB"
// in a message. Units are powers of 1024 however written ("8G", "8GB" and "8GiB" are 8 × 2^30
// bytes), as memory is sold and as free(1) and the kernel's cgroups count it.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tripath {

// `text` as a number of bytes: a non-negative number, whole or decimal, optionally followed by
// K, M, G or T, then optionally B or iB (any case): "8G", "8GB", "1.5TiB", "512m", "4096". nullopt
// for anything else ("", "-1G", "G", "1e3", "8 G", "8X") or a value beyond 2^64 − 1 bytes.
std::optional<uint64_t> parseByteSize(std::string_view text);

// `bytes` with three significant digits in the largest unit that keeps it at least 1:
// "512 B", "96.0 KiB", "3.07 GiB".
std::string bytesText(uint64_t bytes);

}  // namespace tripath
