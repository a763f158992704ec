#!/usr/bin/env bash
# Renders every model of a glTF sample-model collection under a sky and tabulates what tripath
# makes of each: whether it loads (or the one-line error), whether it renders, and what the loader
# ignores (its `warning:` lines). The table is docs/gltf-samples.md's; it shows how far real
# assets get, and catches crashes, hangs and NaNs that hand-written test scenes miss.
#
#   scripts/gltf-survey.sh MODELS_DIR OUT_DIR [TRIPATH]        TRIPATH defaults to build/tripath
#
# MODELS_DIR holds one folder per model laid out as Khronos' collections do (the `2.0` folder of
# glTF-Sample-Models, the `Models` folder of glTF-Sample-Assets, or a folder of some of their
# models): <Model>/glTF/*.gltf, else <Model>/glTF-Binary/*.glb is rendered. The light is
# OUT_DIR/sky.exr, made by scripts/sky-exr.py (OpenImageIO's Python binding at /usr/bin/python3).
# Each model is rendered with
#   tripath render --scene F --environment OUT_DIR/sky.exr --integrator vcm --width S --height S --time T
# (S = $SIZE, default 256; T = $SECONDS_PER_MODEL, default 4) under `nice -n 5` and a timeout of
# $TIMEOUT seconds (default 120; a render still running then is reported as a hang). Written to
# OUT_DIR:
#   <Model>.exr, <Model>.png    the render and its preview
#   <Model>.log                 everything tripath printed
#   survey.md                   the table: model, file, loads, renders, samples, what is ignored
# Then two contact sheets, each made by `tripath montage`, four to a row in the order given:
#   $SHEET (default below: eight models whose licences allow showing renders, see
#   docs/gltf-samples.md) to $SHEET_OUT (default docs/images/khronos-sheet.png), and
#   $MARKER_SHEET (default below: the test models with built-in markers, whose look says what
#   passes, see docs/gltf-samples.md) to $MARKER_SHEET_OUT (default docs/images/khronos-markers.png),
#   each image shrunk by $MARKER_SHRINK (default 3: the sheet in docs/gltf-samples.md is of
#   512 x 512 renders, SIZE=512).
# A sheet one of whose models has no render (not in MODELS_DIR, or not loaded) is not written, with
# a note; SHEET= or MARKER_SHEET= (empty) skips a sheet.
# Runtime: about (T + 1) seconds per model.
set -euo pipefail
if [ $# -lt 2 ] || [ $# -gt 3 ]; then echo "usage: $0 MODELS_DIR OUT_DIR [TRIPATH]" >&2; exit 2; fi
models_dir="${1%/}"
out="${2%/}"
here="$(cd "$(dirname "$0")" && pwd)"
tripath="${3:-$here/../build/tripath}"
seconds="${SECONDS_PER_MODEL:-4}"
timeout="${TIMEOUT:-120}"
size="${SIZE:-256}"
sheet_out="${SHEET_OUT:-$here/../docs/images/khronos-sheet.png}"
sheet="${SHEET-Avocado BoomBoxWithAxes WaterBottle Suzanne NormalTangentTest TextureSettingsTest Cube AnimatedMorphSphere}"
marker_sheet_out="${MARKER_SHEET_OUT:-$here/../docs/images/khronos-markers.png}"
marker_sheet="${MARKER_SHEET-TextureTransformTest AlphaBlendModeTest TextureCoordinateTest TextureSettingsTest NormalTangentTest NormalTangentMirrorTest MetalRoughSpheresNoTextures EmissiveStrengthTest}"
marker_shrink="${MARKER_SHRINK:-3}"

[ -d "$models_dir" ] || { echo "error: $models_dir is not a folder" >&2; exit 1; }
[ -x "$tripath" ] || { echo "error: $tripath not found: build it (scripts/build.sh) or pass TRIPATH" >&2; exit 1; }
mkdir -p "$out"
/usr/bin/python3 "$here/sky-exr.py" "$out/sky.exr"

# The model's scene file: its .gltf, else its .glb; nothing when it has neither.
scene_file() {
    local f
    for f in "$1"/glTF/*.gltf "$1"/glTF-Binary/*.glb; do
        [ -f "$f" ] && { echo "$f"; return; }
    done
}

# Markdown-safe table cell: pipes escaped, cut to $2 characters.
cell() {
    local s="${1//|/\\|}"
    [ ${#s} -gt "$2" ] && s="${s:0:$(($2 - 1))}…"
    echo "$s"
}

# One table row from a finished render: $1 model, $2 file, $3 exit status, $4 log.
row() {
    local model="$1" file="$2" rc="$3" log="$4" loads renders samples ignored error
    error="$(grep -m1 '^error: ' "$log" | sed "s|^error: ||; s|$file: ||; s|$models_dir/||g" || true)"
    ignored="$(grep '^warning: ' "$log" | sed "s|^warning: ||; s|$file: ||" | paste -sd ';' | sed 's/;/; /g' || true)"
    samples="$(grep -o '[0-9]* spp in [0-9.]* s\|[0-9]* NaN/Inf samples dropped' "$log" | paste -sd ',' | sed 's/,/, /' || true)"
    loads=yes renders=yes
    # A hang or a crash may come before the load ends: whether it loaded is not known.
    if [ "$rc" -eq 124 ]; then
        loads="?" renders="no: hang (still running after ${timeout} s)"
    elif [ "$rc" -gt 128 ]; then
        loads="?" renders="no: crash (signal $((rc - 128)))"
    elif [ "$rc" -ne 0 ]; then
        # A load error names the scene file; anything else failed after loading.
        if grep -q "^error: $file: " "$log"; then loads="error: $(cell "$error" 110)"; renders=no
        else renders="no: $(cell "$error" 110)"; fi
    fi
    echo "| $model | ${file#"$models_dir"/} | $loads | $renders | ${samples:-—} | $(cell "${ignored:-—}" 400) |"
}

table="$out/survey.md"
{
    echo "| Model | File | Loads | Renders | Samples | Ignored (warnings) |"
    echo "|---|---|---|---|---|---|"
} > "$table"
for dir in "$models_dir"/*/; do
    model="$(basename "$dir")"
    file="$(scene_file "${dir%/}")"
    [ -n "$file" ] || continue
    echo "$model" >&2
    rm -f "$out/$model.exr" "$out/$model.png"
    rc=0
    nice -n 5 timeout "$timeout" "$tripath" render --scene "$file" --environment "$out/sky.exr" --integrator vcm \
        --width "$size" --height "$size" --time "$seconds" --out "$out/$model.exr" --png "$out/$model.png" \
        > "$out/$model.log" 2>&1 || rc=$?
    row "$model" "$file" "$rc" "$out/$model.log" >> "$table"
done
echo "wrote $table" >&2

# The contact sheet of models $1 (space-separated) to $2, shrunk by $3; not written, with a note,
# when a model has no render.
contact_sheet() {
    local names images=() model
    read -r -a names <<< "$1"
    [ ${#names[@]} -gt 0 ] || return 0
    for model in "${names[@]}"; do
        if [ ! -f "$out/$model.exr" ]; then
            echo "note: $2 not written: $model has no render" >&2
            return 0
        fi
        images+=("$out/$model.exr")
    done
    mkdir -p "$(dirname "$2")"
    "$tripath" montage --columns 4 --shrink "$3" --out "$2" "${images[@]}"
}
contact_sheet "$sheet" "$sheet_out" 1
contact_sheet "$marker_sheet" "$marker_sheet_out" "$marker_shrink"
