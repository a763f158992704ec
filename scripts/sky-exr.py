#!/usr/bin/python3
"""A small analytic sky as an equirectangular EXR, to light glTF models that carry no emitters.

    /usr/bin/python3 scripts/sky-exr.py OUT.exr [WIDTH]        default 256 (the map is WIDTH x WIDTH/2)

Written with OpenImageIO's Python binding (python3-openimageio) and numpy, both from the system's
/usr/bin/python3. The map follows tripath's convention (docs/lights.md): texel (column u, row v)
looks along d = (sin t sin p, cos t, -sin t cos p) with t = v pi and p = (u - 0.5) 2 pi, +Y up.

Above the horizon the radiance runs from a pale horizon to a blue zenith; below it is a dull
brown-grey ground; a soft warm sun (a cos^64 lobe, about 10 degrees wide) sits 40 degrees up, to
the right of and behind a camera looking along -Z, so that models show their shape instead of the
flat look of a constant sky. Its irradiance on a surface facing it is about that of the sky, so a
few seconds of rendering stay free of fireflies. Values are linear radiance; nothing is random.
"""
import sys

import numpy as np
import OpenImageIO as oiio

HORIZON = np.array([1.00, 0.97, 0.92])
ZENITH = np.array([0.25, 0.45, 0.95])
GROUND = np.array([0.30, 0.27, 0.24])
SUN_COLOR = np.array([1.00, 0.90, 0.75]) * 20.0
SUN_EXPONENT = 64.0
SUN_ELEVATION = np.radians(40.0)
SUN_AZIMUTH = np.radians(35.0)  # from +Z (behind a camera looking along -Z) toward +X


def directions(width, height):
    """Unit directions at the texel centres, shape (height, width, 3)."""
    u = (np.arange(width) + 0.5) / width
    v = (np.arange(height) + 0.5) / height
    p, t = np.meshgrid((u - 0.5) * 2.0 * np.pi, v * np.pi)
    return np.stack([np.sin(t) * np.sin(p), np.cos(t), -np.sin(t) * np.cos(p)], axis=-1)


def sky(d):
    """Linear RGB radiance seen along the unit directions d."""
    y = d[..., 1:2]
    above = np.sqrt(np.clip(y, 0.0, 1.0))
    radiance = np.where(y > 0.0, HORIZON * (1.0 - above) + ZENITH * above, GROUND)
    sun = np.array([np.cos(SUN_ELEVATION) * np.sin(SUN_AZIMUTH), np.sin(SUN_ELEVATION),
                    np.cos(SUN_ELEVATION) * np.cos(SUN_AZIMUTH)])
    lobe = np.clip(d @ sun, 0.0, 1.0)[..., None] ** SUN_EXPONENT
    return radiance + SUN_COLOR * lobe


def write_exr(path, rgb):
    out = oiio.ImageOutput.create(path)
    if out is None:
        sys.exit(f"error: cannot write {path}: {oiio.geterror()}")
    height, width = rgb.shape[:2]
    out.open(path, oiio.ImageSpec(width, height, 3, "float"))
    out.write_image(rgb.astype(np.float32))
    out.close()


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit("usage: sky-exr.py OUT.exr [WIDTH]")
    width = int(sys.argv[2]) if len(sys.argv) == 3 else 256
    if width < 2 or width % 2:
        sys.exit("error: WIDTH must be an even number of at least 2")
    write_exr(sys.argv[1], sky(directions(width, width // 2)))


if __name__ == "__main__":
    main()
