"""Frames and posters on Dask (floatcol/cluster.py, issue 34).

    python benchmarks/bench_cluster.py

Prints frames/s of a 60-frame animation rendered here (numba's threads on every core)
and on LocalClusters of 1 and 2 worker processes (one thread each, numba's too), and the time of a poster drawn whole, in bands
here, and in bands on 2 workers. Each cluster is warmed up first (its workers compile
the kernels from the disk cache and the expression once)."""
import os
import time

os.environ.setdefault("FLOATCOL_DRAFT", "0")

import numpy as np  # noqa: E402

import floatcol as fc  # noqa: E402

CLIP = dict(t=(0, 6.28), frames=60, size=(640, 480), progress=False)
EXPR = "sin(x*y + t) * exp(-(x*x + y*y)/8)"
POSTER = dict(size=(4096, 4096), lightsource=(315, 30), shadows=True)


#: the workers' environment: numba's kernels on one thread (the workers are the
#: parallelism), the kernels' pictures (not a fresh process's drafts)
ENV = {"NUMBA_NUM_THREADS": "1", "FLOATCOL_DRAFT": "0"}


def clip(client=None):
    fc.animate(EXPR, ("x", -4, 4), ("y", -4, 4), client=client, **dict(CLIP, frames=4))
    t = time.perf_counter()
    a = fc.animate(EXPR, ("x", -4, 4), ("y", -4, 4), client=client, **CLIP)
    return time.perf_counter() - t, a


def poster(**kw):
    t = time.perf_counter()
    r = fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), **dict(POSTER, **kw))
    return time.perf_counter() - t, r


def main():
    from distributed import Client, LocalCluster
    print(f"| 60 frames {CLIP['size'][0]}x{CLIP['size'][1]} | seconds | frames/s | same frames |")
    print("|---|---|---|---|")
    here, ref = clip()
    print(f"| here (numba's threads: {os.cpu_count()}) | {here:.2f} | {60 / here:.1f} | |")
    for n in (1, 2):
        with LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                          dashboard_address=None, env=ENV) as cl, Client(cl) as c:
            secs, a = clip(c)
            same = all(np.array_equal(np.asarray(x), np.asarray(y))
                       for x, y in zip(ref.frames, a.frames))
            print(f"| {n} worker{'s' if n > 1 else ''} | {secs:.2f} | {60 / secs:.1f} | {same} |",
                  flush=True)
    print(f"\n| poster {POSTER['size'][0]}x{POSTER['size'][1]}, shadows | seconds | bands | "
          "same picture |")
    print("|---|---|---|---|")
    poster(size=(256, 256))                                   # warm up
    whole_s, whole = poster()
    print(f"| whole, here | {whole_s:.2f} | 1 | |")
    tiled_s, tiled = poster(tiles=8)
    print(f"| 8 bands, here | {tiled_s:.2f} | 8 | {np.array_equal(whole.rgba, tiled.rgba)} |")
    lo, hi = whole.stats["w_limits"]
    fixed_s, fixed = poster(tiles=8, vmin=lo, vmax=hi)
    print(f"| 8 bands, here, vmin/vmax given (no band drawn twice) | {fixed_s:.2f} | 8 | "
          f"{np.array_equal(whole.rgba, fixed.rgba)} |")
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None, env=ENV) as cl, Client(cl) as c:
        fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(256, 256), client=c)
        secs, r = poster(tiles=8, client=c)
        print(f"| 8 bands, 2 workers | {secs:.2f} | 8 | {np.array_equal(whole.rgba, r.rgba)} |")


if __name__ == "__main__":
    main()
