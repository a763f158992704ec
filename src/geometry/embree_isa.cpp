#include "geometry/embree_isa.h"

#include <embree3/rtcore_config.h>

#include <atomic>

namespace tripath {

namespace {
std::atomic<int> gLevel{-1};  // -1: not pinned yet
}  // namespace

int bestEmbreeIsaLevel() {
    __builtin_cpu_init();
    // Embree's AVX2 kernels also use FMA and BMI. Its AVX-512 kernels are not among the levels:
    // they were the slower ones for this renderer's single rays (embree_isa.h).
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2")) return 3;
    if (__builtin_cpu_supports("avx")) return 2;
    if (__builtin_cpu_supports("sse4.2")) return 1;
    return 0;
}

void useEmbreeIsa(int level) { gLevel.store(level); }

int embreeIsaLevel() {
    const int level = gLevel.load();
    return level >= 0 ? level : bestEmbreeIsaLevel();
}

std::string embreeDescription() { return std::string(RTC_VERSION_STRING) + " " + kEmbreeIsas[embreeIsaLevel()]; }

}  // namespace tripath
