#!/usr/bin/env bash
# Installs what is missing, then configures and builds tripath (Release) into build/, optimised
# with a GCC profile of its own training renders (scripts/pgo-profile.sh, made into build/pgo and
# remade when the sources change; TRIPATH_PGO=0 builds without one). Extra arguments go to CMake.
# After editing the code, `cmake --build build` rebuilds with the old profile, which GCC applies
# to the functions that did not change (it warns "Missing counts for called function" about the
# others: harmless; this script remakes the profile).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
profile=$(bash scripts/pgo-profile.sh build/pgo | tail -n 1)
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTRIPATH_PGO_PROFILE="$profile" "$@" >/dev/null
cmake --build build -j"$(nproc)"
