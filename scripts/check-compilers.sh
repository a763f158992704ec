#!/usr/bin/env bash
# Checks that a GCC build and a Clang build of tripath render bit-identical images, and so does the
# profile-guided GCC build that scripts/build.sh makes.
#
#   scripts/check-compilers.sh [SIZE] [SPP]       defaults: 64 (pixels a side), 4 samples per pixel
#
# Why: the same seed must give the same image whatever the thread count (docs/design.md §4), and
# whatever the compiler too: the fuzz build is Clang, the release build GCC, and a difference
# between them is a difference in what was computed, e.g. two random draws passed as arguments
# of one call (their order is unspecified in C++; on x86-64 GCC evaluated the last argument
# first and Clang the first, so walk.cpp's sampleBsdf(…, uniform2(rng), rng.uniform(), …) made
# 49 of these 51 images differ), or a floating-point expression that one compiler rounds
# differently.
#
# Floating point: the portable build uses only the x86-64 baseline (SSE2 scalar maths, no x87
# in the renderer), which has no fused multiply-add, and passes -ffp-contract=off to every
# compiler (CMakeLists.txt): Clang's default, on, fuses nothing at run time there, but its
# constant folder evaluates the expressions it marks fusable with one rounding, so scenes built
# from constants (smallvcm-5, door-ajar, degenerate-tiny) would come out an ulp apart from GCC's.
# With it both compilers round every operation as written; GCC's -mtune=native changes
# instruction scheduling and selection, never the operations. With -DTRIPATH_NATIVE on a CPU
# with FMA both compilers fuse (GCC across statements, Clang within expressions), so native
# builds are not expected to match each other or the portable one, and are not compared here.
#
# Profile-guided optimisation (scripts/pgo-profile.sh) reorders and duplicates code by how often
# it runs; it changes no floating-point operation, so its images must match too.
#
# It builds the portable configuration (the default: no -DTRIPATH_NATIVE, only the x86-64
# baseline instructions) with g++ into build-gcc/, with clang++ into build-clang/, and with g++
# and the profile of build/pgo into build-gcc-pgo/ (the program only: no tests, no benchmarks),
# renders every built-in scene (`tripath scenes`) with every integrator with each binary (same
# seed, --threads 2) into build-compilers/, and compares the pixels of Clang's and the
# profile-guided images with GCC's bit for bit (scripts/exr-identical.py; the metadata differs,
# e.g. the render time). Prints one row per pair and exits 1 if any image differs.
#
# Not part of CI (three more builds); scripts/test-sanitized.sh mentions it. Installs clang and
# the Python OpenImageIO bindings if they are missing (scripts/install-deps.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
size="${1:-64}"
spp="${2:-4}"
bash scripts/install-deps.sh clang python3-openimageio python3-numpy

out=build-compilers
profile=$(CXX=g++ bash scripts/pgo-profile.sh build/pgo | tail -n 1)
declare -A cxx=([gcc]=g++ [clang]=clang++ [gcc-pgo]=g++)
declare -A pgo=([gcc]= [clang]= [gcc-pgo]="$profile")
for c in gcc clang gcc-pgo; do
  cmake -S . -B "build-$c" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="${cxx[$c]}" \
    -DTRIPATH_TESTS=OFF -DTRIPATH_BENCH=OFF -DTRIPATH_PGO_PROFILE="${pgo[$c]}" >/dev/null
  cmake --build "build-$c" -j"$(nproc)" --target tripath
  mkdir -p "$out/$c"
done

mapfile -t scenes < <(./build-gcc/tripath scenes | awk '{ print $1 }')
pairs=()
for scene in "${scenes[@]}"; do
  for integrator in pt lt bdpt vcm bpm ppm mlt; do
    for c in gcc clang gcc-pgo; do
      "./build-$c/tripath" render --scene "$scene" --integrator "$integrator" --spp "$spp" \
        --width "$size" --height "$size" --seed 7 --threads 2 \
        --out "$out/$c/$scene-$integrator.exr" 2>>"$out/$c/render.log" ||
        { tail -n 5 "$out/$c/render.log" >&2; exit 1; }
    done
    pairs+=("$scene $integrator clang" "$out/gcc/$scene-$integrator.exr" "$out/clang/$scene-$integrator.exr")
    pairs+=("$scene $integrator gcc-pgo" "$out/gcc/$scene-$integrator.exr" "$out/gcc-pgo/$scene-$integrator.exr")
  done
done

echo "GCC ($(g++ -dumpfullversion)) against Clang ($(clang++ -dumpversion)) and against itself profile-guided, ${size}x${size}, $spp spp:"
if /usr/bin/python3 scripts/exr-identical.py "${pairs[@]}"; then
  echo "all ${#scenes[@]} scenes x 7 integrators are bit-identical in all three builds"
else
  echo "error: the builds render different images (rows marked 'differs')" >&2
  exit 1
fi
