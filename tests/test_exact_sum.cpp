// The film's exact totals (integrators/exact_sum.h): conversion from double is exact to 2^-80 and
// addition is exact, so sums do not depend on order or grouping, which is what lets processes
// combine their films into the film of one process (render.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "integrators/exact_sum.h"

namespace tripath {
namespace {

Fixed192 sum(const std::vector<double>& values) {
    Fixed192 s;
    for (double v : values) s += Fixed192::fromDouble(v);
    return s;
}

// 0.1 + 0.2 − 0.3 in doubles is 2^-54 (0.1 + 0.2 rounds up first); the exact sum of the three
// doubles is 2^-55, which a fixed-point sum must give.
TEST(ExactSum, AddsDoublesWithoutRounding) {
    EXPECT_EQ(0.1 + 0.2 - 0.3, std::ldexp(1.0, -54));
    EXPECT_EQ(sum({0.1, 0.2, -0.3}).toDouble(), std::ldexp(1.0, -55));
    // A small value survives beside a large one: 1e20 + 1e-20 − 1e20.
    EXPECT_NEAR(sum({1e20, 1e-20, -1e20}).toDouble(), 1e-20, std::ldexp(1.0, -80));
}

// Any order and any grouping give the same words: values over 40 decades, both signs.
TEST(ExactSum, OrderAndGroupingDoNotMatter) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> exponent(-20, 20), sign(-1, 1);
    std::vector<double> v(2000);
    for (double& x : v) x = std::copysign(std::pow(10.0, exponent(rng)), sign(rng));
    const Fixed192 forward = sum(v);
    std::reverse(v.begin(), v.end());
    EXPECT_EQ(sum(v), forward);
    std::shuffle(v.begin(), v.end(), rng);
    EXPECT_EQ(sum(v), forward);
    // Pairwise, as a reduction tree over ranks would add.
    std::vector<Fixed192> level;
    for (double x : v) level.push_back(Fixed192::fromDouble(x));
    while (level.size() > 1) {
        std::vector<Fixed192> next;
        for (size_t i = 0; i + 1 < level.size(); i += 2) next.push_back(level[i]), next.back() += level[i + 1];
        if (level.size() % 2) next.push_back(level.back());
        level = next;
    }
    EXPECT_EQ(level[0], forward);
    // The same sum in double depends on the order: the test's values are ones where it must.
    double a = 0, b = 0;
    for (double x : v) a += x;
    for (auto it = v.rbegin(); it != v.rend(); ++it) b += *it;
    EXPECT_NE(a, b);
}

// Negatives cancel to zero words; values at the ends of the range behave as documented.
TEST(ExactSum, CancelsAndKeepsItsRange) {
    EXPECT_EQ(sum({3.75, -3.75}), Fixed192{});
    EXPECT_EQ(sum({-1.5}).toDouble(), -1.5);
    EXPECT_EQ(sum({std::ldexp(1.0, -80)}).toDouble(), std::ldexp(1.0, -80));  // the resolution
    EXPECT_EQ(sum({std::ldexp(1.0, -81)}).toDouble(), 0.0);                   // below it
    EXPECT_EQ(sum({std::ldexp(3.0, -81)}).toDouble(), std::ldexp(1.0, -80));  // truncated toward zero
    EXPECT_EQ(sum({-std::ldexp(3.0, -81)}).toDouble(), -std::ldexp(1.0, -80));
    EXPECT_EQ(sum({1e35}).toDouble(), std::ldexp(1.0, 100));                  // clamped
    EXPECT_EQ(sum({std::ldexp(1.0, 99), std::ldexp(1.0, 99)}).toDouble(), std::ldexp(1.0, 100));
}

}  // namespace
}  // namespace tripath
