"""Which of pt and bdpt wins on cornell-spheres, and how fast: relMSE against a reference as a
function of render time, one render per budget, plotted log-log (docs/python.md).

    PYTHONPATH=build/python /usr/bin/python3 python/examples/error_vs_time.py [figure.png]
"""
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt

import tripath

size = dict(width=128, height=128)
scene = tripath.load("cornell-spheres")

# vcm samples every path of this scene (the caustics under the glass sphere included); its own
# streams are independent of the runs' because its seed differs from theirs.
reference = tripath.render(scene, "vcm", seconds=60, seed=1000, **size)["image"]

budgets = [0.25, 0.5, 1, 2, 4, 8]
plt.figure(figsize=(6, 4))
for method in ["pt", "bdpt"]:
    errors = []
    for seconds in budgets:
        r = tripath.render(scene, method, seconds=seconds, seed=1, **size)
        errors.append(tripath.metrics.relmse(r["image"], reference))
        print(f"{method} {seconds:5.2f} s: {r['spp']:5d} spp, relMSE {errors[-1]:.4g}", flush=True)
    plt.loglog(budgets, errors, "o-", label=method)
plt.xlabel("render time (s)")
plt.ylabel("relMSE against a 60 s vcm reference")
plt.title("cornell-spheres, 128x128")
plt.grid(True, which="both", alpha=0.3)
plt.legend()
plt.tight_layout()
plt.savefig(sys.argv[1] if len(sys.argv) > 1 else "error-vs-time.png", dpi=100)
