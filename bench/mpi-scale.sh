#!/usr/bin/env bash
# Distributed rendering on this machine (docs/distributed.md):
#  1. the time to add the ranks' films into rank 0's at the end of a render (MPI_Reduce of the
#     exact totals, 72 bytes a pixel) at 512², 1920x1080 and 4096², on 1 and 2 ranks;
#  2. throughput of 2 ranks x 1 thread against 1 process x 2 threads (bdpt, cornell, 256²).
# Usage: bash bench/mpi-scale.sh [path/to/tripath]   (default build/tripath)
set -euo pipefail
T=${1:-build/tripath}
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # mpirun refuses root otherwise
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
echo "size ranks reduce_seconds"
for size in "512 512" "1920 1080" "4096 4096"; do
  set -- $size
  for np in 1 2; do
    # One pass of direct light per rank: the film's size, not the render, is what is measured.
    line=$(mpirun --oversubscribe -np $np "$T" render --scene cornell --integrator pt --max-depth 1 \
             --spp $((4 * np)) --width $1 --height $2 --threads 1 --out "$out/r.exr" 2>&1 | grep "films were added" || true)
    secs=$(echo "$line" | sed -n 's/.* in \([0-9.]*\) s$/\1/p')
    echo "${1}x${2} $np $secs"
  done
done
echo
echo "layout Msamples/s (bdpt cornell 256², 64 spp; median of 3)"
run() { for i in 1 2 3; do "$@" 2>&1 | sed -n 's/.*(\([0-9.]*\) Msamples.*/\1/p'; done | sort -n | sed -n 2p; }
args=(render --scene cornell --integrator bdpt --spp 64 --width 256 --height 256 --out "$out/t.exr")
echo "1 process x 2 threads $(run "$T" "${args[@]}" --threads 2)"
echo "2 ranks x 1 thread $(run mpirun --bind-to core -np 2 "$T" "${args[@]}" --threads 1)"
