#!/usr/bin/python3
# Compares tripath's render of a glTF model with Cycles' (scripts/cycles-render.py), for
# docs/gltf-samples.md ("tripath against Cycles"). Blender is for this measurement only, never a
# dependency of the build or the tests. Needs numpy and OpenImageIO's Python binding
# (python3-numpy, python3-openimageio).
#
#   cycles-compare.py variant M.gltf [--lambert] [--flat]
#       writes beside M.gltf the copy tripath renders for cycles-render.py's option of the same
#       name, and prints its path: --lambert sets every material's metallicFactor 0 and
#       roughnessFactor 1 and drops its metallicRoughnessTexture (tripath reads that as
#       Lambertian, albedo = base colour); --flat drops every normalTexture.
#
#   cycles-compare.py compare --tripath T1.exr T2.exr --cycles C1.exr C2.exr [--block 16]
#                             [--heatmap ratio.png]
#       each renderer's image made twice with different seeds (the halves of one render); the
#       means are compared, the halves' difference estimates the noise. Cycles' EXR has a
#       transparent film: its alpha is the model's coverage and (1 − alpha) × the sky (1, 1, 1)
#       is added back to its RGB. Over the pixels the model covers wholly in Cycles (alpha ≥
#       0.999) it prints, from luminance (Rec. 709 Y): the ratio of the mean radiance
#       tripath / Cycles; per block of B × B pixels (those at least half covered) the relative
#       difference tripath / Cycles − 1, its median and 90th percentile of |·|, and the largest
#       blocks; and the noise of both. With T1-k1.exr beside T1.exr (tripath --depth-images:
#       the sky seen directly), it checks the framing first: tripath's coverage (1 − k1) against
#       Cycles' alpha, their overlap and the offset of their centroids in pixels. Two Cycles
#       renders compare as well (give the one as --tripath): how much a Cycles-only option moves it.
#       --heatmap writes the blocks' differences over Cycles' image: red where tripath is
#       brighter, blue where darker, full colour at ±20 %.
#
#   cycles-compare.py error --reference R.exr RUN.exr...
#       each run's relMSE against the reference as tripath's benchmark measures it (the mean over
#       pixels and channels of (x − r)² / (r² + 0.01)), one line per run; a Cycles EXR's sky is
#       added back first. scripts/cycles-equal-time.sh uses it.
#
#   cycles-compare.py spheres MetalRoughSpheresNoTextures.gltf --tripath T1 T2 --cycles C1 C2
#       the same ratio per grey sphere of that model (its 7 × 7 front grid, metallic by row,
#       roughness by column), over a disc of 0.7 of the sphere's radius around its projected
#       centre; the camera is rebuilt from the bounds cycles-render.py logged in C1.exr.log.
import argparse
import json
import math
import os
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        sys.exit(f"error: cannot read {path}: {oiio.geterror()}")
    spec = inp.spec()
    px = inp.read_image(0, 0, 0, spec.nchannels, "float")
    inp.close()
    return np.asarray(px, dtype=np.float64), list(spec.channelnames)


def luminance(rgb):
    return rgb[..., 0] * 0.2126 + rgb[..., 1] * 0.7152 + rgb[..., 2] * 0.0722


def with_sky(img):
    """Cycles' transparent film: the sky seen directly, (1 − alpha) × (1, 1, 1), added back."""
    return img[..., :3] + (1.0 - img[..., 3:4]) if img.shape[-1] == 4 else img[..., :3]


def variant(args):
    with open(args.scene) as f:
        g = json.load(f)
    tags = []
    if args.lambert:
        tags.append("lambert")
        for m in g.get("materials", []):
            pbr = m.setdefault("pbrMetallicRoughness", {})
            pbr["metallicFactor"] = 0.0
            pbr["roughnessFactor"] = 1.0
            pbr.pop("metallicRoughnessTexture", None)
    if args.flat:
        tags.append("flat")
        for m in g.get("materials", []):
            m.pop("normalTexture", None)
    if not tags:
        sys.exit("error: give --lambert and/or --flat")
    base, ext = os.path.splitext(args.scene)
    out = f"{base}.{'-'.join(tags)}{ext}"
    with open(out, "w") as f:
        json.dump(g, f)
    print(out)


def compare(args):
    tp = [read(p)[0] for p in args.tripath]
    cy = [read(p)[0] for p in args.cycles]
    if any(c.shape[-1] != 4 for c in cy):
        sys.exit("error: the Cycles EXR has no alpha (render it with cycles-render.py)")
    alpha = np.mean([c[..., 3] for c in cy], axis=0)
    tp, cy = [with_sky(t) for t in tp], [with_sky(c) for c in cy]
    h, w = alpha.shape

    k1 = os.path.splitext(args.tripath[0])[0] + "-k1.exr"
    if os.path.exists(k1):
        sky = luminance(read(k1)[0][..., :3])
        cov_t = np.clip(1.0 - sky, 0, 1)
        yy, xx = np.mgrid[0:h, 0:w] + 0.5
        ct = np.array([(cov_t * xx).sum(), (cov_t * yy).sum()]) / cov_t.sum()
        cc = np.array([(alpha * xx).sum(), (alpha * yy).sum()]) / alpha.sum()
        mt, mc = cov_t > 0.5, alpha > 0.5
        iou = (mt & mc).sum() / max(1, (mt | mc).sum())
        edge = (alpha > 0.01) & (alpha < 0.99)
        print(f"framing: coverage {cov_t.sum():.1f} px (tripath) vs {alpha.sum():.1f} px (Cycles); "
              f"centroid offset ({ct[0] - cc[0]:+.3f}, {ct[1] - cc[1]:+.3f}) px; overlap (IoU) {iou:.4f}; "
              f"mean |coverage difference| on {edge.sum()} edge pixels {np.abs(cov_t - alpha)[edge].mean():.3f}")

    covered = alpha >= 0.999
    yt = [luminance(t) for t in tp]
    yc = [luminance(c) for c in cy]
    Yt, Yc = np.mean(yt, axis=0), np.mean(yc, axis=0)
    n = covered.sum()

    def ratio_noise(sel):
        st = [y[sel].sum() for y in yt]
        sc = [y[sel].sum() for y in yc]
        mt_, mc_ = np.mean(st), np.mean(sc)
        # with two halves, the standard error of their mean is |a − b| / 2
        rel = math.hypot(abs(st[0] - st[1]) / 2 / mt_, abs(sc[0] - sc[1]) / 2 / mc_)
        return mt_ / mc_, rel

    r, rn = ratio_noise(covered)
    T, C = np.mean(tp, axis=0), np.mean(cy, axis=0)
    chans = " ".join(f"{name} {T[..., i][covered].mean():.4f}/{C[..., i][covered].mean():.4f}" for i, name in enumerate("RGB"))
    print(f"covered pixels: {n} of {w * h}")
    print(f"mean ratio tripath/Cycles (Y): {r:.4f} (noise {rn:.4f}); per channel, tripath/Cycles means: {chans}")

    b = args.block
    rows = []
    for by in range(0, h, b):
        for bx in range(0, w, b):
            sel = np.zeros_like(covered)
            sel[by:by + b, bx:bx + b] = covered[by:by + b, bx:bx + b]
            if sel.sum() < b * b / 2:
                continue
            rr, nn = ratio_noise(sel)
            rows.append((bx, by, rr - 1.0, nn))
    d = np.array([abs(x[2]) for x in rows])
    noise = math.sqrt(np.mean([x[3] ** 2 for x in rows]))
    print(f"blocks {b}x{b} (at least half covered): {len(rows)}; |tripath/Cycles - 1|: median {np.median(d):.4f}, "
          f"90th percentile {np.percentile(d, 90):.4f}, max {d.max():.4f}; block noise (rms) {noise:.4f}")
    worst = sorted(rows, key=lambda x: -abs(x[2]))[:args.worst]
    print("largest blocks (x, y of the corner, difference, noise): " +
          "; ".join(f"({x}, {y}) {dd:+.3f} ±{nn:.3f}" for x, y, dd, nn in worst))
    sign = np.array([x[2] for x in rows])
    print(f"blocks above +3 %: {(sign > 0.03).sum()}, below -3 %: {(sign < -0.03).sum()}")

    if args.heatmap:
        # log2 ratio per pixel, blurred by the block grid: red where tripath is brighter, blue darker
        ratio = np.ones((h, w))
        for x, y, dd, _ in rows:
            ratio[y:y + b, x:x + b] = 1 + dd
        lr = np.clip(np.log2(ratio) / math.log2(1.2), -1, 1)
        img = np.zeros((h, w, 3), dtype=np.float32)
        img[..., 0] = np.where(lr > 0, 1, 1 + lr)
        img[..., 1] = 1 - np.abs(lr)
        img[..., 2] = np.where(lr < 0, 1, 1 - lr)
        shade = np.clip(Yc / max(1e-6, np.percentile(Yc, 98)), 0, 1) ** (1 / 2.2)
        img *= (0.35 + 0.65 * shade)[..., None]
        out = oiio.ImageOutput.create(args.heatmap)
        out.open(args.heatmap, oiio.ImageSpec(w, h, 3, "uint8"))
        out.write_image((np.clip(img, 0, 1) * 255 + 0.5).astype(np.uint8))
        out.close()


def spheres(args):
    with open(args.scene) as f:
        nodes = json.load(f)["nodes"]
    with open(args.cycles[0] + ".log") as f:
        line = next(x for x in f if x.startswith("cycles-render: bounds glTF"))
    lo, hi = (np.array([float(v) for v in part.strip(" ()").split(",")])
              for part in line.split("bounds glTF")[1].split(";")[0].split(".."))
    tp = [luminance(with_sky(read(p)[0])) for p in args.tripath]
    cy = [luminance(with_sky(read(p)[0])) for p in args.cycles]
    h, w = cy[0].shape
    yfov, radius = 0.6911, 0.00035  # tripath's framing; the spheres' radius in the file
    cam = (lo + hi) / 2 + np.array([0, 0, 0.5 * np.linalg.norm(hi - lo) / math.sin(yfov / 2) * 1.05])
    t = math.tan(yfov / 2)
    yy, xx = np.mgrid[0:h, 0:w] + 0.5
    rows = nodes[0]["children"]  # "Gray Spheres": one node per metallic value, a sphere per roughness
    print("metallic \\ roughness: tripath / Cycles")
    for r in rows:
        out = []
        for n in nodes[r]["children"]:
            p = np.array(nodes[n].get("translation", [0, 0, 0]))
            dz = cam[2] - p[2]
            px, py = ((p[0] - cam[0]) / dz / t + 1) * 0.5 * w, (1 - (p[1] - cam[1]) / dz / t / (w / h)) * 0.5 * h
            rp = radius / dz / t * 0.5 * w
            sel = (xx - px) ** 2 + (yy - py) ** 2 < (0.7 * rp) ** 2
            out.append(np.mean([y[sel].sum() for y in tp]) / np.mean([y[sel].sum() for y in cy]))
        print(f"{nodes[r]['name']:>6} " + " ".join(f"{v:.3f}" for v in out) + f"  ({sel.sum()} px a disc)")


def error(args):
    ref = with_sky(read(args.reference)[0])
    for path in args.runs:
        img = with_sky(read(path)[0])
        if img.shape != ref.shape:
            sys.exit(f"error: {path} is {img.shape[1]}x{img.shape[0]}, the reference {ref.shape[1]}x{ref.shape[0]}")
        print(f"{path} {((img - ref) ** 2 / (ref ** 2 + 0.01)).mean():.6g}")


def main():
    p = argparse.ArgumentParser(prog="cycles-compare.py")
    sub = p.add_subparsers(dest="cmd", required=True)
    v = sub.add_parser("variant")
    v.add_argument("scene")
    v.add_argument("--lambert", action="store_true")
    v.add_argument("--flat", action="store_true")
    c = sub.add_parser("compare")
    c.add_argument("--tripath", nargs=2, required=True)
    c.add_argument("--cycles", nargs=2, required=True)
    c.add_argument("--block", type=int, default=16)
    c.add_argument("--worst", type=int, default=6)
    c.add_argument("--heatmap")
    s = sub.add_parser("spheres")
    s.add_argument("scene")
    s.add_argument("--tripath", nargs=2, required=True)
    s.add_argument("--cycles", nargs=2, required=True)
    e = sub.add_parser("error")
    e.add_argument("--reference", required=True)
    e.add_argument("runs", nargs="+")
    a = p.parse_args()
    {"variant": variant, "compare": compare, "spheres": spheres, "error": error}[a.cmd](a)


main()
