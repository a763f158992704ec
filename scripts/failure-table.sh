#!/usr/bin/env bash
# The "where each method fails" table of docs/failures.md, and its contact sheet.
#
#   scripts/failure-table.sh [SECONDS] [SIZE]     defaults: 4 seconds per integrator, 128x128
#
# For each failure scene (src/geometry/failure_scenes.h) it runs `tripath compare`: a reference
# rendered for 10x the time (by bdpt, or by vcm on the scenes with paths bdpt cannot sample),
# then pt, lt, bdpt, vcm, bpm and ppm for SECONDS each (equal time). It
# reads each method's final relMSE (and spp) from the compare's error.csv and writes:
#   docs/failures.md          the table between its <!-- table:begin/end --> markers (the text
#                             around them is written by hand and left alone); best in bold
#   docs/images/failures.png  reference and every method per scene, each row scaled alike
# The renders themselves stay in build/failures/<scene>/ (compare's report: index.html).
# Runtime: 11 scenes x 16 x SECONDS plus start-up, about 12 minutes at the defaults. Timings
# are wall-clock: run it on an otherwise idle machine, or the table measures the neighbours.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-4}"
size="${2:-128}"
tripath="${TRIPATH:-build/tripath}"
out=build/failures
scenes=(caustic caustic-point sds sds-point sds-mirrors door-ajar contact grazing degenerate degenerate-tiny degenerate-far)
methods=(pt lt bdpt vcm bpm ppm)
# The reference's integrator: vcm where some light has no bdpt strategy (the caustic seen through
# the pane), bdpt elsewhere (unbiased, and at least as good where it can sample every path).
declare -A reference_integrator=([sds]=vcm [sds-point]=vcm [sds-mirrors]=vcm)

[ -x "$tripath" ] || { echo "error: $tripath not found: build first (scripts/build.sh) or set TRIPATH" >&2; exit 1; }
mkdir -p "$out" docs/images

# "relMSE spp" of a method's finished render: the last row of its run 0 in error.csv
# (columns: integrator,run,seconds,spp,relmse,mse,mae).
final() {
  awk -F, -v m="$2" '$1 == m && $2 == 0 { spp = $4; rel = $5 } END { print rel, spp }' "$1/error.csv"
}

table="$out/table.md"
{
  echo "| scene | reference | $(IFS='|'; echo "${methods[*]}" | sed 's/|/ | /g') |"
  echo "|---|---|$(printf -- '---|%.0s' "${methods[@]}")"
} >"$table"
sheet=()
for scene in "${scenes[@]}"; do
  dir="$out/$scene"
  rm -rf "$dir"
  refint="${reference_integrator[$scene]:-bdpt}"
  "$tripath" compare --scene "$scene" --integrators "$(IFS=,; echo "${methods[*]}")" --reference-integrator "$refint" \
    --time "$seconds" --width "$size" --height "$size" --out "$dir" 2>"$out/$scene.log" || { cat "$out/$scene.log" >&2; exit 1; }
  declare -A rel=() spp=()
  best=""
  for m in "${methods[@]}"; do
    read -r r s < <(final "$dir" "$m")
    rel[$m]=$r
    spp[$m]=$s
    if [ -z "$best" ] || awk -v a="$r" -v b="${rel[$best]}" 'BEGIN { exit !(a < b) }'; then best=$m; fi
  done
  row="| \`$scene\` | $refint |"
  for m in "${methods[@]}"; do
    cell=$(printf '%.3g (%s spp)' "${rel[$m]}" "${spp[$m]}")
    [ "$m" = "$best" ] && cell="**$cell**"
    row="$row $cell |"
  done
  echo "$row" >>"$table"
  sheet+=("$dir/reference.exr")
  for m in "${methods[@]}"; do sheet+=("$dir/$m.exr"); done
  echo "$row" >&2
done

# Shrunk 2x (box filter) so that the sheet stays small enough for the repository.
"$tripath" montage "${sheet[@]}" --columns $((${#methods[@]} + 1)) --shrink 2 --out docs/images/failures.png \
  --column-labels "reference,$(IFS=,; echo "${methods[*]}")" --row-labels "$(IFS=,; echo "${scenes[*]}")"

# Replace the generated block of docs/failures.md, keeping the hand-written text around it.
note="relMSE against the reference after ${seconds} s per method at ${size}x${size} ($(date -u +%Y-%m-%d), $(nproc) cores); lower is better, the best of each row in bold."
awk -v table="$table" -v note="$note" '
  /<!-- table:begin -->/ { print; print ""; print note; print ""; while ((getline line < table) > 0) print line; print ""; skip = 1; next }
  /<!-- table:end -->/ { skip = 0 }
  !skip { print }
' docs/failures.md >"$out/failures.md"
mv "$out/failures.md" docs/failures.md
echo "wrote docs/failures.md and docs/images/failures.png ($(du -k docs/images/failures.png | cut -f1) KB)" >&2
