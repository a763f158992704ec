#!/usr/bin/env bash
# Builds tripath with AddressSanitizer + UndefinedBehaviorSanitizer (CMake option TRIPATH_SANITIZE)
# into build-asan/ and runs the whole test suite there through CTest.
#
#   scripts/test-sanitized.sh [ctest arguments...]     e.g. -R Stability to run a subset
#
# Any sanitizer report fails the test that triggered it: UBSan is told to halt on its first
# error (by default it prints and carries on, and the test would pass), and LeakSanitizer runs at
# exit. Expect the suite to take 3-5x as long as in Release; the build is RelWithDebInfo so
# reports carry file and line.
#
# Beside it, scripts/check-compilers.sh (not run by CI) builds the portable configuration with
# GCC and with Clang (the compiler of the fuzz build) and checks that both render bit-identical
# images of every built-in scene with pt, lt and bdpt.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRIPATH_SANITIZE=ON -DTRIPATH_BENCH=OFF >/dev/null
cmake --build build-asan -j"$(nproc)"
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Open MPI frees nothing at MPI_Finalize: its allocations are suppressed by library name, which
# needs its components kept loaded and full stacks (the fast unwinder stops inside them).
export OMPI_MCA_mca_base_component_disable_dlclose=1
export LSAN_OPTIONS="suppressions=$PWD/scripts/lsan.supp:fast_unwind_on_malloc=0"
cd build-asan
ctest --output-on-failure -j"$(nproc)" "$@"
