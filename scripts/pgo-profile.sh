#!/usr/bin/env bash
# Makes the GCC profiles for a profile-guided build of tripath (CMakeLists.txt, TRIPATH_PGO_*):
# builds an instrumented `tripath` in DIR/instrumented, renders a training set with it, and
# leaves the profiles in DIR/profile. scripts/build.sh calls it and builds with what it made.
#
#   bash scripts/pgo-profile.sh DIR        prints DIR/profile's absolute path on its last line
#
# Reuses DIR/profile when the sources have not changed since it was made (DIR/stamp holds a hash
# of src/, apps/, the CMake files and this script). With TRIPATH_PGO=0, or a compiler other than
# GCC, it makes nothing and prints an empty line, and the build runs without a profile.
#
# The training set: every integrator on small renders of built-in scenes and glTF files that
# between them have diffuse, mirror, glass and rough metal surfaces, smooth normals, area and
# point lights, and the glTF loader (what the training never runs is compiled as without a
# profile: -fprofile-partial-training). It deliberately leaves out `smallvcm-5`, the scene of the
# peer comparison (bench/README.md), so that the speed measured there is not of a build trained
# on it. About 20 s on 2 cores, besides the instrumented build.
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 1 ] || { echo "usage: bash scripts/pgo-profile.sh DIR" >&2; exit 2; }
# Skipped on request, and for a compiler other than GCC (CMakeLists.txt sets it up for GCC only).
if [ "${TRIPATH_PGO:-1}" = 0 ] || ! "${CXX:-c++}" --version 2>/dev/null | grep -q "Free Software Foundation"; then
  echo
  exit 0
fi
mkdir -p "$1"
dir=$(realpath "$1")
stamp=$(find src apps cmake CMakeLists.txt scripts/pgo-profile.sh -type f -print0 | sort -z | xargs -0 sha256sum | sha256sum | cut -d' ' -f1)
if [ -f "$dir/stamp" ] && [ "$(cat "$dir/stamp")" = "$stamp" ] && [ -d "$dir/profile" ]; then
  echo "$dir/profile"
  exit 0
fi

echo "profile-guided build: making the profiles in $dir (instrumented build, then the training renders)" >&2
rm -rf "$dir/profile" "$dir/stamp"
cmake -S . -B "$dir/instrumented" -DCMAKE_BUILD_TYPE=Release -DTRIPATH_TESTS=OFF -DTRIPATH_BENCH=OFF \
  -DTRIPATH_PYTHON=OFF -DTRIPATH_PGO_PROFILE= -DTRIPATH_PGO_GENERATE="$dir/profile" >/dev/null
cmake --build "$dir/instrumented" -j"$(nproc)" --target tripath >"$dir/instrumented.log" 2>&1 \
  || { tail -n 30 "$dir/instrumented.log" >&2; echo "error: the instrumented build failed ($dir/instrumented.log)" >&2; exit 1; }
train() {
  "$dir/instrumented/tripath" render "$@" --width 96 --height 96 --spp 4 --out "$dir/training.exr" >"$dir/training.log" 2>&1 \
    || { cat "$dir/training.log" >&2; exit 1; }
}
for scene in cornell cornell-spheres cornell-point veach-mis sds-mirrors scenes/caustic.gltf scenes/door-ajar.gltf scenes/grazing.gltf; do
  for integrator in pt lt bdpt vcm bpm ppm mlt; do
    train --scene "$scene" --integrator "$integrator"
  done
done
rm -f "$dir/training.exr" "$dir/training.log"
[ -d "$dir/profile" ] || { echo "error: the instrumented build wrote no profiles into $dir/profile" >&2; exit 1; }
# The Python module's position-independent libraries compile the same sources: the same profiles
# under their object folders' names.
for f in "$dir"/profile/CMakeFiles#tripath_*.dir#*.gcda; do
  cp "$f" "${f/.dir#/_pic.dir#}"
done
echo "$stamp" > "$dir/stamp"
echo "$dir/profile"
