#!/usr/bin/env bash
# The one documented benchmark command (bench/README.md): builds Release into build-bench/ (with
# the profile-guided optimisation of scripts/build.sh), runs every microbenchmark with JSON to
# out/bench.json, measures the 1M-triangle scene's memory in a fresh process (out/memory.json),
# times full 512×512 renders of cornell per integrator (out/render-*.txt), and prints the
# README's tables (also kept in out/report.md).
#
# About 6 minutes on the 2-core development machine at load 3, 9 at load 5-8. Knobs:
#   MIN_TIME=0.5   seconds per benchmark and repetition (Google Benchmark 1.7 takes a bare number)
#   REPS=3         repetitions; the report uses the medians
#   FILTER=...     a --benchmark_filter regex, to run a subset (the report shows what ran)
set -euo pipefail
cd "$(dirname "$0")/.."

MIN_TIME=${MIN_TIME:-0.5}
REPS=${REPS:-3}
FILTER=${FILTER:-.}

# Built as scripts/build.sh builds: with the profile of the training renders (made or reused in build/pgo).
profile=$(bash scripts/pgo-profile.sh build/pgo | tail -n 1)
cmake -S . -B build-bench -DCMAKE_BUILD_TYPE=Release -DTRIPATH_TESTS=OFF -DTRIPATH_PGO_PROFILE="$profile" >/dev/null
cmake --build build-bench -j"$(nproc)" --target tripath_bench tripath

mkdir -p out
rm -f out/render-*.txt out/load-*.txt
echo "before: $(uptime)" | tee out/load-1-before.txt

./build-bench/tripath_bench --benchmark_filter="$FILTER" --benchmark_min_time="$MIN_TIME" \
    --benchmark_repetitions="$REPS" --benchmark_report_aggregates_only=false \
    --benchmark_out=out/bench.json --benchmark_out_format=json

# The memory figure in a process of its own: nothing else resident, so the peak is the scene's.
./build-bench/tripath_bench --benchmark_filter='^memory/tess-1000000/' \
    --benchmark_out=out/memory.json --benchmark_out_format=json

# Whole renders through the CLI: the render loop's own seconds (scene loading and EXR writing
# excluded) are in the summary line "N spp in S s". Depth 16 is the CLI default, 8 the depth the
# targets are stated at.
# /usr/bin/time adds the process's CPU seconds: on a shared machine the wall-clock spp/s says
# how many cores we were given as much as how fast the code is. A 1-pixel render measures the
# fixed CPU cost (process start-up, scene build, EXR writing) to take off.
/usr/bin/time -f "cpu %U %S" ./build-bench/tripath render --scene cornell --integrator pt --spp 1 \
    --width 1 --height 1 --out /tmp/tripath-bench-fixed.exr > out/render-fixed.txt 2>&1
for depth in 16 8; do
    for integrator in pt lt bdpt; do
        spp=16
        [ "$integrator" = bdpt ] && spp=8
        /usr/bin/time -f "cpu %U %S" ./build-bench/tripath render --scene cornell --integrator "$integrator" \
            --spp "$spp" --max-depth "$depth" --width 512 --height 512 --out "/tmp/tripath-bench-$integrator.exr" \
            > "out/render-$integrator-d$depth.txt" 2>&1
        grep -h "spp in\|^cpu" "out/render-$integrator-d$depth.txt" | tr '\n' ' '; echo
    done
done
echo "after: $(uptime)" | tee out/load-2-after.txt

python3 bench/report.py out | tee out/report.md
