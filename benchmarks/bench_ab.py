"""Two versions of floatcol in one process, their renders alternating: the way to
compare speeds on a machine whose speed drifts (a shared virtual machine's does, by
up to 1.5x within minutes, so runs made apart cannot be compared).

    python benchmarks/bench_ab.py REV [REPEATS]

REV is a git revision (HEAD, a commit, a tag): its floatcol/ is exported to a
temporary folder as the package ``floatcol_ab`` (compiled there on first use, about
a minute) and rendered against the working tree's floatcol, the same scenes, best
and median of REPEATS (default 11) after a warm-up. Pictures of the two are
compared too (``same`` when rgba, side and w_limits are bit-identical).
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))
SCENES = [((1920, 1080), "orthographic"), ((1920, 1080), "perspective"),
          ((1024, 768), "orthographic"), ((1024, 768), "perspective")]


def export(rev):
    """The folder holding REV's floatcol as the package floatcol_ab."""
    root = subprocess.run(["git", "rev-parse", "--show-toplevel"], capture_output=True,
                          text=True, check=True).stdout.strip()
    sha = subprocess.run(["git", "rev-parse", "--short", rev], capture_output=True, text=True,
                         check=True, cwd=root).stdout.strip()
    folder = os.path.join(tempfile.gettempdir(), f"floatcol_ab_{sha}")
    if not os.path.isdir(os.path.join(folder, "floatcol_ab")):
        os.makedirs(folder, exist_ok=True)
        archive = subprocess.run(["git", "archive", rev, "floatcol"], capture_output=True,
                                 check=True, cwd=root).stdout
        subprocess.run(["tar", "-x", "-C", folder, "--transform", "s/^floatcol/floatcol_ab/"],
                       input=archive, check=True)
    return folder, sha


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    rev = sys.argv[1]
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 11
    folder, sha = export(rev)
    sys.path.insert(0, folder)
    import floatcol as now
    import floatcol_ab as then
    print(f"| scene | {sha} best / median ms | working tree best / median ms | ratio of bests "
          "| pictures |")
    print("|---|---|---|---|---|")
    for size, proj in SCENES:
        ts = {"then": [], "now": []}
        pics = {}
        for rep in range(repeats + 1):
            for name, fc in (("then", then), ("now", now)):
                t = time.perf_counter()
                r = fc.render(EXPR, size=size, projection=proj, **DOM)
                ts[name].append((time.perf_counter() - t) * 1e3)
                if rep == 0:
                    pics[name] = (r.rgba.copy(), r.side.copy(), r.stats.get("w_limits"))
                del r
        a, b = (ts[k][1:] for k in ("then", "now"))
        same = all(np.array_equal(x, y) if isinstance(x, np.ndarray) else x == y
                   for x, y in zip(pics["then"], pics["now"]))
        print(f"| {size[0]}x{size[1]} {proj} | {min(a):.1f} / {statistics.median(a):.1f} | "
              f"{min(b):.1f} / {statistics.median(b):.1f} | {min(a) / min(b):.3f} | "
              f"{'same' if same else 'differ'} |", flush=True)


if __name__ == "__main__":
    main()
