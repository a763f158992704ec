#!/usr/bin/env bash
# The README's first command: install, build, and render the built-in default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
./build/tripath render --scene cornell --integrator bdpt --spp 32 --width 512 --height 512 \
  --out out/cornell.exr --png out/cornell.png
echo "wrote $(pwd)/out/cornell.exr and $(pwd)/out/cornell.png"
