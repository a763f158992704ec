#!/usr/bin/python3
# Bit-for-bit comparison of pairs of EXR images, for scripts/check-compilers.sh.
#
#   exr-identical.py LABEL A.exr B.exr [LABEL A.exr B.exr ...]
#
# Compares the pixels only (the metadata differs between any two renders: `seconds`), as raw
# 32-bit patterns, so that -0 against +0 or two different NaNs count as differences too. Prints
# one row per pair: "identical", or "differs" with the number of differing pixels and the largest
# absolute difference. Exits 1 if any pair differs or cannot be read.
#
# Uses Debian's python3-openimageio and python3-numpy (the same library tripath writes EXRs
# with), hence /usr/bin/python3 rather than whatever python3 comes first on the PATH.
import sys

import numpy as np
import OpenImageIO as oiio


def read(path):
    inp = oiio.ImageInput.open(path)
    if inp is None:
        raise RuntimeError(f"{path}: {oiio.geterror()}")
    spec = inp.spec()
    pixels = inp.read_image(0, 0, 0, spec.nchannels, oiio.FLOAT)
    inp.close()
    if pixels is None:
        raise RuntimeError(f"{path}: cannot read the pixels")
    return np.ascontiguousarray(pixels, dtype=np.float32).reshape(spec.height, spec.width, spec.nchannels)


def main(argv):
    if len(argv) == 0 or len(argv) % 3 != 0:
        print(__doc__ or "usage: exr-identical.py LABEL A.exr B.exr ...", file=sys.stderr)
        return 2
    failed = False
    print(f"{'case':<32} {'result':<10} {'pixels':>14} {'max |diff|':>12}")
    for i in range(0, len(argv), 3):
        label, a_path, b_path = argv[i : i + 3]
        try:
            a, b = read(a_path), read(b_path)
        except RuntimeError as e:
            print(f"{label:<32} {'error':<10} {str(e)}")
            failed = True
            continue
        if a.shape != b.shape:
            print(f"{label:<32} {'differs':<10} shapes {a.shape} and {b.shape}")
            failed = True
            continue
        bits_differ = (a.view(np.uint32) != b.view(np.uint32)).any(axis=2)
        n = int(bits_differ.sum())
        if n == 0:
            print(f"{label:<32} {'identical':<10} {'0':>14} {'0':>12}")
            continue
        failed = True
        with np.errstate(invalid="ignore"):
            diff = np.abs(a.astype(np.float64) - b.astype(np.float64))
        worst = float(np.nanmax(diff)) if np.isfinite(diff).any() else float("nan")
        print(f"{label:<32} {'differs':<10} {f'{n}/{a.shape[0] * a.shape[1]}':>14} {worst:>12.4g}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
