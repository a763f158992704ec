#!/usr/bin/env bash
# Runs one of the libFuzzer targets of fuzz/ with AddressSanitizer, at the lowest CPU priority:
#   gltf                     the glTF loader, Scene construction and a vcm pass over the scene
#                            (fuzz/gltf_fuzzer.cpp; the default)
#   environment-checkpoint   the environment-map reader (EXR, HDR, PNG) and the checkpoint reader,
#                            each with what it feeds: the map sampled, the render resumed for a pass
#                            (fuzz/environment_checkpoint_fuzzer.cpp)
#
#   scripts/fuzz-gltf.sh [SECONDS [TARGET]]   default 600 gltf
#   KEEP_GOING=1 scripts/fuzz-gltf.sh ...     fork mode: save each crash, hang or OOM and carry on
#                                             (libFuzzer otherwise stops at the first one)
#
# Needs clang with libFuzzer (Debian: clang and libclang-rt-<version>-dev). Builds into
# build-fuzz/ (-DTRIPATH_FUZZ=ON). Seeds: for gltf, scenes/*.gltf plus fuzz/seeds/gltf/ (small
# hand-made files: textures in data URIs and in a .glb's binary chunk, every punctual light,
# instancing, an absorbing glass volume over a tangent-framed normal map, JSON nested to the
# loader's limit); for environment-checkpoint, fuzz/seeds/environment-checkpoint/ (small maps and
# checkpoints, behind the byte that chooses their reader: the target's header says how they were
# made). The growing corpus lives in build-fuzz/corpus/ (gltf) or build-fuzz/corpus-TARGET/.
# Crashes, hangs (-timeout) and out-of-memory inputs are written to build-fuzz/artifacts/ (gltf)
# or build-fuzz/artifacts-TARGET/: copy each into tests/data/fuzz/ (the second target's into
# tests/data/fuzz/environment-checkpoint/, named *.input) once the bug is fixed, where
# Fuzz.EntryPointsSurviveEverySavedFind (tests/test_fuzz_inputs.cpp) feeds it to the same entry
# point, as Fuzz.EntryPointsUseEverySeed feeds the seeds, in the ordinary test build.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
target="${2:-gltf}"

# -max_len: for gltf, big enough for the small scenes; the larger files (caustic, sds, the
# literature scenes of up to 2.9 MB) are seeds too, but the mutator works on their first 64 KB
# (their JSON header and the start of the buffer). The second target's seeds are under 3 KB.
case "$target" in
  gltf) corpus=build-fuzz/corpus artifacts=build-fuzz/artifacts maxLen=65536 seeds=(scenes fuzz/seeds/gltf) ;;
  environment-checkpoint)
    corpus=build-fuzz/corpus-$target artifacts=build-fuzz/artifacts-$target maxLen=16384
    seeds=(fuzz/seeds/environment-checkpoint) ;;
  *) echo "unknown fuzz target '$target' (gltf, environment-checkpoint)" >&2; exit 1 ;;
esac
executable="${target//-/_}_fuzzer"

CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRIPATH_FUZZ=ON \
  -DTRIPATH_TESTS=OFF -DTRIPATH_BENCH=OFF >/dev/null
nice -n 19 cmake --build build-fuzz -j"$(nproc)" --target "$executable"

mkdir -p "$corpus" "$artifacts"
extra=()
[ "${KEEP_GOING:-0}" = 1 ] && extra=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1)
# -timeout: an input that takes more than 10 s (a hang) is an artifact too.
# ASAN_OPTIONS: a leak is a finding as well (but for what scripts/lsan.supp names in libraries);
# allocator_may_return_null turns a giant allocation
# into std::bad_alloc (which escapes the fuzzer as a crash with its input) rather than an abort.
ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp" \
nice -n 19 "./build-fuzz/$executable" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
  -max_len="$maxLen" -print_final_stats=1 -artifact_prefix="$artifacts/" "${extra[@]}" \
  "$corpus" "${seeds[@]}"
