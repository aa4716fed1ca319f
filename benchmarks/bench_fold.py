"""Perspective columns whose curve folds back in t (kernels/fold.py): with and without.

A column whose samples show a fold (a wall steeper than the column plane's tilt: a
vertical rim off the picture's centre) is traced as a curve and drawn by depth. This
prints, per surface: side agreement and PSNR of the lambert intensity against the
ray caster (tests/reference.py, with FINE_STEPS march steps: its default is ragged at
vertical rims) at 300x240, and at 1920x1080 the best ms of REPEATS renders and f's
evaluations, the fold switch (vp's VP_FOLD) on and off, alternating in one process
(a shared machine's speed drifts). Every render is warmed up (compiled) first.

    python benchmarks/bench_fold.py [REPEATS]
"""
import os
import sys
import time
import warnings

os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc
from floatcol import view as view_mod
from floatcol.kernels import layout as L

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
from reference import numpy_surface, psnr, raycast  # noqa: E402

ANNULUS = "sqrt(4 - u**2 - v**2) + sqrt(u**2 + v**2 - 1) - 2"
SURFACES = [("annulus, height x4.9 (aspect='auto's box)", f"4.9*({ANNULUS})", 2.2, 40, -30),
            ("annulus", ANNULUS, 2.2, 40, -30),
            ("hemisphere", "sqrt(1 - u**2 - v**2)", 1.1, 30, -30),
            ("tan(uv) (poles)", "tan(u*v)", 2.0, 30, 30),
            ("no fold: 3 sin(u cos v)", "3*sin(u*cos(v))", 5.0, 30, 20)]
FINE_STEPS = 8000


def _render(expr, d, fold, **kw):
    saved = view_mod.View.params

    def params(self):
        vp = saved(self)
        vp[L.VP_FOLD] = vp[L.VP_FOLD] if fold else 0.0
        return vp
    view_mod.View.params = params
    try:
        t = time.perf_counter()
        r = fc.render(expr, u=(-d, d), v=(-d, d), projection="perspective", **kw)
        return r, (time.perf_counter() - t) * 1e3
    finally:
        view_mod.View.params = saved


def main(repeats=3):
    print("| surface | folds | agreement % | PSNR dB | 1920x1080 ms | evaluations |")
    print("|---|---|---|---|---|---|")
    for name, expr, d, elev, azim in SURFACES:
        small = dict(size=(300, 240), elev=elev, azim=azim, shading="lambert")
        big = dict(size=(1920, 1080), elev=elev, azim=azim)
        rows = {}
        for fold in (True, False):
            r, _ = _render(expr, d, fold, **small)
            vw = r.view
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                ref = raycast(numpy_surface(expr), (-d, d), (-d, d), small["size"], elev, azim,
                              "perspective", vw.d1, vw.d2, vw.scale, center=vw.center,
                              steps=FINE_STEPS)
            rows[fold] = [100.0 * (r.side == ref.side).mean(), psnr(r.intensity, ref.intensity),
                          float("inf"), 0]
            _render(expr, d, fold, **big)                        # warm up
        for _ in range(repeats):
            for fold in (True, False):
                r, ms = _render(expr, d, fold, **big)
                rows[fold][2] = min(rows[fold][2], ms)
                rows[fold][3] = r.stats["samples"]
        for fold in (True, False):
            agree, db, ms, ev = rows[fold]
            print(f"| {name} | {'traced' if fold else 'off'} | {agree:.3f} | {db:.2f} | "
                  f"{ms:.0f} | {ev} |")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
