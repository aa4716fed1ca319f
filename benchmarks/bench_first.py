"""The first picture of a fresh install (issue 33): seconds until a new process with
an empty Numba cache has its first 1920x1080 picture.

1. drafts on (the default): the first pictures are the draft pass's (numpy, no
   compile) while the warm-up process compiles the kernels into the cache;
2. the warm-up's own time, until the cache holds the kernels;
3. a later process with that cache: its first picture loads the kernels;
4. drafts off (FLOATCOL_DRAFT=0): the first picture waits for its kernels to compile
   in the process (what every fresh install did before).

    python benchmarks/bench_first.py
"""
import os
import subprocess
import sys
import tempfile
import time

SCRIPT = """
import sys, time
t0 = time.perf_counter()
import floatcol as fc
from floatcol import warmup
t1 = time.perf_counter()
kw = dict(u=(-5, 5), v=(-5, 5), size=(1920, 1080))
a = fc.render("3*sin(u*cos(v))", **kw)
t2 = time.perf_counter()
b = fc.render("3*sin(u*cos(v))", projection="perspective", **kw)
t3 = time.perf_counter()
lock = warmup._lock_path()
pid = open(lock).read().strip() if lock and __import__("os").path.exists(lock) else "0"
print(f"{t1 - t0:.2f} {t2 - t1:.2f} {a.stats['engine']} {t3 - t2:.2f} {b.stats['engine']} "
      f"{pid or 0}")
"""


def run(cache, drafts=True):
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, FLOATCOL_DRAFT="1" if drafts else "0")
    t = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", SCRIPT], env=env, check=True,
                         capture_output=True, text=True).stdout.split()
    wall = time.perf_counter() - t
    imp, first, e1, second, e2, pid = out[-6:]
    return float(imp), float(first), e1, float(second), e2, int(pid), wall


def alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


def main():
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        t_start = time.perf_counter()
        imp, first, e1, second, e2, pid, _ = run(cache)
        rows.append(("fresh install, drafts on", imp, first, e1, second, e2))
        while pid and alive(pid):
            time.sleep(0.5)
        warm = time.perf_counter() - t_start
        imp, first, e1, second, e2, _, _ = run(cache)
        rows.append(("next process, kernels cached", imp, first, e1, second, e2))
    with tempfile.TemporaryDirectory() as cache:
        imp, first, e1, second, e2, _, _ = run(cache, drafts=False)
        rows.append(("fresh install, drafts off", imp, first, e1, second, e2))
    print(f"{os.cpu_count()} cpus; 3 sin(u cos v), 1920x1080, default quality\n")
    print("| process | import s | first picture s (orthographic) | engine | "
          "then perspective s | engine |")
    print("|---|---|---|---|---|---|")
    for name, imp, first, e1, second, e2 in rows:
        print(f"| {name} | {imp:.2f} | {first:.2f} | {e1} | {second:.2f} | {e2} |")
    print(f"\nThe warm-up process had the kernels in the cache {warm:.0f} s after the fresh "
          "process started.")


if __name__ == "__main__":
    main()
