#!/usr/bin/env python3
"""Turns what bench/run.sh wrote into out/ into the markdown tables of bench/README.md.

usage: python3 bench/report.py OUT_DIR > OUT_DIR/report.md

Reads OUT_DIR/bench.json (tripath_bench, Google Benchmark JSON; with repetitions, the medians),
OUT_DIR/memory.json (the 1M-triangle scene alone in a fresh process), OUT_DIR/render-*.txt (the
`tripath render` summaries) and OUT_DIR/load-*.txt (uptime before and after).

Two rates are given for every throughput figure. "wall" is per wall-clock second. "per CPU-s" is
per second of CPU time the process actually got: on this shared 2-core machine other people's
compiles take a varying share of the cores, and the per-CPU-second rate is
what a benchmark would show with the cores to itself (times the threads it runs), so the ratios
between two benchmarks are much steadier in it.
"""
import json
import os
import re
import sys
from collections import OrderedDict

SCENES = ["cornell", "cornell-spheres", "veach-mis", "tess-1M"]
KINDS = ["camera_subpath", "light_subpath", "pt", "lt", "bdpt"]


def load_runs(path):
    """name -> run dict; the median aggregate when the file has repetitions."""
    with open(path) as f:
        data = json.load(f)
    runs, medians = OrderedDict(), OrderedDict()
    for b in data["benchmarks"]:
        if b.get("error_occurred"):
            continue
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                medians[b["run_name"]] = b
        else:
            runs.setdefault(b.get("run_name", b["name"]), b)
    runs.update(medians)
    return data.get("context", {}), runs


def base_name(name):
    # Google Benchmark appends "/process_time/real_time" for UseRealTime + MeasureProcessCPUTime.
    return name.replace("/process_time", "").replace("/real_time", "")


def per_cpu(run, counter):
    """A rate counter converted from per wall-clock second to per CPU-second of the process."""
    return run[counter] * run["real_time"] / run["cpu_time"]


def si(x, unit=""):
    for scale, prefix in ((1e9, "G"), (1e6, "M"), (1e3, "k")):
        if abs(x) >= scale:
            return f"{x / scale:.3g} {prefix}{unit}".rstrip()
    return f"{x:.3g} {unit}".rstrip()


def ns(run):
    scale = {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}[run.get("time_unit", "ns")]
    return run["cpu_time"] * scale


def fit(xs, ys):
    n = len(xs)
    mx, my = sum(xs) / n, sum(ys) / n
    sxx = sum((x - mx) ** 2 for x in xs)
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    return slope, my - slope * mx


def main(out):
    context, raw = load_runs(os.path.join(out, "bench.json"))
    runs = {base_name(k): v for k, v in raw.items()}
    p = print

    p(f"Machine: {context.get('num_cpus')} CPUs at {context.get('mhz_per_cpu')} MHz; "
      f"load average at start of the benchmark run: {context.get('loadavg_at_start', '?')}")
    for f in sorted(os.listdir(out)):
        if f.startswith("load-") and f.endswith(".txt"):
            p(f"`{f[:-4]}`: {open(os.path.join(out, f)).read().strip()}")
    p()

    # ---- ceiling
    p("### Ceiling: incoherent random rays through Scene::intersect / Scene::unoccluded\n")
    p("| scene | kind | 1 thread (wall) | 2 threads (wall) | 2 threads (per CPU-s) | CPU use at 2 threads | hit fraction |")
    p("|---|---|---|---|---|---|---|")
    ceiling = {}
    for s in SCENES:
        for kind in ("intersect", "occluded"):
            r1 = runs.get(f"ceiling/{kind}/{s}/threads:1")
            r2 = runs.get(f"ceiling/{kind}/{s}/threads:2")
            if not (r1 and r2):
                continue
            ceiling[(s, kind)] = (r2["rays_per_s"], per_cpu(r2, "rays_per_s"))
            p(f"| {s} | {kind} | {si(r1['rays_per_s'])} | {si(r2['rays_per_s'])} | "
              f"{si(per_cpu(r2, 'rays_per_s'))} | {r2['cpu_time'] / r2['real_time']:.2f} | {r2['hit_fraction']:.2f} |")
    p()

    # ---- whole samples
    p("### Whole samples at max-depth 8\n")
    p("Rays per sample: *exact* counts every rtcIntersect1/rtcOccluded1 call (isect + occl); *est* is "
      "the estimate from vertices: ray-found subpath vertices + unoccluded shadow connections. "
      "Fraction of ceiling: the sample's rays/s over the ceiling for the same mix of closest-hit "
      "and shadow rays on the same scene, both on 2 threads.\n")
    p("| scene | kind | samples/s 1T (wall) | samples/s 2T (wall) | samples/s per CPU-s (1T / 2T) | CPU use 2T | rays/sample exact (isect+occl) | rays/sample est | rays/s 2T (wall) | fraction of ceiling (wall) | fraction of ceiling (per CPU-s) |")
    p("|---|---|---|---|---|---|---|---|---|---|---|")
    fractions = {}
    for s in SCENES:
        for k in KINDS:
            r1 = runs.get(f"sample/{k}/{s}/depth:8/threads:1")
            r2 = runs.get(f"sample/{k}/{s}/depth:8/threads:2")
            if not (r1 and r2):
                continue
            ni, no = r2["isect_per_sample"], r2["occl_per_sample"]
            frac = ["–", "–"]
            if (s, "intersect") in ceiling and (s, "occluded") in ceiling and ni + no > 0:
                vals = []
                for j in (0, 1):
                    ri, ro = ceiling[(s, "intersect")][j], ceiling[(s, "occluded")][j]
                    mix = (ni + no) / (ni / ri + no / ro)
                    rate = r2["rays_per_s"] if j == 0 else per_cpu(r2, "rays_per_s")
                    vals.append(rate / mix)
                fractions[(s, k)] = vals
                frac = [f"{v:.0%}" for v in vals]
            p(f"| {s} | {k} | {si(r1['samples_per_s'])} | {si(r2['samples_per_s'])} | "
              f"{si(per_cpu(r1, 'samples_per_s'))} / {si(per_cpu(r2, 'samples_per_s'))} | "
              f"{r2['cpu_time'] / r2['real_time']:.2f} | {r2['rays_per_sample']:.2f} ({ni:.2f}+{no:.2f}) | "
              f"{r2['rays_est_per_sample']:.2f} | {si(r2['rays_per_s'])} | {frac[0]} | {frac[1]} |")
    p()

    # ---- kernels
    p("### Kernels (single thread, CPU time per call)\n")
    p("| kernel | ns/call |")
    p("|---|---|")
    for name, r in runs.items():
        if name.startswith("kernel/") and not name.startswith("kernel/mis/") and not name.startswith("kernel/connect/"):
            extra = f" (visible {r['visible_fraction']:.0%})" if "visible_fraction" in r else ""
            p(f"| {name[7:]} | {ns(r):.1f}{extra} |")
    p()

    p("### connect() on real cornell subpaths (single thread)\n")
    p("| (s,t) | ns/call | non-zero | rays/call |")
    p("|---|---|---|---|")
    for name, r in runs.items():
        m = re.match(r"kernel/connect/s:(\d+)/t:(\d+)$", name)
        if m:
            p(f"| ({m[1]},{m[2]}) | {ns(r):.0f} | {r['nonzero_fraction']:.0%} | {r['rays_per_call']:.2f} |")
    p()

    p("### MIS weight against path length k (single thread, ns/call)\n")
    series = OrderedDict()
    for name, r in runs.items():
        m = re.match(r"kernel/mis/(\w+)/(\w+)/k:(\d+)$", name)
        if m:
            series.setdefault(f"{m[1]} {m[2]}", {})[int(m[3])] = ns(r)
    if series:
        ks = sorted(next(iter(series.values())).keys())
        p("| series | " + " | ".join(f"k={k}" for k in ks) + " | slope ns/vertex | intercept ns |")
        p("|---|" + "---|" * (len(ks) + 2))
        for label, pts in series.items():
            xs = sorted(pts)
            slope, icpt = fit(xs, [pts[x] for x in xs])
            p(f"| {label} | " + " | ".join(f"{pts[k]:.1f}" for k in ks) + f" | {slope:.2f} | {icpt:.1f} |")
    p()

    # ---- scaling
    p("### Scaling (2 threads)\n")
    p("| scene | triangles | pt samples/s (wall) | pt samples/s (per CPU-s) | slowdown vs 36 (per CPU-s) |")
    p("|---|---|---|---|---|")
    base = None
    for n in (36, 1000, 10000, 100000, 1000000):
        r = runs.get(f"scaling/triangles/pt/tess-{n}/depth:8/threads:2")
        if not r:
            continue
        v = per_cpu(r, "samples_per_s")
        base = base or v
        p(f"| tess-{n} | {n} | {si(r['samples_per_s'])} | {si(v)} | {base / v:.2f}× |")
    p()
    p("| integrator | max-depth | samples/s (wall) | samples/s (per CPU-s) | rays/sample |")
    p("|---|---|---|---|---|")
    for k in ("pt", "bdpt"):
        for d in (4, 8, 16, 32):
            r = runs.get(f"scaling/depth/{k}/cornell/depth:{d}/threads:2")
            if r:
                p(f"| {k} | {d} | {si(r['samples_per_s'])} | {si(per_cpu(r, 'samples_per_s'))} | {r['rays_per_sample']:.2f} |")
    p()

    # ---- memory
    p("### Memory\n")
    p("| run | triangles | RSS before build | RSS after build | scene resident | peak during build | build time |")
    p("|---|---|---|---|---|---|---|")
    mem_runs = [("same process as the benchmarks", runs)]
    mpath = os.path.join(out, "memory.json")
    if os.path.exists(mpath) and os.path.getsize(mpath) == 0:
        mpath = os.path.join(out, "missing-memory.json")  # the fresh-process run failed: skip it
    if os.path.exists(mpath):
        mem_runs.insert(0, ("fresh process", {base_name(k): v for k, v in load_runs(mpath)[1].items()}))
    for label, rs in mem_runs:
        for name, r in rs.items():
            if name.startswith("memory/"):
                p(f"| {label}: {name[7:]} | {r['triangles']:.0f} | {r['rss_before_MiB']:.0f} MiB | {r['rss_after_MiB']:.0f} MiB | "
                  f"{r['scene_resident_MiB']:.0f} MiB | {r['peak_MiB']:.0f} MiB | {r['build_s']:.2f} s |")
    p()

    # ---- renders
    p("### Full renders: `tripath render --scene cornell --width 512 --height 512`\n")
    p("*spp/s (wall)* is the render loop's own time as `tripath render` reports it. *per CPU-s* divides "
      "by the process's CPU seconds less the fixed cost of a 1-pixel render (start-up, scene, EXR); "
      "*2 free cores* is twice that, what the render would do with both cores to itself, assuming "
      "the 2-thread scaling the harness measures (per-CPU-s rates at 1 and 2 threads agree).\n")
    p("| integrator | max-depth | spp | render seconds | spp/s (wall) | CPU seconds | spp per CPU-s | projected spp/s on 2 free cores |")
    p("|---|---|---|---|---|---|---|---|")
    def cpu_seconds(text):
        g = re.search(r"^cpu ([\d.]+) ([\d.]+)", text, re.M)
        return float(g[1]) + float(g[2]) if g else None
    fixed = 0.0
    fpath = os.path.join(out, "render-fixed.txt")
    if os.path.exists(fpath):
        fixed = cpu_seconds(open(fpath).read()) or 0.0
    renders = {}
    for f in sorted(os.listdir(out)):
        m = re.match(r"render-(\w+)-d(\d+)\.txt$", f)
        if not m:
            continue
        text = open(os.path.join(out, f)).read()
        g = re.search(r"(\d+) spp in ([\d.]+) s", text)
        if g:
            spp, sec = int(g[1]), float(g[2])
            cpu = cpu_seconds(text)
            proj = 2 * spp / (cpu - fixed) if cpu and cpu > fixed else None
            renders[(m[1], int(m[2]))] = (spp / sec, proj)
            cells = f"{cpu:.2f} | {spp / (cpu - fixed):.2f} | {proj:.2f}" if proj else "– | – | –"
            p(f"| {m[1]} | {m[2]} | {spp} | {sec:.2f} | {spp / sec:.2f} | {cells} |")
    if fixed:
        p(f"\nFixed CPU cost of `tripath render` (1×1 pixel, 1 spp): {fixed:.2f} s.")
    p()

    # ---- targets
    p("### Targets\n")
    def verdict(ok):
        return "**met**" if ok else "**missed**"
    # The verdict uses the per-CPU-second fraction: the wall-clock one compares two runs made at
    # different moments, each with whatever share of the cores the machine left it, and is only
    # meaningful when both had the two cores (CPU use near 2.0).
    for k in ("pt", "bdpt"):
        if ("cornell", k) in fractions:
            w, c = fractions[("cornell", k)]
            r2 = runs[f"sample/{k}/cornell/depth:8/threads:2"]
            ci = runs["ceiling/intersect/cornell/threads:2"]
            co = runs["ceiling/occluded/cornell/threads:2"]
            uses = f"CPU use {r2['cpu_time'] / r2['real_time']:.2f} vs ceiling {ci['cpu_time'] / ci['real_time']:.2f}/{co['cpu_time'] / co['real_time']:.2f}"
            p(f"- {k} on cornell, max-depth 8, 2 threads: rays/s = {c:.0%} of the ceiling per CPU-second "
              f"(wall: {w:.0%}, {uses}); target ≥ 60%: {verdict(c >= 0.6)}")
    for k, target in (("pt", 7), ("bdpt", 2)):
        for d in (16, 8):
            if (k, d) in renders:
                wall, proj = renders[(k, d)]
                ptxt = f", {proj:.2f} projected on 2 free cores" if proj else ""
                p(f"- {k} 512×512 cornell (max-depth {d}): {wall:.2f} spp/s measured{ptxt}; target ≥ {target}: "
                  f"{verdict(wall >= target)} as measured" + (f", {verdict(proj >= target)} as projected" if proj else ""))
    if "bdpt power" in series:
        pts = series["bdpt power"]
        p(f"- MIS weight: {pts[min(pts)]:.0f} ns at k={min(pts)}, {pts[max(pts)]:.0f} ns at k={max(pts)} "
          f"(O(k) by design; see the slope above)")
    r36 = runs.get("scaling/triangles/pt/tess-36/depth:8/threads:2")
    r1m = runs.get("scaling/triangles/pt/tess-1000000/depth:8/threads:2")
    if r36 and r1m:
        sw = r36["samples_per_s"] / r1m["samples_per_s"]
        sc = per_cpu(r36, "samples_per_s") / per_cpu(r1m, "samples_per_s")
        p(f"- 36 → 1M triangles: pt samples/s falls {sw:.2f}× (wall), {sc:.2f}× (per CPU-s); target < 3×: "
          f"{verdict(sc < 3)}")
    mem = None
    if os.path.exists(mpath):
        for name, r in load_runs(mpath)[1].items():
            if "tess-1000000" in name:
                mem = r
    if mem:
        p(f"- 1M triangles resident: {mem['rss_after_MiB']:.0f} MiB for the whole process after the build "
          f"(peak {mem['peak_MiB']:.0f} MiB); target < 1 GiB: {verdict(mem['peak_MiB'] < 1024)}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "out")
