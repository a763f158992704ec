#!/bin/bash
# tripath's pt against Blender's Cycles at equal time on one glTF model under a white sky, each
# renderer against its own long reference, as docs/performance-notes.md measures it ("tripath
# against Cycles at equal time"). Blender is for this measurement only, never a dependency of the
# build or the tests (install it by hand: apt-get install blender).
#
#   scripts/cycles-equal-time.sh OUT/NAME SCENE.gltf
#
# 1. References: Cycles (scripts/cycles-render.py) and tripath (pt, --sampler independent) at
#    $REF_SPP samples (default 4096), seed 1000, $SIZE × $SIZE pixels (default 256).
# 2. Cycles at $SPP samples (default 64) with seeds 1..$SEEDS (default 3); its time is the render's
#    own ("Time:" in Blender's log: the scene's upload and BVH, the samples, the file).
# 3. tripath pt with each sampler of $SAMPLERS (default "independent sobol"): a first run at $SPP
#    samples gives its seconds per sample, then seeds 1..$SEEDS at the samples that take Cycles'
#    mean time; its time is the process's wall time (the glTF's load, the BVH, the samples, the
#    file), so that both count the same work.
# 4. Per run: its time, samples and relMSE against its own renderer's reference
#    (scripts/cycles-compare.py error); per renderer the mean relMSE, and relMSE × spp.
# Every render runs on 2 threads under `nice`; files already in OUT are reused.
#
# Environment: TRIPATH (default build/tripath), BLENDER (default blender), SIZE, SPP, REF_SPP,
# SEEDS, SAMPLERS.
set -euo pipefail
[ $# -eq 2 ] || { sed -n 2,22p "$0"; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
prefix=$1 scene=$2
TRIPATH=${TRIPATH:-build/tripath} BLENDER=${BLENDER:-blender} SIZE=${SIZE:-256} SPP=${SPP:-64}
REF_SPP=${REF_SPP:-4096} SEEDS=${SEEDS:-3} SAMPLERS=${SAMPLERS:-independent sobol}
mkdir -p "$(dirname "$prefix")"

cycles() {  # cycles OUT.exr SEED SPP
    [ -f "$1" ] || nice -n 10 "$BLENDER" -b --factory-startup -t 2 -P "$here/cycles-render.py" -- --scene "$scene" \
        --out "$1" --width "$SIZE" --height "$SIZE" --spp "$3" --seed "$2" > "$1.log" 2>&1 || { cat "$1.log"; exit 1; }
}
cycles_seconds() {  # the last " Time: MM:SS.ss" of Blender's log
    grep -E '^ ?Time: ' "$1.log" | tail -1 | sed -E 's/^ ?Time: ([0-9]+):([0-9.]+).*/\1 \2/' | awk '{print $1 * 60 + $2}'
}
tripath() {  # tripath OUT.exr SEED SPP SAMPLER
    if [ ! -f "$1" ]; then
        local start end
        start=$(date +%s.%N)
        nice -n 10 "$TRIPATH" render --scene "$scene" --environment 1,1,1 --integrator pt --sampler "$4" --spp "$3" \
            --seed "$2" --width "$SIZE" --height "$SIZE" --threads 2 --out "$1" > "$1.log" 2>&1 || { cat "$1.log"; exit 1; }
        end=$(date +%s.%N)
        awk -v a="$start" -v b="$end" 'BEGIN {print b - a}' > "$1.seconds"
    fi
}
error() {  # error REFERENCE RUN: its relMSE
    /usr/bin/python3 "$here/cycles-compare.py" error --reference "$1" "$2" | awk '{print $2}'
}
report() {  # report NAME REFERENCE SPP SECONDS-OF-EACH-RUN... (runs as $prefix-NAME<seed>.exr)
    local name=$1 ref=$2 spp=$3 sum=0 secs=0
    shift 3
    for seed in $(seq 1 "$SEEDS"); do
        local e t
        e=$(error "$ref" "$prefix-$name$seed.exr")
        t=$1
        shift
        printf '  %-18s seed %d: %5d spp, %7.2f s, relMSE %.5g\n' "$name" "$seed" "$spp" "$t" "$e"
        sum=$(awk -v a="$sum" -v b="$e" 'BEGIN {print a + b}')
        secs=$(awk -v a="$secs" -v b="$t" 'BEGIN {print a + b}')
    done
    awk -v n="$name" -v s="$sum" -v t="$secs" -v k="$SEEDS" -v spp="$spp" \
        'BEGIN {printf "%s: mean relMSE %.5g at %.2f s (%d spp); relMSE x spp %.4g, relMSE x s %.4g\n", n, s / k, t / k, spp, s / k * spp, s / k * t / k}'
}

echo "references ($REF_SPP spp)..."
cycles "$prefix-cy-ref.exr" 1000 "$REF_SPP"
tripath "$prefix-tp-ref.exr" 1000 "$REF_SPP" independent

times=()
for seed in $(seq 1 "$SEEDS"); do
    cycles "$prefix-cy$seed.exr" "$seed" "$SPP"
    times+=("$(cycles_seconds "$prefix-cy$seed.exr")")
done
report cy "$prefix-cy-ref.exr" "$SPP" "${times[@]}"
target=$(printf '%s\n' "${times[@]}" | awk '{s += $1} END {print s / NR}')

for sampler in $SAMPLERS; do
    tripath "$prefix-tp-$sampler-probe.exr" 99 "$SPP" "$sampler"
    spp=$(awk -v t="$target" -v p="$(cat "$prefix-tp-$sampler-probe.exr.seconds")" -v s="$SPP" \
        'BEGIN {n = int(s * t / p + 0.5); print n < 1 ? 1 : n}')
    times=()
    for seed in $(seq 1 "$SEEDS"); do
        tripath "$prefix-tp-$sampler$seed.exr" "$seed" "$spp" "$sampler"
        times+=("$(cat "$prefix-tp-$sampler$seed.exr.seconds")")
    done
    report "tp-$sampler" "$prefix-tp-ref.exr" "$spp" "${times[@]}"
done
