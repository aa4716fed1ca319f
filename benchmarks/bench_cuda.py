"""device="cuda" against device="cpu" (issue 34): one prepared script for a machine
with an NVIDIA GPU. Prints, after a warm-up (the GPU kernel's compile, about 2
minutes on 2 cores, timed too):

- 1920x1080 of 3 sin(u cos v) at default quality, orthographic and perspective:
  median and best ms of the whole render and of the column pass (stats
  "kernel_seconds") on each device, and fps;
- the GPU's pictures against the CPU kernel's: PSNR of the intensities (background
  0), side agreement, the largest rgba difference;
- issue 32's fly-through (bench_terrain.py's speed table: a 4097^2 fractal DEM, beta
  2.4, at 1280x720, 8 frames of a slow flight): point sampled (the ray march) and area
  sampled (the level-of-detail engine) on each device, ms a frame, fps, and the GPU's
  pictures against the CPU's.

Without a GPU (or without numba-cuda) it says so and prints the kernels' compile to
PTX instead (no GPU needed), then exits 0.

    python benchmarks/bench_cuda.py [--quick]
"""
import os
import statistics
import sys
import time

import numpy as np

os.environ.setdefault("FLOATCOL_DRAFT", "0")

import floatcol as fc  # noqa: E402

EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))


def psnr(a, b):
    a = np.nan_to_num(np.asarray(a, float))
    b = np.nan_to_num(np.asarray(b, float))
    mse = float(np.mean((a - b) ** 2))
    return float("inf") if mse == 0 else 10 * np.log10(1.0 / mse)


def timed(repeat, **kw):
    totals, kernels = [], []
    for _ in range(repeat):
        t = time.perf_counter()
        r = fc.render(EXPR, **DOM, **kw)
        totals.append((time.perf_counter() - t) * 1e3)
        kernels.append(r.stats["kernel_seconds"] * 1e3)
    return r, totals, kernels


def gpu_here():
    try:
        from floatcol.kernels.cuda import check_device
        check_device()
        return True
    except ValueError as exc:
        print(f"no GPU here: {exc}")
        return False


def main():
    quick = "--quick" in sys.argv
    if not gpu_here():
        from floatcol.kernels.cuda import ptx
        for which in ("column", "march", "lod"):
            try:
                text, seconds = ptx(fc.as_surface(EXPR), which=which)
            except Exception as exc:              # no NVVM either
                print(f"and no CUDA toolkit to compile the kernels to PTX: {exc}")
                return
            print(f"the {which} kernel compiles to PTX for sm_90 in {seconds:.1f} s "
                  f"({len(text) / 1e6:.1f} MB of PTX)")
        return
    repeat = 3 if quick else 11
    size = (960, 540) if quick else (1920, 1080)
    t = time.perf_counter()
    fc.render(EXPR, **DOM, size=(64, 48), device="cuda")
    print(f"first GPU render (the kernel's compile): {time.perf_counter() - t:.1f} s")
    print(f"\n| {size[0]}x{size[1]} | device | median ms | best ms | column pass median ms "
          "| fps | PSNR vs cpu dB | sides agree | max rgba diff |")
    print("|---|---|---|---|---|---|---|---|---|")
    for proj in ("orthographic", "perspective"):
        kw = dict(size=size, projection=proj)
        fc.render(EXPR, **DOM, **kw)
        fc.render(EXPR, **DOM, device="cuda", **kw)
        cpu, c_tot, c_ker = timed(repeat, **kw)
        gpu, g_tot, g_ker = timed(repeat, device="cuda", **kw)
        for name, r, tot, ker in (("cpu", cpu, c_tot, c_ker), ("cuda", gpu, g_tot, g_ker)):
            med = statistics.median(tot)
            extra = "| | | |"
            if name == "cuda":
                diff = np.abs(gpu.rgba.astype(int) - cpu.rgba.astype(int)).max()
                extra = (f"| {psnr(gpu.intensity, cpu.intensity):.2f} | "
                         f"{(gpu.side == cpu.side).mean() * 100:.3f} % | {diff} |")
            print(f"| {proj} | {name} | {med:.1f} | {min(tot):.1f} | "
                  f"{statistics.median(ker):.1f} | {1e3 / med:.1f} {extra}")
    fly(quick)


def fly(quick):
    """Issue 32's fly-through on each device (bench_terrain.py's speed table)."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
    from reference import fractal
    n = 1025 if quick else 4097
    size = (320, 180) if quick else (1280, 720)
    hf = fc.HeightField(fractal(n, 2.4, seed=3) * 40, u=(0, 4 * (n - 1)), v=(0, 4 * (n - 1)))
    print(f"\n| fly-through, {n}^2 DEM, {size[0]}x{size[1]} | device | engine | median ms | fps "
          "| PSNR vs cpu dB | sides agree |")
    print("|---|---|---|---|---|---|---|")
    for name, extra in (("point (antialias=False)", dict(antialias=False)),
                        ("area (antialias='area')", dict(antialias="area"))):
        frames = [dict(fc.fly(hf, (2000.0 + 40 * k, 1000.0), heading=30, pitch=-10, fov=60,
                              size=size, above=300), **extra) for k in range(8)]
        last = {}
        for device in ("cpu", "cuda"):
            fc.render(hf, device=device, **frames[0])          # (compiles; the copies)
            ts = []
            for kw in frames[1:]:
                t = time.perf_counter()
                r = fc.render(hf, device=device, **kw)
                ts.append((time.perf_counter() - t) * 1e3)
            last[device] = r
            med = statistics.median(ts)
            extra_cols = "| |"
            if device == "cuda":
                a, b = last["cpu"], r
                extra_cols = (f"| {psnr(b.intensity, a.intensity):.2f} | "
                              f"{(a.side == b.side).mean() * 100:.3f} % |")
            print(f"| {name} | {device} | {r.stats['geometry']} | {med:.1f} | {1e3 / med:.1f} "
                  f"{extra_cols}", flush=True)


if __name__ == "__main__":
    main()
