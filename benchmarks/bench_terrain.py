"""Terrain (issue 32): Cohen-Or's tables (1997) reproduced with floatcol, Szenberg's
Table 1 (1997), and the fly-through's speed.

1. Flicker, Cohen-Or's Table 6: pixels whose grey level changes by 0, 1, ... 5 and
   6-60 levels between frames of a slow motion. Here a slow orbit (0.02 deg a frame,
   the picture moves by at most 0.06 px a frame) over a dense fractal DEM that is not
   in the tests (1025^2 heights, 1000 x 1000 units, seed 11), 320x240 in perspective:
   point sampling (antialias=False), floatcol's default coverage antialiasing,
   supersampling 4 (2 x 2) and 16 (4 x 4, point-sampled pictures at 2x and 4x the
   size, averaged), and antialias="area".
2. Coverage, Cohen-Or's Tables 2-4: his set-up (field of view 10 deg, 400 px, pitch
   40, 20 and 5 deg, the eye as high as puts the first hit's footprint at one voxel
   wide) over a 4097^2 fractal DEM of unit cells (beta 3, std 15). V: the cells (voxels) seen from one
   pixel column (its 400 pixels cast VREF = 80 rays each); M: the cells that point
   sampling (1 ray a pixel) and supersampling N (N rays a pixel, one column of N x
   400 rows) sample; P the pixels that show terrain, NP the rays cast. Area sampling
   weighs every visible piece of the column (kernels/area.py), so its M is V.
3. Guedes' Table 1: his variants (kernels/voxel.py) timed, and how far each puts
   the terrain from where the exact ray finds it; floatcol's exact perspective, its
   level-of-detail engine and its ray march too.
4. Szenberg's Table 1: the time of each step of a terrain with objects (640x360 fly
   view over matplotlib's Jacksboro DEM, 43 objects): the terrain, its window depth
   (eq. 7), the objects (z-buffer).
5. Speed: a fly-through over a 4097^2 DEM at 1280x720 (the issue asks 30 fps point
   sampled, 10 fps area sampled): fc.fly's engines, the level-of-detail engine
   (sampling="lod", passes/lod.py; its antialiased views) and the ray march
   (sampling="march", passes/march.py; its point-sampled ones), and the exact column
   pass (sampling="adaptive"); over the benchmark's rough fractal DEM and a smoother
   one.

    python benchmarks/bench_terrain.py [--quick] [--only=flicker,coverage,guedes,szenberg,speed]
"""
import statistics
import sys
import time

import os

import numpy as np

os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
from reference import bilinear_surface, fractal as _fractal, raycast  # noqa: E402


def fractal(n, beta=2.4, seed=11):
    """The benchmark's DEMs: tests/reference.py's fractal, another seed by default."""
    return _fractal(n, beta, seed)


QUICK = "--quick" in sys.argv
#: rays a pixel that find the visible cells V (a picture is at most 32768 rows)
VREF = 80


def grey(rgba):
    return rgba[..., :3].astype(float) @ np.array([0.299, 0.587, 0.114])


def table6():
    n = 513 if QUICK else 1025
    hf = fc.HeightField(fractal(n) * 60, u=(0, 1000), v=(0, 1000))
    W, H = 320, 240
    frames = 6 if QUICK else 12
    base = fc.render(hf, size=(W, H), elev=25, azim=30, projection="perspective")
    cam = dict(elev=25, projection="perspective", center=base.view.center, d1=base.view.d1,
               d2=base.view.d2)
    rows = []
    paper = {"area": "AS 32183 14933 1725 362 99 46 52",
             "point": "PS 28903 11287 912 708 659 599 5432",
             "ss16": "SS16 23283 18346 4985 1721 630 232 203"}
    print(f"\n## Flicker (Cohen-Or Table 6): {n}^2 fractal DEM, {W}x{H}, {frames} frames, "
          "orbit 0.02 deg/frame\n")
    print("| method | 0 | 1 | 2 | 3 | 4 | 5 | 6-60 | >60 | 6-60 vs point | ms/frame |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    point = None
    for name, aa, ss in (("point", False, 1), ("default AA", True, 1), ("ss4", False, 2),
                         ("ss16", False, 4), ("area", "area", 1)):
        if QUICK and ss == 4:
            continue
        fc.render(hf, size=(W * ss, H * ss), azim=30, antialias=aa, scale=base.view.scale * ss,
                  **cam)                                  # (warm: compiled, pyramid built)
        imgs = []
        t = time.perf_counter()
        for f in range(frames):
            r = fc.render(hf, size=(W * ss, H * ss), azim=30 + 0.02 * f, antialias=aa,
                          scale=base.view.scale * ss, **cam)
            g = grey(r.rgba)
            imgs.append(g.reshape(H, ss, W, ss).mean(axis=(1, 3)) if ss > 1 else g)
        ms = (time.perf_counter() - t) / frames * 1e3
        d = np.round(np.abs(np.diff(np.array(imgs), axis=0)))
        hist = [int((d == v).sum()) for v in range(6)]
        hist += [int(((d >= 6) & (d <= 60)).sum()), int((d > 60).sum())]
        if point is None:
            point = hist[6]
        rows.append((name, hist))
        print(f"| {name} | " + " | ".join(str(h) for h in hist)
              + f" | {hist[6] / point:.3f} | {ms:.0f} |", flush=True)
    print("\nCohen-Or's Table 6 (one column over 400 frames, 0.5 m a frame): " + "; ".join(
        paper.values()) + " (bins 0, 1, 2, 3, 4, 5, 6-60): AS/PS 6-60 = 0.0096, SS16/PS "
        "= 0.037")
    return rows


def coverage_tables():
    n = 2049 if QUICK else 4097
    z = fractal(n, beta=3.0, seed=5) * 15
    hf = fc.HeightField(z, u=(0, n - 1), v=(0, n - 1))
    fov, size = 10.0, 400
    first = 0.5 * size / np.tan(np.radians(fov / 2))       # px per unit at distance 1
    rates = (1, 2, 4, 8, 16, 32)
    paper = {40: "M 847 400 751 844 847 847 847; M/V 1 0.47 0.88 0.99 1 1 1",
             20: "M 1347 400 799 1151 1244 1272 1283; M/V 1 0.3 0.59 0.85 0.92 0.94 0.94",
             5: "M 4271 328 654 1298 2110 2630 2900; M/V 1 0.07 0.15 0.3 0.49 0.61 0.67"}
    print(f"\n## Coverage (Cohen-Or Tables 2-4): {n}^2 fractal DEM of unit cells, fov "
          f"{fov:g} deg, {size} px, one column\n")
    for pitch in (40, 20, 5):
        # the eye's height: the first hit (the lowest ray, pitch + fov/2 down) a
        # footprint of one cell wide
        down = np.radians(pitch + fov / 2)
        dist = first                                         # a pixel = a unit there
        height = dist * np.sin(down)
        ground = float(hf.evaluate(np.array([n / 2]), np.array([2.0]))[0])
        eye = (n / 2, 2.0, ground + height)
        cells = {}
        P = 0
        for N in rates + (VREF,):
            kw = fc.fly(hf, eye, heading=0, pitch=-pitch, fov=fov, size=(size, size),
                        near=1.0)
            kw["size"] = (1, size * N)
            kw["scale"] *= N
            kw["step"] = 0.25                   # (uniform planes, a quarter cell apart)
            kw["sampling"] = "uniform"
            r = fc.render(hf, antialias=False, **kw)
            seen = r.side[:, 0] != 0
            u, v = r.u[seen, 0], r.v[seen, 0]
            ids = set(zip(np.floor(u).astype(int), np.floor(v).astype(int)))
            cells[N] = len(ids)
            if N == 1:
                P = int(seen.sum())
        V = cells[VREF]
        print(f"pitch {pitch} deg: eye {height:.0f} above the ground, P = {P} pixels, "
              f"V = {V} visible cells")
        print("\n| | AS | PS | " + " | ".join(f"SS{N}" for N in rates[1:]) + " |")
        print("|---|" + "---|" * (len(rates) + 1))
        print("| M | " + f"{V} | " + " | ".join(str(cells[N]) for N in rates) + " |")
        print("| NP | - | - | " + " | ".join(str(N * P) for N in rates[1:]) + " |")
        print("| M/V | 1 | " + " | ".join(f"{cells[N] / V:.2f}" for N in rates) + " |")
        print(f"\nCohen-Or (AS PS SS2 SS4 SS8 SS16 SS32): {paper[pitch]}\n", flush=True)


def guedes_table():
    """Guedes' Table 1: ms per frame of each variant (640x360), and where each puts
    the terrain: per pixel, the distance (in cells) from the ground point it shows to
    the exact ray's hit; his variants against the brute-force ray caster of the same
    voxel model, floatcol against tests/reference.py's ray caster on the bilinear
    surface (320x180)."""
    from floatcol.terrain import guedes
    from matplotlib.cbook import get_sample_data
    hf = fc.read_dem(get_sample_data("jacksboro_fault_dem.npz", asfileobj=False), vert_exag=2)
    (ua, ub), (va, vb) = hf.default_domain
    cell = (ub - ua) / (hf.hf.shape[1] - 1)
    pos, cam = (15000.0, 2500.0), dict(heading=15, pitch=-30, fov=55, above=1500)
    paper = {"standard": "107 ms, 9.3 fps", "naive": "123, 8.1", "uncorrected": "134, 7.5",
             "corrected": "277, 3.6", "brute": "4697, 0.21"}
    print("\n## Guedes' Table 1: the Jacksboro DEM (x2), 640x360 to time, 320x180 to place; "
          "pitch -30 deg, fov 55 deg\n")
    print("| variant | ms/frame | fps | cells off: median | 90 % | > 1 cell | Guedes (Pentium 133) |")
    print("|---|---|---|---|---|---|---|")
    small = (320, 180)
    _, exact, _ = guedes(hf, pos, size=small, variant="brute", **cam)
    for v in ("standard", "naive", "uncorrected", "corrected", "brute"):
        guedes(hf, pos, size=(640, 360), variant=v, **cam)
        ms = statistics.median(guedes(hf, pos, size=(640, 360), variant=v, **cam)[2]
                               for _ in range(3)) * 1e3
        _, uv, _ = guedes(hf, pos, size=small, variant=v, **cam)
        both = np.isfinite(uv[..., 0]) & np.isfinite(exact[..., 0])
        d = np.hypot(*(uv[both] - exact[both]).T) / cell
        print(f"| {v} | {ms:.0f} | {1e3 / ms:.1f} | {np.median(d):.2f} | "
              f"{np.percentile(d, 90):.2f} | {100 * (d > 1).mean():.1f} % | {paper[v]} |",
              flush=True)
    for name, sampling, extra in (("floatcol (exact, bilinear)", "adaptive", {}),
                                  ("floatcol (sampling='lod', fc.fly's antialiased)", "lod", {}),
                                  ("floatcol (sampling='march', fc.fly's point sampled)", "march",
                                   dict(antialias=False))):
        kw = dict(fc.fly(hf, pos, size=(640, 360), **cam), sampling=sampling, **extra)
        fc.render(hf, **kw)
        ts = []
        for _ in range(3):
            t = time.perf_counter()
            fc.render(hf, **kw)
            ts.append(time.perf_counter() - t)
        ms = statistics.median(ts) * 1e3
        kw = dict(fc.fly(hf, pos, size=small, **cam), sampling=sampling, **extra)
        r = fc.render(hf, **kw)
        ref = raycast(bilinear_surface(hf.hf, (ua, ub), (va, vb)), (ua, ub), (va, vb), small,
                      kw["elev"], kw["azim"], "perspective", kw["d1"], kw["d2"], kw["scale"],
                      center=kw["center"], steps=3000)
        both = (r.side != 0) & (ref.side != 0)
        d = np.hypot(r.u[both] - ref.u[both], r.v[both] - ref.v[both]) / cell
        print(f"| {name} | {ms:.0f} | {1e3 / ms:.1f} | {np.median(d):.3f} | "
              f"{np.percentile(d, 90):.3f} | {100 * (d > 1).mean():.1f} % | |", flush=True)


def szenberg():
    from matplotlib.cbook import get_sample_data
    hf = fc.read_dem(get_sample_data("jacksboro_fault_dem.npz", asfileobj=False), vert_exag=2)
    rng = np.random.default_rng(3)
    objs = [fc.tree(u, v, 400) for u, v in rng.uniform(12000, 18000, (40, 2))]
    objs += [fc.box(15500, 6000, 600, 300, 250, color="firebrick", heading=30),
             fc.pole(14000, 5000, 1200), fc.marker(16000, 8000, 300)]
    kw = fc.fly(hf, (15000, 2000), heading=20, pitch=-12, fov=60, size=(640, 360), above=600)
    opts = dict(cmap="gist_earth", lightsource=(315, 35), **kw)
    fc.render(hf, objects=objs, **opts)
    t_ter, t_all, t_wd = [], [], []
    for _ in range(3 if QUICK else 7):
        t = time.perf_counter()
        r = fc.render(hf, **opts)
        r.depth
        t_ter.append(time.perf_counter() - t)
        t = time.perf_counter()
        r.window_depth(10.0, 40000.0)
        t_wd.append(time.perf_counter() - t)
        t = time.perf_counter()
        fc.render(hf, objects=objs, **opts)
        t_all.append(time.perf_counter() - t)
    ter, wd, both = (statistics.median(x) * 1e3 for x in (t_ter, t_wd, t_all))
    print("\n## Szenberg's Table 1: 640x360 fly view of the Jacksboro DEM with 43 objects\n")
    print("| step | ms | % |\n|---|---|---|")
    total = both + wd
    for name, ms in (("terrain (floating column) + depth", ter), ("window depth (eq. 7)", wd),
                     ("objects (z-buffer, 40 trees, a box, a pole, a marker)", both - ter)):
        print(f"| {name} | {ms:.1f} | {100 * ms / total:.0f} |")
    print(f"| total | {total:.1f} | 100 |\n\nfps with objects {1e3 / total:.1f}, without "
          f"{1e3 / (ter + wd):.1f} (Szenberg on a Pentium 166: 4.6 and 14.1)")


def speed():
    n = 2049 if QUICK else 4097
    size = (1280, 720)
    print(f"\n## Fly-through speed: {n}^2 DEM, {size[0]}x{size[1]}\n")
    print("| DEM | engine | sampling | ms/frame | fps | evaluations |\n|---|---|---|---|---|---|")
    # the warm-up: every kernel timed below compiled (or loaded from the cache) on a
    # small DEM before the clock starts (a run on an empty cache took 8.5 s for its
    # first view and 572 ms a frame for the clip with shadows, their compiles included)
    small = fc.HeightField(fractal(65, 2.4, seed=1) * 40, u=(0, 256), v=(0, 256))
    few = dict(heading=30, pitch=-10, fov=60, size=(64, 36), above=300)
    for sampling in ("lod", "march", "adaptive"):
        for aa in (False, "area"):
            fc.render(small, **dict(fc.fly(small, (100.0, 50.0), **few), sampling=sampling,
                                    antialias=aa))
    for shadows in (False, True):
        fc.fly_through(small, [(100.0, 50.0), (120.0, 50.0)], frames=2, vert_exag=1,
                       progress=False, shadows=shadows, **few)
    # the benchmark's DEM (beta 2.4: a bed of needles, its median slope 1.6) and a
    # smoother one, more like a landscape (beta 3.4: median slope 0.1), where more of
    # the terrain is in view
    firsts = []
    for dem, beta in (("fractal, beta 2.4", 2.4), ("fractal, beta 3.4", 3.4)):
        hf = fc.HeightField(fractal(n, beta, seed=3) * 40, u=(0, 4 * (n - 1)),
                            v=(0, 4 * (n - 1)))
        # a new DEM's first view makes its pyramid and block maxima (kept with it)
        kw = fc.fly(hf, (2000.0, 1000.0), heading=30, pitch=-10, fov=60, size=size,
                    above=300)
        t = time.perf_counter()
        fc.render(hf, **kw, antialias="area")
        firsts.append((dem, (time.perf_counter() - t) * 1e3))
        for engine, sampling in (("level of detail (fc.fly's antialiased)", "lod"),
                                 ("ray march (fc.fly's point sampled)", "march"),
                                 ("exact column pass", "adaptive")):
            if sampling == "adaptive" and beta != 2.4:
                continue
            for name, extra in (("point (antialias=False)", dict(antialias=False)),
                                ("area (antialias='area')", dict(antialias="area"))):
                if sampling == "march" and extra["antialias"]:
                    continue                    # (antialiased: the lod engine's)
                ts = []
                frames = 8 if sampling != "adaptive" else (3 if QUICK else 5)
                for k in range(frames):
                    kw = fc.fly(hf, (2000.0 + 40 * k, 1000.0), heading=30, pitch=-10, fov=60,
                                size=size, above=300)
                    kw.update(extra, sampling=sampling)
                    t = time.perf_counter()
                    r = fc.render(hf, **kw)
                    ts.append(time.perf_counter() - t)
                ms = statistics.median(ts[1:]) * 1e3
                print(f"| {dem} | {engine} | {name} | {ms:.0f} | {1e3 / ms:.1f} | "
                      f"{r.stats['samples']} |", flush=True)
        # the same flight as one clip (fc.fly_through, its landscape defaults: area
        # sampled, smooth shading): a frame's time, the plot around each render included
        path = [(2000.0, 1000.0), (2000.0 + 40 * 7, 1000.0)]
        clip = dict(heading=30, pitch=-10, fov=60, size=size, above=300, vert_exag=1,
                    progress=False)
        fc.fly_through(hf, path, frames=2, **clip)
        anim = fc.fly_through(hf, path, frames=8, **clip)
        ms = anim.stats["seconds"] / 8 * 1e3
        print(f"| {dem} | a flight's clip (fc.fly_through) | area, smooth shading | {ms:.0f} | "
              f"{1e3 / ms:.1f} | {anim.stats['samples'] // 8} |", flush=True)
        if beta != 2.4:
            continue
        # with shadows: the clip keeps its shadow texture from frame to frame (the
        # texels capped, the same grid each frame); the same frames each with a texture
        # made afresh (passes/shadow.py forget), as without that
        from floatcol.passes import shadow
        anim = fc.fly_through(hf, path, frames=8, shadows=True, **clip)
        ms = anim.stats["seconds"] / 8 * 1e3
        ts = []
        for pos, head in zip(anim.stats["positions"], anim.stats["headings"]):
            shadow.forget()
            t = time.perf_counter()
            fc.terrain(hf, vert_exag=1, shadows=True, fly=dict(
                position=tuple(pos), heading=head, pitch=-10, fov=60, size=size)).draw()
            ts.append(time.perf_counter() - t)
        fresh = statistics.mean(ts) * 1e3
        print(f"| {dem} | a flight's clip, shadows (texture kept; made afresh: {fresh:.0f} ms) "
              f"| area, smooth shading | {ms:.0f} | {1e3 / ms:.1f} | "
              f"{anim.stats['samples'] // 8} |", flush=True)
    for dem, ms in firsts:
        print(f"\n{dem}: the first area-sampled fly view of the new DEM (its pyramid and "
              f"block maxima made): {ms:.0f} ms")


TABLES = {"flicker": table6, "coverage": coverage_tables, "guedes": guedes_table,
          "szenberg": szenberg, "speed": speed}

if __name__ == "__main__":
    only = [a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--only=")]
    names = only[0].split(",") if only else list(TABLES)
    unknown = [n for n in names if n not in TABLES]
    if unknown:
        sys.exit(f"--only takes {', '.join(TABLES)}; got {', '.join(unknown)}")
    for name in names:
        TABLES[name]()
