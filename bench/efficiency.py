#!/usr/bin/env python3
"""Efficiency at equal quality: samples/s ÷ (relMSE × spp) of several configurations of `tripath
render` (binaries or flags), from interleaved runs, against one reference.

Each configuration is NAME=BINARY or NAME=BINARY|EXTRA FLAGS. For each seed (301, 302, ...) every
configuration renders in turn, so that a change in the machine's load touches them alike. relMSE
is tripath.metrics.relmse of each run against the reference; relMSE × spp estimates an unbiased
method's error after one sample per pixel; samples/s is the median over runs, from the time the
render reports. Higher efficiency is lower error at equal time. This is how bench/README.md's
"Roulette start depth per integrator" and "No loss elsewhere" tables were made, e.g.

    PYTHONPATH=build/python /usr/bin/python3 bench/efficiency.py --scene cornell --integrator bdpt \\
        --spp 64 --runs 8 --reference ref.exr "rr3=build/tripath|--rr-depth 3" "rr2=build/tripath|--rr-depth 2"

where ref.exr is a long render of the same scene and size (`tripath render --time 90 --seed 999`).
"""
import argparse
import re
import statistics
import subprocess
import sys
import tempfile

import tripath


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("configs", nargs="+", help="NAME=BINARY or NAME=BINARY|EXTRA FLAGS")
    parser.add_argument("--scene", required=True)
    parser.add_argument("--integrator", required=True)
    parser.add_argument("--reference", required=True, help="EXR of the same scene, size and max depth")
    parser.add_argument("--spp", type=int, default=16, help="samples per pixel of each run")
    parser.add_argument("--runs", type=int, default=8, help="runs per configuration (seeds 301, 302, ...)")
    parser.add_argument("--size", type=int, default=256, help="width and height")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--flags", default="", help="flags every configuration gets (e.g. '--max-depth 10')")
    args = parser.parse_args()

    configs = []
    for c in args.configs:
        name, sep, spec = c.partition("=")
        if not sep or not spec:
            parser.error(f"'{c}' is not NAME=BINARY or NAME=BINARY|FLAGS")
        binary, _, extra = spec.partition("|")
        configs.append((name, binary, extra.split()))
    reference = tripath.read_exr(args.reference)[0]
    pixels = args.size * args.size
    results = {name: [] for name, _, _ in configs}
    with tempfile.TemporaryDirectory() as tmp:
        for seed in range(301, 301 + args.runs):
            for name, binary, extra in configs:
                out = f"{tmp}/{name}.exr"
                command = [binary, "render", "--scene", args.scene, "--integrator", args.integrator, "--spp", str(args.spp),
                           "--width", str(args.size), "--height", str(args.size), "--threads", str(args.threads),
                           "--seed", str(seed), "--out", out, *args.flags.split(), *extra]
                p = subprocess.run(command, capture_output=True, text=True)
                if p.returncode != 0:
                    sys.exit(f"error: {' '.join(command)}: {p.stderr.strip()}")
                seconds = float(re.search(r"spp in ([0-9.]+) s", p.stderr).group(1))
                results[name].append((seconds, tripath.metrics.relmse(tripath.read_exr(out)[0], reference)))
    print(f"{args.scene}, {args.integrator}: {args.runs} runs × {args.spp} spp, {args.size}², {args.threads} threads")
    for name, rows in results.items():
        rate = statistics.median(args.spp * pixels / s for s, _ in rows)
        per_sample = [r * args.spp for _, r in rows]
        mean = statistics.mean(per_sample)
        error = statistics.stdev(per_sample) / len(per_sample) ** 0.5 if len(per_sample) > 1 else float("nan")
        print(f"{name:12s} ksamples/s {rate / 1e3:8.1f}   relMSE × spp {mean:.4g} ± {error:.2g}   "
              f"efficiency {rate / mean / 1e6:.4g}")


if __name__ == "__main__":
    main()
