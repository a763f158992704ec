#include "core/sobol.h"

#include "core/rng.h"

namespace tripath {

namespace {

// sobol() by the index's eight nibbles: the sum of the direction numbers of each nibble's set bits,
// tabulated for every nibble value. A scrambled index has all 32 bits in play, where the loop over
// them would take 32 steps; these take 8 lookups in 2 KiB.
struct NibbleTables {
    std::array<std::array<std::array<uint32_t, 16>, 8>, 4> sums{};
    constexpr NibbleTables() {
        for (int d = 0; d < 4; ++d)
            for (int n = 0; n < 8; ++n)
                for (uint32_t value = 0; value < 16; ++value) sums[size_t(d)][size_t(n)][value] = sobol(value << (4 * n), d);
    }
};
constexpr NibbleTables kNibbles;

uint32_t tabulatedSobol(uint32_t index, int dim) {
    const auto& tables = kNibbles.sums[size_t(dim)];
    uint32_t x = 0;
    for (size_t n = 0; n < 8; ++n, index >>= 4) x ^= tables[n][index & 15u];
    return x;
}

}  // namespace

SobolPoint::SobolPoint(uint32_t index, uint64_t key)
    : key_(mix64(key)), shuffled_(owenScramble(index, static_cast<uint32_t>(key_))) {}

uint32_t SobolPoint::operator[](int dim) const {
    const uint32_t x = dim == 0 ? reverseBits(shuffled_) : tabulatedSobol(shuffled_, dim);
    return owenScramble(x, static_cast<uint32_t>(mix64(key_ + uint64_t(dim) + 1)));
}

}  // namespace tripath
