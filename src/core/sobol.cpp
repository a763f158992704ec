#include "core/sobol.h"

#include "core/rng.h"

namespace tripath {

namespace {

// A scramble works on a fraction's digits reversed (its first digit in bit 0), as the index's
// scramble does: so the points are made reversed, from the reversed scrambled index, and each is
// turned once, at the end. Sobol's sum is linear in the index's bits, so a reversed point is the
// sum over the reversed index's four bytes of a table's entry: for every byte place and value
// the reversed sum of the direction numbers of the index bits it stands for, four dimensions side
// by side (16 KiB: bytes take half the lookups of nibbles, and measured faster).
struct ReversedByteTables {
    std::array<std::array<std::array<uint32_t, 4>, 256>, 4> sums{};
    constexpr ReversedByteTables() {
        for (int n = 0; n < 4; ++n)
            for (uint32_t value = 0; value < 256; ++value)
                for (int d = 0; d < 4; ++d)
                    sums[size_t(n)][value][size_t(d)] = reverseBits(sobol(reverseBits(value << (8 * n)), d));
    }
};
constexpr ReversedByteTables kReversedBytes;

// A 32-bit hash (Wellons's lowbias32): each dimension's scramble key from the stream's.
constexpr uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

}  // namespace

SobolPoint::DimensionKeys SobolPoint::dimensionKeys(uint64_t key) {
    const auto base = static_cast<uint32_t>(mix64(key) >> 32);
    DimensionKeys keys{};
    for (size_t d = 0; d < 4; ++d) keys[d] = hash32(base + 0x9e3779b9u * uint32_t(d));
    return keys;
}

SobolPoint::SobolPoint(uint32_t index, uint64_t key)
    : SobolPoint(ReversedIndex{reverseBits(index)}, static_cast<uint32_t>(mix64(key)), dimensionKeys(key)) {}

SobolPoint::SobolPoint(ReversedIndex index, uint32_t indexKey, const DimensionKeys& keys) {
    const uint32_t shuffled = upwardPermutation(index.bits, indexKey);
    std::array<uint32_t, 4> reversed{};
    for (size_t n = 0; n < 4; ++n) {
        const auto& sums = kReversedBytes.sums[n][(shuffled >> (8 * n)) & 255u];
        for (size_t d = 0; d < 4; ++d) reversed[d] ^= sums[d];
    }
    for (size_t d = 0; d < 4; ++d) coordinates_[d] = reverseBits(upwardPermutation(reversed[d], keys[d]));
}

}  // namespace tripath
