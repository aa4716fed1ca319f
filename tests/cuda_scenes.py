"""Renders the GPU kernel's test scenes on device="cuda" and on device="cpu", for
tests/test_cuda.py, in a process of its own: run with NUMBA_ENABLE_CUDASIM=1 (Numba's
CUDA simulator, which must be chosen before numba.cuda is first imported).

    NUMBA_ENABLE_CUDASIM=1 python tests/cuda_scenes.py SCENES.json OUT.npz

SCENES.json: a list of [name, expression, {"heightfield": seed} or {"fractal": seed},
render keywords];
the keyword "objects" as a list of [kind, arguments...] (fc.box, fc.pole, fc.tree).
OUT.npz gets NAME/DEVICE/ARRAY for rgba, side, intensity, depth, u, v and samples.
"""
import json
import os
import sys

import numpy as np

os.environ.setdefault("FLOATCOL_DRAFT", "0")

import floatcol as fc  # noqa: E402


def surface(spec):
    if isinstance(spec, dict) and "fractal" in spec:
        # (test_lod.py's fly-through DEM: 65^2 fractal heights on cells of 40 units)
        from reference import fractal
        return fc.HeightField(fractal(65, seed=spec["fractal"]) * 30, u=(0, 2560),
                              v=(0, 2560))
    if isinstance(spec, dict):
        rng = np.random.default_rng(spec["heightfield"])
        z = np.cumsum(np.cumsum(rng.normal(size=(33, 33)), 0), 1) / 12.0
        return fc.HeightField(z, u=(-4, 4), v=(-4, 4))
    return spec


def main(scenes_path, out_path):
    with open(scenes_path) as fh:
        scenes = json.load(fh)
    out = {}
    for name, spec, kw in scenes:
        if "objects" in kw:
            kw = dict(kw, objects=[getattr(fc, kind)(*args) for kind, *args in kw["objects"]])
        for device in ("cpu", "cuda"):
            r = fc.render(surface(spec), device=device, **kw)
            for key in ("rgba", "side", "intensity", "depth", "u", "v"):
                out[f"{name}/{device}/{key}"] = np.asarray(getattr(r, key))
            out[f"{name}/{device}/samples"] = np.array(r.stats["samples"])
            out[f"{name}/{device}/geometry"] = np.array(r.stats.get("geometry", ""))
    np.savez(out_path, **out)


if __name__ == "__main__":
    main(*sys.argv[1:3])
