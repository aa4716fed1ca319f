"""Shadows (Gordon 6.2, issue 28): cost and agreement.

    python benchmarks/bench_shadow.py [--cost | --agreement | --objects]

Prints (1) the cost of shadows at 1920x1080 and 1024x768: render time without
shadows and with each method (the texture of 6.2.1, the sweep on the fly of 6.2.2;
hard and soft), best and median of N after a warm-up, the shadow pass's own time and
the memory it keeps, each texture made afresh (as for a new light or view), and the
texture kept from the render before (the same light and texels: a view turned at one
scale, a fly-through's frames); (1b) the cost of objects' shadows (202 objects on a surface,
1920x1080: shadows, objects, both); (2) the agreement of the lit/shadow state
with the reference ray caster's shadow rays (tests/reference.py) on surfaces, views and
lights that are not in tests/test_shadow.py, both projections.
"""
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc  # noqa: E402
from conftest import reference_for  # noqa: E402
from floatcol.passes import shadow  # noqa: E402
from reference import numpy_surface, shadow_rays  # noqa: E402

EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))
N = 11


VARIANTS = [("none", dict()),
            ("texture (6.2.1)", dict(shadows=True)),
            ("on the fly (6.2.2)", dict(shadows="on-the-fly")),
            ("texture, soft 0.27 deg", dict(shadows=True, light_radius=0.27)),
            ("texture kept (the same light and texels again)", dict(shadows=True))]
#: the variant drawn again with the texture the render before it made (passes/shadow.py
#: keeps a surface's last one); every other variant's texture is made afresh
KEPT = VARIANTS[-1][0]


def timed(**kw):
    """{variant: (best ms, median ms, last Render)}, the variants interleaved so that a
    drift of the machine's speed hits all alike."""
    ts = {name: [] for name, _ in VARIANTS}
    last = {}
    for _ in range(N):
        for name, extra in VARIANTS:
            shadow.forget()
            if name == KEPT:
                fc.render(EXPR, **DOM, **kw, **extra)           # (makes the texture)
            t = time.perf_counter()
            last[name] = fc.render(EXPR, **DOM, **kw, **extra)
            ts[name].append(time.perf_counter() - t)
    return {name: (min(x) * 1e3, sorted(x)[N // 2] * 1e3, last[name]) for name, x in ts.items()}


def memory(name, r):
    """MiB the shadows keep: the texture's planes, or the sweep's pixel cells and
    order (int32 each) and its fronts (per band of lines and thread: two samples of
    three planes, the running extremes, the batch's coordinates)."""
    H, W = r.side.shape
    if "texture" in name:
        # three float32 planes; soft shadows four float64 more
        return r.stats["shadow_texels"] * (12 + (32 if "soft" in name else 0)) / 2**20
    from floatcol.kernels.shadow import BAND
    seen = int((r.side != 0).sum())
    front = (BAND + 1) * 2 * 3 * 4 + (BAND + 1) * 2 * 8 + (BAND + 1) * 3 * 8
    return (H * W * 4 + seen * 4 + front * os.cpu_count()) / 2**20


def cost():
    print("| size | projection | shadows | ms (best / median) | + % (best) | shadow pass ms "
          "| memory MiB |")
    print("|---|---|---|---|---|---|---|")
    for size in ((1920, 1080), (1024, 768)):
        for proj in ("orthographic", "perspective"):
            kw = dict(size=size, projection=proj, lightsource=(315, 35))
            for _, extra in VARIANTS:
                fc.render(EXPR, **DOM, **kw, **extra)          # warm up
            got = timed(**kw)
            b0 = got["none"][0]
            for name, (b, m, r) in got.items():
                if name == "none":
                    print(f"| {size[0]}x{size[1]} | {proj} | none | {b:.1f} / {m:.1f} | | | |")
                    continue
                print(f"| | | {name} | {b:.1f} / {m:.1f} | {100 * (b / b0 - 1):+.0f} % "
                      f"| {r.stats['shadow_seconds'] * 1e3:.1f} | {memory(name, r):.1f} |",
                      flush=True)


CASES = [("2*exp(-((u-1)**2+v**2)) + exp(-((u+1.5)**2+(v-1)**2)/0.5)", (-4, 4), (-4, 4)),
         ("cos(u)*sin(v)*0.8 + 0.3*cos(3*u)", (-6, 6), (-6, 6)),
         ("u*v/2", (-2, 2), (-2, 2)),
         ("sqrt(4 - u**2 - v**2)", (-2, 2), (-2, 2)),
         ("0.5*sin(2*u) + 0.25*v**2", (-3, 3), (-2, 2))]
LIGHTS = [(300, 10), (200, 30), (60, 50), (10, 70)]


def agreement():
    print("\n| surface | projection | " + " | ".join(f"sun {a}/{b}" for a, b in LIGHTS) + " |")
    print("|---|---|" + "---|" * len(LIGHTS))
    worst = 1.0
    for expr, U, V in CASES:
        for proj in ("orthographic", "perspective"):
            row = []
            for az, alt in LIGHTS:
                kw = dict(size=(200, 150), projection=proj, elev=40, azim=-35)
                r = fc.render(expr, u=U, v=V, lightsource=(az, alt), shadows=True, **kw)
                ref = reference_for(r, expr, U, V, 40, -35, proj)
                rs = shadow_rays(numpy_surface(expr), ref, U, V, fc.Light.sun(az, alt).direction)
                both = (r.side != 0) & (ref.side == r.side)
                a = ((r.shadow[both] >= 0.5) == (rs[both] >= 0.5)).mean()
                r2 = fc.render(expr, u=U, v=V, lightsource=(az, alt), shadows="on-the-fly",
                               **kw)
                a2 = ((r2.shadow[both] >= 0.5) == (rs[both] >= 0.5)).mean()
                worst = min(worst, a, a2)
                row.append(f"{100 * a:.2f} %" + ("" if a2 == a else f" ({100 * a2:.2f} %)"))
            print(f"| {expr} | {proj[:5]} | " + " | ".join(row) + " |")
    print(f"\nworst agreement: {100 * worst:.2f} % (on the fly in brackets where it differs "
          "from the texture)")


def objects_cost():
    """Objects' shadows (objects.Occluders): 200 trees, a box and a pole on a gentle
    surface at 1920x1080, the variants interleaved, median of N after a warm-up."""
    rng = np.random.default_rng(1)
    objs = [fc.tree(u, v, 0.6) for u, v in rng.uniform(-4, 4, (200, 2))]
    objs += [fc.box(-1, 0, 1, 1, 1.5), fc.pole(1.5, 1, 2.0)]
    variants = [("shadows", dict(shadows=True)), ("objects", dict(objects=objs)),
                ("objects and their shadows", dict(objects=objs, shadows=True))]
    print("\n| 1920x1080, 202 objects | " + " | ".join(n for n, _ in variants)
          + " | object pixels |")
    print("|---|---|---|---|---|")
    for proj in ("orthographic", "perspective"):
        kw = dict(u=(-4, 4), v=(-4, 4), size=(1920, 1080), elev=35, azim=20,
                  projection=proj, lightsource=(300, 30))
        ts = {n: [] for n, _ in variants}
        for k in range(N + 1):
            for n, extra in variants:
                shadow.forget()                 # (each its own texture, as at a new light)
                t = time.perf_counter()
                r = fc.render("0.2*sin(u)*cos(v)", **kw, **extra)
                if k:
                    ts[n].append(time.perf_counter() - t)
        print(f"| {proj} | " + " | ".join(f"{sorted(x)[N // 2] * 1e3:.1f} ms" for x in ts.values())
              + f" | {r.stats['object_pixels']} |", flush=True)


if __name__ == "__main__":
    args = sys.argv[1:]
    if "--objects" in args:
        objects_cost()
    else:
        if "--agreement" not in args:
            cost()
            objects_cost()
        if "--cost" not in args:
            agreement()
