#!/usr/bin/env bash
# Equal-time comparison with SmallVCM on its scene 5 (the peer is described in bench/README.md,
# "Peers: SmallVCM"): tripath pt, bdpt and vcm on the built-in `smallvcm-5` against
# SmallVCM's pt, bpt and vcm on its own analytic scene 5, at 256×256, max path length 10, on two
# cores, SECONDS_EACH seconds each. Each image is measured against a converged reference of its
# own renderer (the two scenes differ by the tessellation of the spheres), with tripath's relMSE
# (bench/peers_images.py), and the table gives relMSE, samples per pixel and relMSE × spp (lower
# is better: the error a method would have after one sample per pixel), and relMSE × seconds.
#
# It downloads nothing. Give it a SmallVCM binary built with two edits to src/config.hxx (the
# steps are in bench/README.md, "Peers"): scenes 4 and 5 appended to g_SceneConfigs, and the
# base seed read from SMALLVCM_SEED (SmallVCM's seed is a constant, so without it the reference
# would repeat the random numbers of the runs it measures). The script checks for both.
#
#   bash bench/peers-smallvcm.sh /tmp/smallvcm/smallvcm        (or SMALLVCM=/path/smallvcm)
#
# Knobs: SECONDS_EACH=20, SEED=7 (the runs' seed in both renderers: another seed is another
# independent run against the same references), OUT=out/peers-smallvcm, TRIPATH=<binary>
# (default: build Release into build-bench/ as bench/run.sh does, with scripts/build.sh's profile),
# TRIPATH_REF_SECONDS=600, SMALLVCM_REF_ITERATIONS=800 (SmallVCM bpt at 512², 4 samples per 256²
# pixel each). References already in OUT are reused; delete them to render new ones. About 3
# minutes plus the references on the 2-core machine.
#
# SmallVCM's traps, handled here: it ignores OMP_NUM_THREADS (it is pinned with `taskset -c 0,1`
# and uses what it is given), its -t counts CPU time summed over threads (so it is run for a
# number of iterations, -i, measured per wall-clock second just before), and its resolution is
# fixed at 512×512 (its images are box-filtered to 256×256; one iteration is 4 samples per pixel
# there). tripath is pinned the same way.
set -euo pipefail
cd "$(dirname "$0")/.."

SMALLVCM=${1:-${SMALLVCM:-}}
SECONDS_EACH=${SECONDS_EACH:-20}
SEED=${SEED:-7}
OUT=${OUT:-out/peers-smallvcm}
TRIPATH_REF_SECONDS=${TRIPATH_REF_SECONDS:-600}
SMALLVCM_REF_ITERATIONS=${SMALLVCM_REF_ITERATIONS:-800}
SIZE=256
DEPTH=10
PY=/usr/bin/python3
IMAGES="$PY bench/peers_images.py"

die() { echo "error: $*" >&2; exit 1; }
[ -n "$SMALLVCM" ] || die "give the SmallVCM binary: bash bench/peers-smallvcm.sh /path/to/smallvcm"
[ -x "$SMALLVCM" ] || die "$SMALLVCM is not an executable"
SMALLVCM=$(realpath "$SMALLVCM")
help=$("$SMALLVCM" -h 2>&1 || true)
grep -q "5    small spheres + ceiling" <<<"$help" \
    || die "$SMALLVCM has no scene 5 'small spheres + ceiling': append the two scene configs (bench/README.md)"
grep -q SMALLVCM_SEED "$SMALLVCM" \
    || die "$SMALLVCM does not read SMALLVCM_SEED: its reference would reuse the runs' random numbers (bench/README.md)"
"$PY" -c "import OpenImageIO, numpy" 2>/dev/null || die "$PY needs python3-openimageio and python3-numpy"

if [ -z "${TRIPATH:-}" ]; then
    profile=$(bash scripts/pgo-profile.sh build/pgo | tail -n 1)
    cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DTRIPATH_TESTS=OFF -DTRIPATH_PGO_PROFILE="$profile" >/dev/null
    cmake --build build-bench -j2 --target tripath
    TRIPATH=build-bench/tripath
fi
[ -x "$TRIPATH" ] || die "$TRIPATH is not an executable"
TRIPATH=$(realpath "$TRIPATH")

mkdir -p "$OUT"
OUT=$(realpath "$OUT")
PIN="taskset -c 0,1"
now() { date +%s.%N; }
echo "before: $(uptime)" | tee "$OUT/load-before.txt"

# ---- references ------------------------------------------------------------------------------
if [ ! -f "$OUT/tripath-ref.exr" ]; then
    echo "tripath reference: bdpt, $TRIPATH_REF_SECONDS s"
    $PIN "$TRIPATH" reference --scene smallvcm-5 --integrator bdpt --time "$TRIPATH_REF_SECONDS" \
        --width $SIZE --height $SIZE --max-depth $DEPTH --threads 2 --out "$OUT/tripath-ref.exr" 2>&1 | tail -1
fi
if [ ! -f "$OUT/smallvcm-ref.hdr" ]; then
    echo "SmallVCM reference: bpt, $SMALLVCM_REF_ITERATIONS iterations, seed 900001"
    # SmallVCM writes into its working directory only what -o names; run it in OUT anyway.
    (cd "$OUT" && SMALLVCM_SEED=900001 $PIN "$SMALLVCM" -s 5 -a bpt -i "$SMALLVCM_REF_ITERATIONS" \
        -o smallvcm-ref.hdr >/dev/null)
fi
echo "references: tripath $($IMAGES relmse "$OUT/tripath-ref.exr" "$OUT/tripath-ref.exr" --size $SIZE | cut -d' ' -f3-)," \
     "SmallVCM $($IMAGES relmse "$OUT/smallvcm-ref.hdr" "$OUT/smallvcm-ref.hdr" --size $SIZE | cut -d' ' -f3-) (mean RGB)"

# ---- the runs ------------------------------------------------------------------------------
ROWS="$OUT/rows.txt"
: > "$ROWS"
row() {  # renderer method seconds spp image reference
    local m
    m=$($IMAGES relmse "$5" "$6" --size $SIZE)
    echo "$1 $2 $3 $4 $m" >> "$ROWS"
}

for method in pt bdpt vcm; do
    echo "tripath $method: $SECONDS_EACH s"
    log=$($PIN "$TRIPATH" render --scene smallvcm-5 --integrator $method --time "$SECONDS_EACH" --width $SIZE \
        --height $SIZE --max-depth $DEPTH --threads 2 --seed "$SEED" --out "$OUT/tripath-$method.exr" 2>&1 | grep "spp in")
    echo "  $log"
    spp=$(sed -E 's/.*: ([0-9]+) spp in ([0-9.]+) s.*/\1/' <<<"$log")
    secs=$(sed -E 's/.*: ([0-9]+) spp in ([0-9.]+) s.*/\2/' <<<"$log")
    row tripath $method "$secs" "$spp" "$OUT/tripath-$method.exr" "$OUT/tripath-ref.exr"
done

# SmallVCM: iterations per wall-clock second from a short run, then -i N for SECONDS_EACH.
declare -A CALIBRATE=([pt]=12 [bpt]=6 [vcm]=4)
for method in pt bpt vcm; do
    k=${CALIBRATE[$method]}
    t0=$(now)
    (cd "$OUT" && $PIN "$SMALLVCM" -s 5 -a $method -i "$k" -o "calibrate-$method.hdr" >/dev/null)
    t1=$(now)
    n=$(awk -v k="$k" -v a="$t0" -v b="$t1" -v s="$SECONDS_EACH" 'BEGIN { n = int(k / (b - a) * s + 0.5); print (n < 1 ? 1 : n) }')
    echo "SmallVCM $method: $(awk -v k="$k" -v a="$t0" -v b="$t1" 'BEGIN { printf "%.2f", k / (b - a) }') iterations/s, running $n"
    t0=$(now)
    (cd "$OUT" && SMALLVCM_SEED=$SEED $PIN "$SMALLVCM" -s 5 -a $method -i "$n" -o "smallvcm-$method.hdr" >/dev/null)
    t1=$(now)
    secs=$(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }')
    echo "  $n iterations in $secs s"
    row smallvcm $method "$secs" $((n * 4)) "$OUT/smallvcm-$method.hdr" "$OUT/smallvcm-ref.hdr"
    rm -f "$OUT/calibrate-$method.hdr"
done
echo "after: $(uptime)" | tee "$OUT/load-after.txt"

# ---- the table -----------------------------------------------------------------------------
{
    echo "SmallVCM scene 5 at ${SIZE}², max length $DEPTH, 2 cores, ${SECONDS_EACH} s each (spp per ${SIZE}² pixel;"
    echo "each renderer against its own reference; $(cut -d, -f3- "$OUT/load-before.txt" | sed 's/^ *//'))"
    echo
    echo "| renderer | method | seconds | spp | relMSE | relMSE × spp | relMSE × s | mean RGB |"
    echo "|---|---|---|---|---|---|---|---|"
    awk '{ printf "| %s | %s | %s | %s | %.4g | %.3g | %.3g | %s %s %s |\n", $1, $2, $3, $4, $5, $5 * $4, $5 * $3, $7, $8, $9 }' "$ROWS"
} | tee "$OUT/table.md"
