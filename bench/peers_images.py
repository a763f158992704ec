#!/usr/bin/python3
# Image arithmetic for the peer comparisons (bench/peers-smallvcm.sh): tripath's relMSE of an
# image against a reference, and a block-by-block comparison of two converged images (to check
# that a rebuilt peer scene is the same scene). Reads anything OpenImageIO reads (.exr, .hdr).
#
# Why a separate script: the peers write their own formats at their own resolutions, and the
# error must be computed the same way for every image of a comparison. relMSE here is exactly
# src/evaluation/metrics.cpp's: the mean over pixels and all three channels of (x − r)² / (r² + ε),
# ε = 0.01. An image whose size is an integer multiple of the requested size is box-filtered down
# first (SmallVCM renders 512×512 only; the mean of 2×2 box-filtered pixels is the 256×256
# box-filtered pixel, so nothing but the sample count changes).
#
# Run with Debian's /usr/bin/python3 (python3-openimageio, python3-numpy).
#   peers_images.py relmse TEST REF --size 256      prints "relmse mse mean_r mean_g mean_b"
#   peers_images.py blocks A B --size 256 --blocks 8  prints means and per-block differences
import argparse
import sys

import numpy as np
import OpenImageIO as oiio


def load_rgbe(path):
    """A flat (not run-length encoded) Radiance RGBE file, as SmallVCM writes it, decoded the way
    Ward's own reader does: (m + 0.5) · 2^(e − 136). Writers truncate the 8-bit mantissa m, so a
    value lies anywhere in [m, m + 1) units; OpenImageIO's reader returns m · 2^(e − 136), the
    bottom of that interval, which reads every channel 0.5 units low: −0.2 % to −0.4 % on a
    pixel's brightest channel and several per cent on dim ones (the green wall's red), enough
    to mask a real difference between two scenes."""
    data = open(path, "rb").read()
    pos = 0
    while True:  # header lines up to the empty one
        end = data.index(b"\n", pos)
        line = data[pos:end].decode("ascii", "replace")
        pos = end + 1
        if line == "":
            break
        if line.startswith("FORMAT=") and line != "FORMAT=32-bit_rle_rgbe":
            sys.exit(f"error: {path}: {line}")
    end = data.index(b"\n", pos)
    res = data[pos:end].decode("ascii").split()
    pos = end + 1
    if len(res) != 4 or res[0] != "-Y" or res[2] != "+X":
        sys.exit(f"error: {path}: resolution line {' '.join(res)} (expected -Y H +X W)")
    h, w = int(res[1]), int(res[3])
    if len(data) - pos != w * h * 4:
        sys.exit(f"error: {path}: not a flat RGBE image of {w}x{h} (run-length encoded?)")
    px = np.frombuffer(data, dtype=np.uint8, count=w * h * 4, offset=pos).reshape(h, w, 4)
    e = px[:, :, 3].astype(np.int32)
    scale = np.where(e > 0, np.ldexp(1.0, e - 136), 0.0)
    return (px[:, :, :3].astype(np.float64) + 0.5) * scale[:, :, None]


def load(path, size):
    if path.lower().endswith(".hdr"):
        return downsample(path, load_rgbe(path), size)
    buf = oiio.ImageBuf(path)
    if buf.has_error:
        sys.exit(f"error: {path}: {buf.geterror()}")
    img = buf.get_pixels(oiio.FLOAT)
    if img is None or img.ndim != 3 or img.shape[2] < 3:
        sys.exit(f"error: {path}: not an RGB image")
    return downsample(path, img[:, :, :3].astype(np.float64), size)


def downsample(path, img, size):
    h, w = img.shape[:2]
    if size:
        if h % size or w % size or h != w:
            sys.exit(f"error: {path} is {w}x{h}, not a square multiple of {size}")
        f = h // size
        img = img.reshape(size, f, size, f, 3).mean(axis=(1, 3))
    return img


def relmse(test, ref, eps=0.01):
    d = test - ref
    return float(np.mean(d * d / (ref * ref + eps))), float(np.mean(d * d))


def main():
    p = argparse.ArgumentParser(description="relMSE and block comparisons of images from tripath and its peers")
    p.add_argument("mode", choices=["relmse", "blocks"])
    p.add_argument("a")
    p.add_argument("b")
    p.add_argument("--size", type=int, default=0, help="box-filter both images down to size×size")
    p.add_argument("--blocks", type=int, default=8, help="blocks per side (blocks mode)")
    args = p.parse_args()
    a, b = load(args.a, args.size), load(args.b, args.size)
    if a.shape != b.shape:
        sys.exit(f"error: sizes differ: {a.shape} and {b.shape}")
    if not (np.isfinite(a).all() and np.isfinite(b).all()):
        sys.exit("error: non-finite pixels")
    if args.mode == "relmse":
        rel, mse = relmse(a, b)
        m = a.reshape(-1, 3).mean(axis=0)
        print(f"{rel:.6g} {mse:.6g} {m[0]:.5f} {m[1]:.5f} {m[2]:.5f}")
        return
    # blocks: means, relMSE of A against B, and each block's relative difference (A − B) / B
    # per channel, over an n×n grid.
    n = args.blocks
    h = a.shape[0]
    if h % n:
        sys.exit(f"error: {h} pixels do not split into {n} blocks")
    s = h // n
    ba = a.reshape(n, s, n, s, 3).mean(axis=(1, 3))
    bb = b.reshape(n, s, n, s, 3).mean(axis=(1, 3))
    rd = (ba - bb) / np.maximum(bb, 1e-6)
    ma, mb = a.reshape(-1, 3).mean(axis=0), b.reshape(-1, 3).mean(axis=0)
    print(f"mean A  {ma[0]:.5f} {ma[1]:.5f} {ma[2]:.5f}   ({args.a})")
    print(f"mean B  {mb[0]:.5f} {mb[1]:.5f} {mb[2]:.5f}   ({args.b})")
    print(f"mean (A-B)/B per channel: {' '.join(f'{x:+.4f}' for x in (ma - mb) / mb)}")
    print(f"relMSE of A against B: {relmse(a, b)[0]:.5g}")
    lum = rd.mean(axis=2)
    print(f"{n}x{n} blocks, (A-B)/B averaged over channels (row 0 = top of the image):")
    for row in lum:
        print("  " + " ".join(f"{x:+.3f}" for x in row))
    k = np.unravel_index(np.argmax(np.abs(rd)), rd.shape)
    print(f"blocks: median |rel diff| {np.median(np.abs(rd)):.4f}, max |rel diff| {np.abs(rd).max():.4f} "
          f"at block row {k[0]} col {k[1]} channel {'RGB'[k[2]]}")


if __name__ == "__main__":
    main()
