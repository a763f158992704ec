#!/bin/bash
# tripath against Blender's Cycles on one glTF model, as measured in docs/gltf-samples.md
# ("tripath against Cycles"). Blender is for this measurement only, never a dependency of the
# build or the tests (install it by hand: apt-get install blender).
#
#   scripts/cycles-compare.sh OUT/NAME SCENE.gltf [--lambert] [--flat]
#       renders SCENE with tripath (pt) and with Cycles (scripts/cycles-render.py), each twice
#       with seeds 1 and 2 at $SPP samples (default 256), $SIZE × $SIZE pixels (default 256), 2
#       threads, under `nice`, as OUT/NAME[-lambert][-flat]-{tp,cy}{1,2}.exr, and prints
#       scripts/cycles-compare.py's comparison (also written to OUT/NAME….txt). --lambert and
#       --flat change both renderers alike (tripath renders the copy of SCENE that
#       `cycles-compare.py variant` writes beside it).
#   scripts/cycles-compare.sh OUT/NAME SCENE.gltf --cycles-only OPTION
#       renders Cycles with --OPTION of cycles-render.py (e.g. linear-textures, no-specular) and
#       compares it with OUT/NAME-cy{1,2}.exr from the first form: how much OPTION moves Cycles.
#
# Environment: TRIPATH (default build/tripath), BLENDER (default blender), SPP, SIZE.
set -euo pipefail
[ $# -ge 2 ] || { sed -n 2,16p "$0"; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
prefix=$1 scene=$2
shift 2
TRIPATH=${TRIPATH:-build/tripath} BLENDER=${BLENDER:-blender} SPP=${SPP:-256} SIZE=${SIZE:-256}
mkdir -p "$(dirname "$prefix")"

cycles() {  # cycles OUT.exr SEED [options of cycles-render.py]
    local out=$1 seed=$2
    shift 2
    [ -f "$out" ] || nice -n 10 "$BLENDER" -b --factory-startup -t 2 -P "$here/cycles-render.py" -- \
        --scene "$scene" --out "$out" --width "$SIZE" --height "$SIZE" --spp "$SPP" --seed "$seed" "$@" \
        > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
}

if [ "${1:-}" = --cycles-only ]; then
    option=$2
    for seed in 1 2; do cycles "$prefix-cy-$option$seed.exr" $seed "--$option"; done
    /usr/bin/python3 "$here/cycles-compare.py" compare --tripath "$prefix-cy-$option"1.exr "$prefix-cy-$option"2.exr \
        --cycles "$prefix"-cy1.exr "$prefix"-cy2.exr --heatmap "$prefix-cy-$option-heat.png" | tee "$prefix-cy-$option.txt"
    exit 0
fi

tag="" tscene=$scene
if [ $# -gt 0 ]; then
    tag=$(printf '%s' "$@" | tr -s '-' '-')
    tscene=$(/usr/bin/python3 "$here/cycles-compare.py" variant "$scene" "$@")
fi
out=$prefix$tag
for seed in 1 2; do
    depth=()
    [ $seed = 1 ] && depth=(--depth-images)  # its -k1.exr: the sky seen directly, for the framing check
    [ -f "$out-tp$seed.exr" ] || nice -n 10 "$TRIPATH" render --scene "$tscene" --environment 1,1,1 --integrator pt \
        --spp "$SPP" --seed $seed --width "$SIZE" --height "$SIZE" --threads 2 --out "$out-tp$seed.exr" "${depth[@]}"
    cycles "$out-cy$seed.exr" $seed "$@"
done
/usr/bin/python3 "$here/cycles-compare.py" compare --tripath "$out"-tp1.exr "$out"-tp2.exr \
    --cycles "$out"-cy1.exr "$out"-cy2.exr --heatmap "$out-heat.png" | tee "$out.txt"
