"""Fuzz floatcol's render with random expressions, ranges and options (issue 26).

    python benchmarks/fuzz.py [N] [SEED] [--terrain | --mesh]   (default 10000 cases, seed 26)

--terrain: height-field cases instead (tests/fuzzing.py terrain_case: DEMs with
holes, 16-bit, flat, huge or tiny heights, fly cameras anywhere, area sampling, lod,
shadows, objects on the terrain).
--mesh: matplotlib's plot_surface(X, Y, Z) on meshes of every kind instead
(tests/fuzzing.py mesh_case: even, uneven, polar, wound, a sphere's, scattered,
collinear, collapsed grids with NaN, infinite and huge values, in 2-D and 3-D Axes).

Each case runs in a worker process (tests/fuzzing.py): a segfault or a hang is
counted, the worker restarted. Prints the counts of each outcome, the first few
findings of each kind other than "ok" and "value", and the five slowest cases. Exit
status 1 if any case crashed, hung, raised anything but ValueError, leaked an internal
name, or raised an exception inside compiled code (printed there as "Exception
ignored").
"""
import collections
import os
import random
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))
import fuzzing  # noqa: E402


def main():
    args = [a for a in sys.argv[1:] if a not in ("--terrain", "--mesh")]
    make = fuzzing.terrain_case if "--terrain" in sys.argv[1:] else \
        fuzzing.mesh_case if "--mesh" in sys.argv[1:] else fuzzing.case
    n = int(args[0]) if len(args) > 0 else 10000
    seed = int(args[1]) if len(args) > 1 else 26
    rng = random.Random(seed)
    worker = fuzzing.Worker(timeout=60.0)
    counts = collections.Counter()
    findings = collections.defaultdict(list)
    slowest = []                        # (seconds, case number, case): the 5 slowest
    t0 = time.perf_counter()
    try:
        for i in range(n):
            c = make(rng)
            tc = time.perf_counter()
            res = worker.run(c)
            slowest = sorted(slowest + [(time.perf_counter() - tc, i, c)],
                             key=lambda x: -x[0])[:5]
            counts[res["outcome"]] += 1
            if res["outcome"] not in ("ok", "value") and len(findings[res["outcome"]]) < 5:
                findings[res["outcome"]].append((c, res["message"]))
                print(f"case {i}: {res['outcome']}: {res['message'][:200]}\n  {c}", flush=True)
            if (i + 1) % 500 == 0:
                print(f"{i + 1} cases, {time.perf_counter() - t0:.0f} s: {dict(counts)}",
                      flush=True)
    finally:
        worker.close()
    print(f"\n{n} cases (seed {seed}) in {time.perf_counter() - t0:.0f} s")
    print(f"{'outcome':<10}{'cases':>8}")
    for k in ("ok", "value", "other", "leak", "raised", "crash", "hang"):
        print(f"{k:<10}{counts[k]:>8}")
    # (a case's pictures are at most 160 x 120: seconds here are a near-hang to look at)
    print("\nslowest cases (s, a worker's start and compiles included):")
    for sec, i, c in slowest:
        print(f"  {sec:6.2f}  case {i}: {str(c)[:300]}")
    bad = sum(counts[k] for k in ("other", "leak", "raised", "crash", "hang"))
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
