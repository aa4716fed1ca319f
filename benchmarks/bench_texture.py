"""Textures (issue 31): flicker of point lookups against filtered ones, and the cost.

Flicker as Cohen-Or et al. measure it (their Table 6: pixels whose value changes by 6
to 60 levels between two frames of a slow camera move): a gently rolling terrain
draped with fine grey noise (1024 x 1024 texels, each a random level from 60 to
190: neighbours differ by 6 to 60 levels, as a photo's do, and far away many texels
fall in one pixel), seen at a low angle in perspective while the camera
turns by 0.1 degree a frame. Counted on the grey level of the pixels seen in both
frames, per frame, for each texture_filter.

Then the cost at 1920x1080 of a texture, a colour field, contours and a wireframe
against the same render without (warm, median of 7).

    python benchmarks/bench_texture.py
"""
import statistics
import time

import numpy as np

import os
os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc

EXPR = "0.4*sin(u/2)*cos(v/3)"
DOM = dict(u=(-10, 10), v=(-10, 10))


def noise(n=1024):
    g = np.random.default_rng(1).integers(60, 191, (n, n)).astype(np.uint8)
    return np.stack([g] * 3, axis=-1)


def flicker(filt, frames=21, size=(640, 480)):
    tex = noise()
    prev = None
    counts = []
    for k in range(frames):
        r = fc.render(EXPR, size=size, elev=12, azim=30 + 0.1 * k, projection="perspective",
                      texture=tex, texture_filter=filt, ambient=1.0, specular=0.0, **DOM)
        grey = r.rgba[..., :3].astype(int).mean(-1)
        seen = r.side != 0
        if prev is not None:
            both = seen & prev[1]
            d = np.abs(grey - prev[0])[both]
            counts.append(int(((d >= 6) & (d <= 60)).sum()))
        prev = (grey, seen)
    return statistics.mean(counts), int(seen.sum())


def cost_ms(**kw):
    size = (1920, 1080)
    fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=size, **kw)
    ts = []
    for _ in range(7):
        t = time.perf_counter()
        fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=size, **kw)
        ts.append((time.perf_counter() - t) * 1e3)
    return statistics.median(ts)


def main():
    print("Flicker: pixels changing by 6-60 grey levels between frames (camera turning "
          "0.1 degree a frame, 640x480, 20 frame pairs)\n")
    print("| texture_filter | pixels per frame pair | of pixels seen | against point |")
    print("|---|---|---|---|")
    point = None
    for filt in ("point", "linear", "mipmap"):
        n, seen = flicker(filt)
        point = n if point is None else point
        print(f"| {filt} | {n:.0f} | {100 * n / seen:.2f} % | {n / point:.3f}x |")
    print("\nCost at 1920x1080 (3 sin(u cos v), orthographic, default quality)\n")
    print("| what | median ms | added ms |")
    print("|---|---|---|")
    base = cost_ms()
    print(f"| nothing | {base:.1f} | |")
    for name, kw in (("texture 1024x1024 (mipmap)", dict(texture=noise())),
                     ("color='sqrt(u**2+v**2)'", dict(color="sqrt(u**2+v**2)")),
                     ("contours=10", dict(contours=10)),
                     ("wireframe=20", dict(wireframe=20))):
        ms = cost_ms(**kw)
        print(f"| {name} | {ms:.1f} | {ms - base:+.1f} |")


if __name__ == "__main__":
    main()
