"""Fidelity table: floatcol against the independent ray caster (tests/reference.py).

For each function of the suite, in orthographic and perspective projection, and for
each mode (iis/nis x corrections, sampling, antialiasing), print: PSNR of
``intensity`` against the ray caster (shading="lambert", background counted as 0),
side-mask agreement, samples, and ms (median of 3, kernels compiled first). The
antialiasing rows compare the picture (``rgba``) with a 3x3 box-filtered ray caster
instead, since antialiasing changes only ``rgba``.

    python benchmarks/bench_fidelity.py            # the whole table (a few minutes)
    python benchmarks/bench_fidelity.py --quick    # 4 functions, fewer modes
"""
import argparse
import os
import statistics
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))

os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc  # noqa: E402
from reference import bilinear_surface, numpy_surface, psnr, raycast, raycast_box  # noqa: E402

SIZE = (160, 120)
PEAKS = ("3*(1-u)**2*exp(-u**2-(v+1)**2) - 10*(u/5-u**3-v**5)*exp(-u**2-v**2)"
         " - exp(-(u+1)**2-v**2)/3")
JUMP = "Piecewise((exp(-u**2-v**2), u < 0.3), (0.4 + 0.2*v, True))"
#: the ray caster shades the jump's wall (the line u = 0.3) as a vertical wall
WALLS = {JUMP: lambda u, v: (np.ones_like(u), np.zeros_like(u))}


def _heightfield():
    rng = np.random.default_rng(7)
    z = rng.normal(size=(24, 24))
    for _ in range(3):                          # smooth a little
        z = (z + np.roll(z, 1, 0) + np.roll(z, -1, 0) + np.roll(z, 1, 1) + np.roll(z, -1, 1)) / 5
    return z * 2.0


HF = _heightfield()
SUITE = [
    # name, expr, half-width of the domain, elev, azim
    ("3 sin(u cos v)", "3*sin(u*cos(v))", 5, 30, 20),
    ("peaks", PEAKS, 3, 30, 30),
    ("sinc", "8*sin(sqrt(u**2+v**2))/sqrt(u**2+v**2)", 12, 30, 30),
    ("saddle", "u**2 - v**2", 2, 35, -30),
    ("monkey saddle", "u**3 - 3*u*v**2", 1.5, 30, 25),
    ("ripples", "2*exp(-(u**2+v**2))*cos(3*sqrt(u**2+v**2))", 3, 25, 40),
    ("jump", JUMP, 2, 30, 30),
    ("heightfield", "hf", 1, 40, 30),
]
MODES = [
    # label, render options
    ("nis none", dict(interpolation="normal", corrections="none")),
    ("nis spline", dict(interpolation="normal", corrections="spline")),
    ("nis supersample", dict(interpolation="normal", corrections="supersample")),
    ("nis adaptive", dict(interpolation="normal", corrections="adaptive")),
    ("nis spline+adaptive (default)", dict(interpolation="normal")),
    ("nis default, sampling=adaptive", dict(interpolation="normal", sampling="adaptive")),
    ("iis none", dict(interpolation="intensity", corrections="none")),
    ("iis spline", dict(interpolation="intensity", corrections="spline")),
    ("iis supersample", dict(interpolation="intensity", corrections="supersample")),
    ("iis adaptive", dict(interpolation="intensity", corrections="adaptive")),
    ("iis spline+adaptive", dict(interpolation="intensity")),
]
AA_MODES = [("AA off", dict(antialias=False)), ("AA coverage", dict(antialias=True)),
            ("AA 3 sub-columns", dict(antialias=3))]


def _surface(expr):
    if expr == "hf":
        return fc.HeightField(HF, u=(-1, 1), v=(-1, 1)), bilinear_surface(HF, (-1, 1), (-1, 1))
    return expr, numpy_surface(expr)


def _timed(fn, reps=3):
    ts, out = [], None
    for _ in range(reps):
        t = time.perf_counter()
        out = fn()
        ts.append(time.perf_counter() - t)
    return out, statistics.median(ts) * 1e3


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    suite = SUITE[6:7] if args.quick else SUITE
    modes = [m for m in MODES if not args.quick or "supersample" not in m[0]]
    fc.render("u*v", size=(16, 12))                 # compile the kernels
    print(f"{SIZE[0]}x{SIZE[1]}, shading='lambert'; PSNR in dB against tests/reference.py")
    summary = []
    for name, expr, d, elev, azim in suite:
        surf, funcs = _surface(expr)
        dom = (-d, d)
        for proj in ("orthographic", "perspective"):
            kw = dict(u=dom, v=dom, size=SIZE, elev=elev, azim=azim, projection=proj,
                      shading="lambert")
            if expr == "hf":
                kw.pop("u"), kw.pop("v")
            base = fc.render(surf, **kw)
            vw = base.view
            ref = raycast(funcs, dom, dom, SIZE, elev, azim, proj, vw.d1, vw.d2, vw.scale,
                          center=vw.center, wall_normal=WALLS.get(expr))
            print(f"\n### {name}, {proj}  (reference sees {100 * (ref.side != 0).mean():.0f} %)")
            print("| mode | PSNR dB | agreement % | samples | ms |")
            print("|---|---|---|---|---|")
            none_samples = None
            for label, opts in modes:
                if proj == "orthographic" and "sampling" in opts:
                    continue
                r, ms = _timed(lambda: fc.render(surf, **kw, **opts))
                p = psnr(r.intensity, ref.intensity)
                agree = 100 * (r.side == ref.side).mean()
                samples = r.stats["samples"]
                if label == "nis none":
                    none_samples = samples
                print(f"| {label} | {p:.2f} | {agree:.3f} | {samples} | {ms:.1f} |")
                if "(default)" in label:
                    summary.append((name, proj, p, agree, samples / none_samples))
            box, _ = raycast_box(funcs, dom, dom, SIZE, elev, azim, proj, vw.d1, vw.d2,
                                 vw.scale, center=vw.center, k=3, wall_normal=WALLS.get(expr))
            for label, opts in AA_MODES:
                r, ms = _timed(lambda: fc.render(surf, **kw, **opts))
                err = (r.rgba[..., 0] / 255.0 - box) ** 2
                print(f"| nis default, {label}: picture vs 3x3 box | "
                      f"{10 * np.log10(1 / err.mean()):.2f} | | {r.stats['samples']} | {ms:.1f} |")
    print("\n### The default (nis, spline+adaptive) with shading='lambert'")
    print("| function | projection | PSNR dB | agreement % | samples / uncorrected |")
    print("|---|---|---|---|---|")
    for name, proj, p, agree, ratio in summary:
        print(f"| {name} | {proj} | {p:.2f} | {agree:.3f} | {ratio:.2f} |")


if __name__ == "__main__":
    main()
