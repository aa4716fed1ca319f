"""device="cuda" against device="cpu" (issue 34): one prepared script for a machine
with an NVIDIA GPU. Prints, after a warm-up (the GPU kernel's compile, about 2
minutes on 2 cores, timed too):

- 1920x1080 of 3 sin(u cos v) at default quality, orthographic and perspective:
  median and best ms of the whole render and of the column pass (stats
  "kernel_seconds") on each device, and fps;
- the GPU's pictures against the CPU kernel's: PSNR of the intensities (background
  0), side agreement, the largest rgba difference.

Without a GPU (or without numba-cuda) it says so and prints the kernel's compile to
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
        try:
            text, seconds = ptx(fc.as_surface(EXPR))
        except Exception as exc:                  # no NVVM either
            print(f"and no CUDA toolkit to compile the kernel to PTX: {exc}")
            return
        print(f"the column kernel compiles to PTX for sm_90 in {seconds:.1f} s "
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


if __name__ == "__main__":
    main()
