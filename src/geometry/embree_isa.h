// Which of Embree's instruction sets the ray queries run on. Left alone, Embree picks the widest
// one the CPU has, and its kernels for different widths (SSE, AVX2, AVX-512) build different BVHs
// and may return different hits for the same ray. A render shared by processes on different
// CPUs, or continued on another machine, must therefore run one ISA throughout: the command line
// pins it (the narrowest of the ranks' best), records it with Embree's version in the EXR
// (tripath:embree), and refuses to add samples made with another.
#pragma once
#include <string>

namespace tripath {

// The ISAs this code pins, narrowest first; a level is an index into this list.
inline constexpr const char* kEmbreeIsas[] = {"sse2", "sse4.2", "avx", "avx2", "avx512"};
// The level of an ISA's name in kEmbreeIsas, or -1.
int embreeIsaNamed(const std::string& name);
// The widest ISA of kEmbreeIsas this CPU runs (Embree's own choice when left alone), which renders
// run on unless the command line's --embree-isa pins another.
int bestEmbreeIsaLevel();
// Every Scene built after this call runs this ISA (default: bestEmbreeIsaLevel()).
void useEmbreeIsa(int level);
int embreeIsaLevel();
// "3.13.5 avx2": Embree's version and the ISA in use, as tripath:embree records them.
std::string embreeDescription();

}  // namespace tripath
