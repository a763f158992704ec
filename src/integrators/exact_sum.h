// Exact, order-free sums of doubles: 192-bit two's-complement fixed point with 80 fractional bits.
//
// Why: a render shared by N processes must give the image one process gives, bit for bit,
// whatever N and whichever process renders which passes. Floating-point addition is not
// associative, so the film cannot simply add the processes' partial sums. The render loop
// therefore sums a canonical block of passes in double, in the one order every process uses for
// that block, and then adds the block's sums into these integers. Integer addition is exact and
// associative: the total is the same for any grouping of blocks, so blocks may be rendered by any
// rank, added in any order, and reduced over ranks in any tree (render.h).
//
// Conversion from double is exact down to 2^-80 ≈ 8·10^-25 (lower bits are truncated toward zero,
// the same way on every machine); a block value beyond ±2^100 ≈ 1.3·10^30, which no radiance
// reaches, is clamped there, so 2^10 such blocks can still be added before the 2^111 range ends.
// The way back rounds through long double, so a sum reads with 64 significant bits before it is
// rounded to double. Cost: a few integer operations per value per block (bench/distributed.cpp).
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace tripath {

struct alignas(8) Fixed192 {
    uint64_t w[3] = {0, 0, 0};  // little-endian words; w[2]'s top bit is the sign

    static constexpr int kFractionBits = 80;

    static Fixed192 fromDouble(double x) {
        Fixed192 f;
        const uint64_t bits = std::bit_cast<uint64_t>(x);
        const int biased = static_cast<int>((bits >> 52) & 0x7ff);
        if (biased == 0 || biased == 0x7ff) return f;  // zero and subnormals are below 2^-80; NaN/Inf never reach a film
        uint64_t mantissa = (bits & ((uint64_t(1) << 52) - 1)) | (uint64_t(1) << 52);  // |x| = mantissa · 2^(biased − 1075)
        int shift = biased - 1075 + kFractionBits;                                      // fixed = mantissa · 2^shift
        constexpr int kClampShift = 100 - 52 + kFractionBits;                           // 2^100
        if (shift > kClampShift) {
            mantissa = uint64_t(1) << 52;
            shift = kClampShift;
        }
        if (shift <= -53) return f;
        if (shift < 0) {
            mantissa >>= -shift;
            shift = 0;
        }
        const int word = shift / 64, bit = shift % 64;
        f.w[word] = mantissa << bit;
        if (bit > 0 && word < 2) f.w[word + 1] = mantissa >> (64 - bit);
        if (bits >> 63) f.negate();
        return f;
    }

    void negate() {
        unsigned carry = 1;
        for (uint64_t& v : w) {
            v = ~v + carry;
            carry = carry && v == 0;
        }
    }

    Fixed192& operator+=(const Fixed192& o) {
        unsigned __int128 carry = 0;
        for (int i = 0; i < 3; ++i) {
            const unsigned __int128 s = static_cast<unsigned __int128>(w[i]) + o.w[i] + carry;
            w[i] = static_cast<uint64_t>(s);
            carry = s >> 64;
        }
        return *this;
    }

    double toDouble() const {
        Fixed192 m = *this;
        const bool negative = w[2] >> 63;
        if (negative) m.negate();
        const long double v = std::ldexp(static_cast<long double>(m.w[2]), 128 - kFractionBits) +
                              std::ldexp(static_cast<long double>(m.w[1]), 64 - kFractionBits) +
                              std::ldexp(static_cast<long double>(m.w[0]), -kFractionBits);
        return static_cast<double>(negative ? -v : v);
    }

    bool operator==(const Fixed192&) const = default;
};

// A vector of exact sums, one per film value.
class ExactSums {
public:
    explicit ExactSums(size_t n = 0) : v_(n) {}
    size_t size() const { return v_.size(); }
    // Adds doubles[i] to sum i, for a range of i (the render loop folds a block in parallel chunks).
    void add(std::span<const double> doubles, size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) v_[i] += Fixed192::fromDouble(doubles[i]);
    }
    // Adds one value to sum i.
    void add(size_t i, double value) { v_[i] += Fixed192::fromDouble(value); }
    void add(const ExactSums& o) {
        for (size_t i = 0; i < v_.size(); ++i) v_[i] += o.v_[i];
    }
    double value(size_t i) const { return v_[i].toDouble(); }
    // Sets sum i back to zero.
    void clear(size_t i) { v_[i] = Fixed192{}; }
    // The raw words, 3 per value: what processes exchange and checkpoints store.
    std::span<uint64_t> words() { return {reinterpret_cast<uint64_t*>(v_.data()), 3 * v_.size()}; }
    std::span<const uint64_t> words() const { return {reinterpret_cast<const uint64_t*>(v_.data()), 3 * v_.size()}; }

private:
    std::vector<Fixed192> v_;
};

}  // namespace tripath
