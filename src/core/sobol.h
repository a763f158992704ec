// Owen-scrambled Sobol points, four dimensions at a time (Burley 2020, "Practical hash-based Owen
// scrambling"): the low-discrepancy numbers of `--sampler sobol`.
//
// The first four dimensions of Sobol's sequence, each a binary fraction x_d(i) = ⊕ over the set
// bits b of i of the direction number v_{d,b}. Any 2^k consecutive points from a multiple of 2^k
// are stratified: the first two dimensions put one point in each of the 2^k elementary intervals
// of area 2^-k (a (0, 2)-sequence). Owen's scramble keeps that and randomises the rest: each binary
// digit is flipped by a hash of the digits before it, so a scrambled point is uniform on [0, 1)
// and estimates stay unbiased. A stream of such 4D points is keyed: its index is scrambled the
// same way first (which permutes the points within every aligned block of 2^k, so prefixes stay
// stratified, and takes each stream to its own block of the sequence), then each dimension with
// its own key. Streams whose index keys differ are independent, whether or not they share the
// dimensions' keys: their points are the sequence's at indices shuffled apart, so each pair of
// them is two independent uniform points, scrambled. A path draws its dimensions beyond four from
// further streams (sample_stream.h) that share the dimensions' keys: a point then costs no hashes
// of its own but its index key's.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

namespace tripath {

// The bits of x in reverse order.
constexpr uint32_t reverseBits(uint32_t x) {
    x = (x >> 16) | (x << 16);
    x = ((x & 0xff00ff00u) >> 8) | ((x & 0x00ff00ffu) << 8);
    x = ((x & 0xf0f0f0f0u) >> 4) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x & 0xccccccccu) >> 2) | ((x & 0x33333333u) << 2);
    return ((x & 0xaaaaaaaau) >> 1) | ((x & 0x55555555u) << 1);
}

// A permutation of the 32-bit integers, keyed by `key`, in which each bit of the result depends on
// that bit of x and the bits below it alone: additions, multiplications by odd numbers and
// x ⊕ x·(even) each carry only upward. The operations and constants are Vegdahl's (2021) hash
// in Laine and Karras's form, which mixes better than Burley's original.
constexpr uint32_t upwardPermutation(uint32_t x, uint32_t key) {
    x ^= x * 0x3d20adeau;
    x += key;
    x *= (key >> 16) | 1u;
    x ^= x * 0x05526c56u;
    x ^= x * 0x53a22864u;
    return x;
}

namespace detail {

// The direction numbers of Sobol's first four dimensions, v_{d,b} for bit b of the index, as
// binary fractions: dimension 0 is van der Corput's (v_b = 2^-(b+1)); the others follow the
// recurrence of Bratley and Fox from primitive polynomials and initial numbers m (Joe and Kuo's
// table: x + 1 with m = 1; x² + x + 1 with 1, 3; x³ + x + 1 with 1, 3, 1).
constexpr std::array<std::array<uint32_t, 32>, 4> sobolDirections() {
    struct Polynomial {
        int degree;
        uint32_t inner;  // the coefficients between the leading and the constant one, highest first
        std::array<uint32_t, 3> m;
    };
    constexpr std::array<Polynomial, 3> polynomials{{{1, 0, {1, 0, 0}}, {2, 1, {1, 3, 0}}, {3, 1, {1, 3, 1}}}};
    std::array<std::array<uint32_t, 32>, 4> v{};
    for (int b = 0; b < 32; ++b) v[0][size_t(b)] = 1u << (31 - b);
    for (size_t d = 1; d < 4; ++d) {
        const Polynomial& p = polynomials[d - 1];
        std::array<uint32_t, 32> m{};
        for (int k = 0; k < 32; ++k) {
            if (k < p.degree) {
                m[size_t(k)] = p.m[size_t(k)];
                continue;
            }
            // m_k = 2^s m_{k−s} ⊕ m_{k−s} ⊕ ⊕_{j=1}^{s−1} 2^j a_j m_{k−j}
            uint32_t mk = (m[size_t(k - p.degree)] << p.degree) ^ m[size_t(k - p.degree)];
            for (int j = 1; j < p.degree; ++j)
                if ((p.inner >> (p.degree - 1 - j)) & 1u) mk ^= m[size_t(k - j)] << j;
            m[size_t(k)] = mk;
        }
        for (int b = 0; b < 32; ++b) v[d][size_t(b)] = m[size_t(b)] << (31 - b);
    }
    return v;
}

inline constexpr std::array<std::array<uint32_t, 32>, 4> kSobolDirections = sobolDirections();

}  // namespace detail

// Point `index` of Sobol's sequence in dimension `dim` (0–3), as a binary fraction: the sum
// (⊕) of the direction numbers of the index's set bits.
constexpr uint32_t sobol(uint32_t index, int dim) {
    uint32_t x = 0;
    for (int b = 0; index != 0; ++b, index >>= 1)
        if (index & 1u) x ^= detail::kSobolDirections[size_t(dim)][size_t(b)];
    return x;
}

// Point `index` of a scrambled stream: the index scrambled by a key of the point's, then each
// dimension's coordinate by a key of the dimension's. The four coordinates are made together,
// lane by lane, as the compiler can vectorise them.
class SobolPoint {
public:
    using DimensionKeys = std::array<uint32_t, 4>;
    // The dimensions' keys of a stream keyed by `key`: a hash of the key and the dimension.
    static DimensionKeys dimensionKeys(uint64_t key);
    // The index's bits reversed, which a stream of one index keeps.
    struct ReversedIndex {
        uint32_t bits;
    };

    SobolPoint() = default;
    // The point of a stream keyed by `key`, with its index's key and its dimensions' from it.
    SobolPoint(uint32_t index, uint64_t key);
    // The point of index `index` scrambled by `indexKey`, its coordinates by `keys`. Streams that
    // share the dimensions' keys and not the index's are independent (their indices are shuffled
    // apart): so a sample's sets of dimensions share the sample's dimension keys.
    SobolPoint(ReversedIndex index, uint32_t indexKey, const DimensionKeys& keys);
    // Dimension `dim` (0–3), as a binary fraction.
    uint32_t operator[](int dim) const { return coordinates_[size_t(dim)]; }

private:
    std::array<uint32_t, 4> coordinates_{};
};

// A binary fraction as a float in [0, 1): its first 24 digits, exactly.
constexpr float fractionToFloat(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

}  // namespace tripath
