#!/usr/bin/env bash
# The "where each method fails" table of docs/failures.md, and its contact sheet: one
# `tripath benchmark` run over the failure scenes and the literature scenes.
#
#   scripts/failure-table.sh [SECONDS] [SIZE] [RUNS]     defaults: 10 seconds per run, 128x128, 4 runs
#
# The benchmark (docs/compare.md, "Over many scenes") renders every failure scene
# (src/scenes/failure_scenes.h), then the four literature scenes (scenes/README.md: glTF files,
# named by their stems below), with pt, lt, bdpt, vcm, bpm, ppm, mlt and auto, RUNS runs of SECONDS
# each (equal time), against a vcm reference of 10 x SECONDS per scene (vcm samples every path
# here, the caustics seen through glass or a mirror included), and tests each method for bias
# against bdpt's runs. Its report stays in build/failures/ (index.html: the table, a page per
# scene, the bias maps); the references stay cached in build/failures/references/ for the next
# run at the same settings (their names hold them). From it this writes:
#   docs/failures.md          the benchmark's results.md between the <!-- table:begin/end -->
#                             markers (the text around them is written by hand and left alone)
#   docs/images/failures.png  reference and every method's run 0 per scene, each row scaled alike
#   docs/images/failures-bias-<scene>.png for the scenes named in $BIAS_MAPS (default: sds): the
#                             benchmark's bias maps of lt and pt there
#   docs/images/failures-benchmark.png, failures-page-sds.png: the benchmark's index.html and the
#                             page of sds as headless Chromium shows them (scripts/install-test-deps.sh
#                             installs it)
# Runtime: 15 scenes x (8 x RUNS x SECONDS + 10 x SECONDS), about 105 minutes at the defaults
# (80 with the references cached).
# Timings are wall-clock: run it on an otherwise idle machine, or the table measures the neighbours.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-10}"
size="${2:-128}"
runs="${3:-4}"
tripath="${TRIPATH:-build/tripath}"
out=build/failures
scenes=(caustic caustic-point sds sds-point sds-mirrors door-ajar contact grazing degenerate degenerate-tiny degenerate-far
        scenes/veach-bidir.gltf scenes/lamp-caustic.gltf scenes/box-light-top.gltf scenes/water-caustic.gltf)
names=("${scenes[@]##*/}")    # what the benchmark names a scene: a built-in's name, a file's stem
names=("${names[@]%.gltf}")
methods=(pt lt bdpt vcm bpm ppm mlt auto)

[ -x "$tripath" ] || { echo "error: $tripath not found: build first (scripts/build.sh) or set TRIPATH" >&2; exit 1; }
mkdir -p docs/images
mkdir -p "$out"
find "$out" -mindepth 1 -maxdepth 1 ! -name references -exec rm -rf {} +
"$tripath" benchmark --scenes "$(IFS=,; echo "${scenes[*]}")" --integrators "$(IFS=,; echo "${methods[*]}")" \
  --time "$seconds" --runs "$runs" --width "$size" --height "$size" --reference-integrator vcm --bias-reference bdpt \
  --out "$out"

sheet=()
for scene in "${names[@]}"; do
  sheet+=("$(ls "$out"/references/"$scene"-"$size"x"$size"-vcm-*.exr)")
  for m in "${methods[@]}"; do sheet+=("$out/$scene/$m.exr"); done
done
# Shrunk 2x (box filter) so that the sheet stays small enough for the repository.
"$tripath" montage "${sheet[@]}" --columns $((${#methods[@]} + 1)) --shrink 2 --out docs/images/failures.png \
  --column-labels "reference,$(IFS=,; echo "${methods[*]}")" --row-labels "$(IFS=,; echo "${names[*]}")"
for scene in ${BIAS_MAPS:-sds}; do
  for m in lt pt; do cp "$out/$scene/bias-$m.png" "docs/images/failures-bias-$scene-$m.png"; done
done
# The pages as a reader sees them (screenshots of the top of each page).
screenshot() {
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --user-data-dir="$out/chromium-profile" \
    --window-size="$3" --screenshot="$2" "file://$(realpath "$1")" 2>/dev/null
}
screenshot "$out/index.html" docs/images/failures-benchmark.png 1400,1150
screenshot "$out/sds/index.html" docs/images/failures-page-sds.png 1400,1400

# Replace the generated block of docs/failures.md, keeping the hand-written text around it.
note="relMSE against a vcm reference (10 × the time) after ${seconds} s per run at ${size}x${size}, mean of ${runs} runs ($(date -u +%Y-%m-%d), $(nproc) cores); lower is better; in bold, a row's best where its mean ± sd is clear of the runner-up's; \"biased n/N\": blocks where Welch's t-test against bdpt's runs finds bias (Holm, family-wise 1 %)."
awk -v table="$out/results.md" -v note="$note" '
  /<!-- table:begin -->/ { print; print ""; print note; print ""; while ((getline line < table) > 0) print line; print ""; skip = 1; next }
  /<!-- table:end -->/ { skip = 0 }
  !skip { print }
' docs/failures.md >"$out/failures.md"
mv "$out/failures.md" docs/failures.md
echo "wrote docs/failures.md and docs/images/failures.png ($(du -k docs/images/failures.png | cut -f1) KB)" >&2
