#!/usr/bin/env bash
# Fuzzes the glTF loader, Scene construction and a vcm pass over the scene (fuzz/gltf_fuzzer.cpp)
# with libFuzzer and AddressSanitizer, at the lowest CPU priority.
#
#   scripts/fuzz-gltf.sh [SECONDS]      default 600
#   KEEP_GOING=1 scripts/fuzz-gltf.sh   fork mode: save each crash, hang or OOM and carry on
#                                       (libFuzzer otherwise stops at the first one)
#
# Needs clang with libFuzzer (Debian: clang and libclang-rt-<version>-dev). Builds into
# build-fuzz/ (-DTRIPATH_FUZZ=ON). The seed corpus is scenes/*.gltf plus fuzz/seeds/ (small
# hand-made files: textures in data URIs and in a .glb's binary chunk, every punctual light,
# instancing, an absorbing glass volume over a tangent-framed normal map, JSON nested to the
# loader's limit); the growing corpus lives in build-fuzz/corpus/. Crashes, hangs
# (-timeout) and out-of-memory inputs are written to build-fuzz/artifacts/: copy each into
# tests/data/fuzz/ once the bug is fixed, where Fuzz.EntryPointSurvivesEverySavedFind
# (tests/test_fuzz_inputs.cpp) feeds it to the same entry point, as it feeds the seeds, in the
# ordinary test build.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRIPATH_FUZZ=ON \
  -DTRIPATH_TESTS=OFF -DTRIPATH_BENCH=OFF >/dev/null
nice -n 19 cmake --build build-fuzz -j"$(nproc)" --target gltf_fuzzer

mkdir -p build-fuzz/corpus build-fuzz/artifacts
extra=()
[ "${KEEP_GOING:-0}" = 1 ] && extra=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
# -max_len: big enough for the small scenes; the larger files (caustic, sds, the literature scenes
# of up to 2.9 MB) are seeds too, but the mutator works on their first 64 KB (their JSON header
# and the start of the buffer).
# -timeout: an input that takes more than 10 s to load (a hang) is an artifact too.
# ASAN_OPTIONS: a leak is a finding as well (but for what scripts/lsan.supp names in libraries);
# allocator_may_return_null turns a giant allocation
# into std::bad_alloc (which escapes the fuzzer as a crash with its input) rather than an abort.
ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp" \
nice -n 19 ./build-fuzz/gltf_fuzzer -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len=65536 -print_final_stats=1 -artifact_prefix=build-fuzz/artifacts/ "${extra[@]}" \
  build-fuzz/corpus scenes fuzz/seeds
