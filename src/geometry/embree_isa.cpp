#include "geometry/embree_isa.h"

#include <embree3/rtcore_config.h>

#include <atomic>
#include <iterator>

namespace tripath {

namespace {
std::atomic<int> gLevel{-1};  // -1: not pinned yet
}  // namespace

int embreeIsaNamed(const std::string& name) {
    for (int level = 0; level < int(std::size(kEmbreeIsas)); ++level)
        if (name == kEmbreeIsas[level]) return level;
    return -1;
}

int bestEmbreeIsaLevel() {
    __builtin_cpu_init();
    // Embree's AVX-512 kernels need the Skylake-server subset; its AVX2 kernels also use FMA and BMI.
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512cd") &&
        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl"))
        return 4;
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
