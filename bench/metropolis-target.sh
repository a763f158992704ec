#!/usr/bin/env bash
# mlt against bdpt and vcm at equal time, side by side in one run on one machine: on door-ajar,
# where the light reaches the camera through a 7 cm gap that independent samples rarely find, and
# on cornell, where they do well. Each method renders RUNS runs of SECONDS at 128x128 (`tripath
# compare`), measured against a vcm reference of REF_SECONDS per scene (rendered once, then kept in
# build/metropolis-target/). Prints relMSE per method (mean over the runs) and mlt's ratio to the
# better of bdpt and vcm on door-ajar and to bdpt on cornell.
#
#   bench/metropolis-target.sh [SECONDS] [REF_SECONDS] [RUNS]      defaults: 20, 600, 3
#
# Timings are wall-clock: run it on an otherwise idle machine.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-20}"
refSeconds="${2:-600}"
runs="${3:-3}"
tripath="${TRIPATH:-build/tripath}"
out=build/metropolis-target
[ -x "$tripath" ] || { echo "error: $tripath not found: build first (scripts/build.sh) or set TRIPATH" >&2; exit 1; }
mkdir -p "$out"
for scene in door-ajar cornell; do
  ref="$out/$scene-reference.exr"
  [ -f "$ref" ] || "$tripath" reference --scene "$scene" --integrator vcm --time "$refSeconds" --width 128 --height 128 \
    --out "$ref"
  rm -rf "${out:?}/$scene"
  "$tripath" compare --scene "$scene" --integrators bdpt,vcm,mlt --time "$seconds" --runs "$runs" --width 128 \
    --height 128 --reference "$ref" --out "$out/$scene"
done
python3 - "$out" <<'PY'
import csv, sys
out = sys.argv[1]
def final(scene):
    # error.csv: one row per measurement; keep each method's last relMSE of each run, then average.
    last = {}
    with open(f"{out}/{scene}/error.csv") as f:
        for row in csv.DictReader(f):
            last[(row["integrator"], row["run"])] = float(row["relmse"])
    methods = sorted({m for m, _ in last})
    return {m: sum(v for (mm, _), v in last.items() if mm == m) / sum(1 for (mm, _) in last if mm == m) for m in methods}
door, cornell = final("door-ajar"), final("cornell")
for scene, e in (("door-ajar", door), ("cornell", cornell)):
    print(scene, "  ".join(f"{m} {v:.4g}" for m, v in sorted(e.items())))
print(f"door-ajar: mlt / min(bdpt, vcm) = {door['mlt'] / min(door['bdpt'], door['vcm']):.3f} (target <= 0.5)")
print(f"cornell:   mlt / bdpt = {cornell['mlt'] / cornell['bdpt']:.3f} (target <= 3)")
PY
