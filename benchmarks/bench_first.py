"""The first picture of a fresh install (issue 33): seconds until a new process with
an empty Numba cache has its first 1920x1080 picture.

1. drafts on (the default): the first pictures are the draft pass's (numpy, no
   compile) while the warm-up process compiles the kernels into the cache;
2. the warm-up's own time, until the cache holds the kernels;
3. a later process with that cache: its first picture loads the kernels;
4. drafts off (FLOATCOL_DRAFT=0): the first picture waits for its kernels to compile
   in the process (what every fresh install did before);

and the same for fc.terrain's default picture of matplotlib's sample DEM (area-sampled
and smooth-shaded) and then a fly camera's view of it (the level-of-detail engine):
kernels the warm-up compiles besides the default picture's, the terrain's first.

    python benchmarks/bench_first.py
    python benchmarks/bench_first.py --compile   # where the compile's time goes
    python benchmarks/bench_first.py --shadows   # a first picture with shadows
    python benchmarks/bench_first.py --lines     # a first line drawing
    python benchmarks/bench_first.py --scenes    # objects, several surfaces, ...

``--shadows`` instead times a first picture with shadows (1920x1080, the sun at 120/15)
and then one with soft shadows (a light of 1 degree), drafted (passes/draft_shadow.py)
while the warm-up compiles the column pass's and the shadows' kernels. ``--lines`` times
a line drawing (method="horizon", passes/draft_horizon.py) and then plot_wireframe's
hidden-line drawing (fill=False), both drafted while the column pass's kernels compile.
``--scenes`` times the first picture of each of SCENES (objects with shadows or
translucency, several translucent or shadowed surfaces, a translucent surface's colour
field and lines, a perspective view from straight above) with drafts on and off.

``--compile`` instead compiles with an empty cache, in a process of its own on one
core, the default picture's kernels and then every kernel (warmup.warm_all), as the
test suite compiles them (NUMBA_BOUNDSCHECK=1, NUMBA_OPT=1; ``--plain`` as users'
installs do), and prints the seconds of each and the jitted functions whose own compile
took longest: Numba's compile events, each one's time less the compiles nested in it
(a function's own typing, and the optimisation and code generation of its library,
which holds the code of everything it calls).
"""
import os
import shutil
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

SHADOW_SCRIPT = SCRIPT.replace(
    'size=(1920, 1080))', 'size=(1920, 1080), lightsource=(120, 15), shadows=True)').replace(
    'projection="perspective", **kw', 'light_radius=1.0, **kw')

LINES_SCRIPT = SCRIPT.replace(
    'a = fc.render("3*sin(u*cos(v))", **kw)',
    'a = fc.render("3*sin(u*cos(v))", method="horizon", **kw)').replace(
    'projection="perspective", **kw', 'projection="perspective", wireframe=40, fill=False, **kw')

#: --scenes: a fresh install's first picture of each (1920x1080), its code after SCENE_HEAD
SCENE_HEAD = """
import sys, time
import numpy as np
import floatcol as fc
from floatcol import warmup
x = np.linspace(0, 6, 200)
dem = fc.HeightField(np.add.outer(np.sin(x), np.cos(x)) * 30 + np.add.outer(x, x) * 5)
objs = [fc.pole(40 + 20 * k, 60, 40) for k in range(5)] + [fc.box(100, 120, 20, 20, 25),
                                                          fc.tree(150, 80, 30)]
size = (1920, 1080)
t = time.perf_counter()
"""
SCENES = {
    "a height field with objects and shadows":
        "r = fc.render(dem, objects=objs, shadows=True, lightsource=(120, 30), size=size)",
    "a translucent height field with objects":
        "r = fc.render(dem, objects=objs, opacity=0.5, size=size)",
    "two translucent surfaces (render_many)":
        "r = fc.render_many([fc.Layer('sin(u)*cos(v)', ((-3, 3), (-3, 3)), "
        "fc.Material(opacity=0.5)), fc.Layer('0.5*cos(u*v)', ((-3, 3), (-3, 3)), "
        "fc.Material(opacity=0.5, cmap='plasma'))], size=size)",
    "a plate's shadow on a wave (render_many)":
        "r = fc.render_many([fc.Layer('sin(u)*cos(v)', ((-3, 3), (-3, 3))), "
        "fc.Layer('1.5 + 0*u', ((-1, 1), (-1.5, 1.5)))], shadows=True, "
        "lightsource=(300, 40), size=size)",
    "translucent, a colour field and a wireframe":
        "r = fc.render('sin(u)*cos(v)', (-3, 3), (-3, 3), opacity=0.5, wireframe=20, "
        "color='u*v', size=size)",
    "perspective from straight above (elev 90)":
        "r = fc.render('sin(u)*cos(v)', (-3, 3), (-3, 3), projection='perspective', "
        "elev=90, size=size)",
}
SCENE_TAIL = """
print(f"{time.perf_counter() - t:.2f} {r.stats['engine']}")
lock = warmup._lock_path()
pid = open(lock).read().strip() if lock and __import__("os").path.exists(lock) else "0"
print(pid or 0)
"""


def scenes_main():
    """--scenes: each scene's first picture after a fresh install, drafts on (the
    warm-up it starts stopped before the next scene) and off."""
    import signal
    print(f"{os.cpu_count()} cpus; a fresh install's first picture, 1920x1080\n")
    print("| scene | drafts on s | engine | drafts off s | engine |\n|---|---|---|---|---|")
    for name, code in SCENES.items():
        out = []
        for drafts in (True, False):
            with tempfile.TemporaryDirectory() as cache:
                env = dict(os.environ, NUMBA_CACHE_DIR=cache,
                           FLOATCOL_DRAFT="1" if drafts else "0")
                got = subprocess.run([sys.executable, "-c", SCENE_HEAD + code + SCENE_TAIL],
                                     env=env, check=True, capture_output=True,
                                     text=True).stdout.split()
                sec, engine, pid = float(got[-3]), got[-2], int(got[-1])
                if pid and alive(pid):          # (the warm-up: not beside the next scene)
                    os.kill(pid, signal.SIGTERM)
                    while alive(pid):
                        time.sleep(0.2)
                out.append((sec, engine))
        print(f"| {name} | {out[0][0]:.2f} | {out[0][1]} | {out[1][0]:.2f} | {out[1][1]} |",
              flush=True)


TERRAIN_SCRIPT = """
import os, time
t0 = time.perf_counter()
import floatcol as fc
from floatcol import warmup
from matplotlib.cbook import get_sample_data
t1 = time.perf_counter()
dem = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)
r = fc.terrain(dem).draw()
t2 = time.perf_counter()
f = fc.terrain(dem, fly=dict(position=(15000, 2500), above=900)).draw()
t3 = time.perf_counter()
lock = warmup._lock_path()
pid = open(lock).read().strip() if lock and os.path.exists(lock) else "0"
print(f"{t1 - t0:.2f} {t2 - t1:.2f} {r.stats['engine']} {t3 - t2:.2f} {f.stats['engine']} "
      f"{pid or 0}")
"""


def run_terrain(cache, drafts=True):
    """(import s, first picture s, engine, then a fly camera's s, engine, warm-up pid)
    of fc.terrain's default picture (area-sampled, smooth-shaded) and a fly view in a
    new process."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, FLOATCOL_DRAFT="1" if drafts else "0")
    out = subprocess.run([sys.executable, "-c", TERRAIN_SCRIPT], env=env, check=True,
                         capture_output=True, text=True).stdout.split()
    imp, first, engine, fly, f_engine, pid = out[-6:]
    return float(imp), float(first), engine, float(fly), f_engine, int(pid)


def run(cache, drafts=True, script=SCRIPT):
    env = dict(os.environ, NUMBA_CACHE_DIR=cache, FLOATCOL_DRAFT="1" if drafts else "0")
    t = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", script], env=env, check=True,
                         capture_output=True, text=True).stdout.split()
    wall = time.perf_counter() - t
    imp, first, e1, second, e2, pid = out[-6:]
    return float(imp), float(first), e1, float(second), e2, int(pid), wall


COMPILE_SCRIPT = """
import collections, sys, time
from numba.core import event
marks = []

class Listener(event.Listener):
    def on_start(self, e):
        marks.append((0, e.data["dispatcher"], time.perf_counter()))

    def on_end(self, e):
        marks.append((1, e.data["dispatcher"], time.perf_counter()))

event.register("numba:compile", Listener())
import floatcol as fc
from floatcol.warmup import warm_all_steps
t0 = time.perf_counter()
fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(64, 48)).intensity
t1 = time.perf_counter()
for step in warm_all_steps():
    step()
t2 = time.perf_counter()
own = collections.Counter()
count = collections.Counter()
stack = []
for end, d, t in marks:
    name = d.py_func.__module__.replace("floatcol.kernels.", "") + "." + d.py_func.__name__
    if not end:
        stack.append([t, 0.0])
        continue
    start, nested = stack.pop()
    own[name] += t - start - nested
    count[name] += 1
    if stack:
        stack[-1][1] += t - start
print(f"{t1 - t0:.1f} {t2 - t0:.1f}")
for name, sec in own.most_common(int(sys.argv[1])):
    print(f"{sec:.1f} {count[name]} {name}")
"""


def compile_times(plain, top=12):
    """(default picture s, every kernel s, [(own s, signatures, function)]) of a process
    with an empty cache."""
    env = dict(os.environ, FLOATCOL_DRAFT="0", OMP_WAIT_POLICY="PASSIVE")
    if not plain:
        env.update(NUMBA_BOUNDSCHECK="1", NUMBA_OPT="1")
    with tempfile.TemporaryDirectory() as cache:
        env["NUMBA_CACHE_DIR"] = cache
        pin = ["taskset", "-c", "0"] if shutil.which("taskset") else []
        out = subprocess.run(pin + [sys.executable, "-c", COMPILE_SCRIPT, str(top)], env=env,
                             check=True, capture_output=True, text=True).stdout.splitlines()
    first, every = (float(x) for x in out[0].split())
    return first, every, [line.split(maxsplit=2) for line in out[1:]]


def compile_main(plain):
    first, every, rows = compile_times(plain)
    how = "plain" if plain else "bounds-checked, NUMBA_OPT=1 (the suite's)"
    print(f"Empty cache, one core, {how}: the default picture's kernels {first:.1f} s, "
          f"every kernel (warm_all) {every:.1f} s\n")
    print("| own compile s | signatures | function |\n|---|---|---|")
    for sec, n, name in rows:
        print(f"| {float(sec):.1f} | {n} | {name} |")


def wait_for(cache, pid, kinds, t_start):
    """([seconds until the kernels of each geometry pass of ``kinds`` are in the cache
    (warmup.kernels_ready, smooth-shaded but for "column")], seconds until the warm-up
    process ``pid`` ends), from t_start."""
    checks = {k: [sys.executable, "-c", "from floatcol import warmup; "
                  f"print(warmup.kernels_ready({k!r}, {k != 'column'}))"] for k in kinds}
    own = {}
    while pid and alive(pid):
        for k, check in checks.items():
            if k not in own and subprocess.run(
                    check, env=dict(os.environ, NUMBA_CACHE_DIR=cache), capture_output=True,
                    text=True).stdout.strip() == "True":
                own[k] = time.perf_counter() - t_start
        time.sleep(0.5)
    done = time.perf_counter() - t_start
    return [own.get(k, done) for k in kinds], done


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
        (own,), warm = wait_for(cache, pid, ["column"], t_start)
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
    print(f"\nThe warm-up process had the kernels in the cache {own:.0f} s after the fresh "
          f"process started (its warm-up ended {warm:.0f} s after: a terrain's and a fly "
          "camera's kernels, then every option's at a lower priority).")
    # fc.terrain's default picture (area-sampled, smooth-shaded) and a fly view: other
    # kernels, which the warm-up compiles besides the default picture's
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        t_start = time.perf_counter()
        imp, first, engine, fly, f_engine, pid = run_terrain(cache)
        rows.append(("fresh install, drafts on", imp, first, engine, fly, f_engine))
        (own, own_fly), warm = wait_for(cache, pid, ["area", "lod"], t_start)
        rows.append(("next process, after the warm-up",) + run_terrain(cache)[:5])
    with tempfile.TemporaryDirectory() as cache:
        rows.append(("fresh install, drafts off",) + run_terrain(cache, drafts=False)[:5])
    print("\nfc.terrain(matplotlib's jacksboro_fault_dem.npz): its default picture, "
          "1000x600, then a fly camera's\n")
    print("| process | import s | first picture s | engine | then a fly view s | engine |")
    print("|---|---|---|---|---|---|")
    for name, imp, first, engine, fly, f_engine in rows:
        print(f"| {name} | {imp:.2f} | {first:.2f} | {engine} | {fly:.2f} | {f_engine} |")
    print(f"\nThe warm-up process (the terrain's kernels first) had them in the cache "
          f"{own:.0f} s after the fresh process started, a fly camera's {own_fly:.0f} s "
          f"after; it ended {warm:.0f} s after (every option's kernels too).")


#: the options' first pictures: (script, the scene, its first picture, its second, what
#: the warm-up compiles first)
OPTIONS = {
    "--shadows": (SHADOW_SCRIPT, "the sun at 120/15, shadows=True", "(shadows)",
                  "then soft shadows s", "the shadows' kernels after the column pass's"),
    "--lines": (LINES_SCRIPT, "line drawings", "(method='horizon')",
                "then plot_wireframe's (perspective, wireframe=40, fill=False) s",
                "the column pass's kernels first"),
}


def options_main(option):
    """--shadows: a first picture with shadows, then one with soft shadows; --lines: a
    line drawing, then a hidden-line wireframe."""
    script, scene, first_name, second_name, order = OPTIONS[option]
    rows = []
    with tempfile.TemporaryDirectory() as cache:
        t_start = time.perf_counter()
        out = run(cache, script=script)
        rows.append(("fresh install, drafts on",) + out[:5])
        _, warm = wait_for(cache, out[5], [], t_start)
        rows.append(("next process, after the warm-up",) + run(cache, script=script)[:5])
    with tempfile.TemporaryDirectory() as cache:
        rows.append(("fresh install, drafts off",) + run(cache, drafts=False, script=script)[:5])
    print(f"{os.cpu_count()} cpus; 3 sin(u cos v), 1920x1080, {scene}\n")
    print(f"| process | import s | first picture s {first_name} | engine | {second_name} | "
          "engine |")
    print("|---|---|---|---|---|---|")
    for name, imp, first, e1, second, e2 in rows:
        print(f"| {name} | {imp:.2f} | {first:.2f} | {e1} | {second:.2f} | {e2} |")
    print(f"\nThe warm-up process ({order}) ended {warm:.0f} s after the fresh process "
          "started.")


if __name__ == "__main__":
    chosen = [a for a in sys.argv[1:] if a in OPTIONS]
    if chosen:
        options_main(chosen[0])
    elif "--scenes" in sys.argv[1:]:
        scenes_main()
    elif "--compile" in sys.argv[1:]:
        compile_main("--plain" in sys.argv[1:])
    else:
        main()
