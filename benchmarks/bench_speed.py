"""floatcol against what users use today, in one run on the same machine.

floatcol at 1920x1080 and 1024x768, default quality (corrections, antialiasing), in
both projections; matplotlib ``plot_surface`` of a 400x400 mesh saved to PNG at
1024x768; PyVista off-screen (optional: ``pip install -e .[bench]``) of the same mesh
at 1024x768 and 1920x1080 in both projections (its parallel projection against
floatcol's orthographic), screenshot included (VTK renders with whatever OpenGL the
machine has: on a machine without a GPU, Mesa's software llvmpipe). Every tool is
warmed up first (Numba compilation, VTK context); times are medians (floatcol's best
too: a shared virtual machine's speed drifts, compare ratios within one run). A
floatcol render's time is the picture's; its intensity and depth arrays are computed
when first read, and the rows "+ intensity and depth read" time that too.

Then where 1920x1080 perspective's time goes: the column, finishing and staircase
passes (each wrapped and timed, medians) at pixel_step 1, 2, 4 and 16, which shows
what no thinning of the planes can take away.

Then fidelity, the other half of the comparison: the three tools' pictures of the
same surface from the same orthographic camera, lit by the reference model (I =
|L.N|, light at the viewer; floatcol shading="lambert"), against the ray caster
(tests/reference.py) at 512x384: PSNR (background 0) and the share of pixels where
surface/background agree. matplotlib's camera is read off its axes (its orthographic
projection is an exact similarity of floatcol's: the fit's residual is printed) and
the others take it; matplotlib's quads get the reference model's shade at their
centres as facecolors (its own LightSource model differs), PyVista a headlight
without ambient or specular, flat and smooth (Gouraud) shaded.

    python benchmarks/bench_speed.py
    python benchmarks/bench_speed.py --thinning   # + the fidelity of thinned perspective planes
"""
import ctypes
import io
import math
import os
import statistics
import sys
import time

import numba
import numpy as np

os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts
import floatcol as fc

EXPR = "3*sin(u*cos(v))"
DOM = dict(u=(-5, 5), v=(-5, 5))
MESH = 400


def _times_ms(fn, repeat):
    ts = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        ts.append((time.perf_counter() - t) * 1e3)
    return ts


def _median_ms(fn, repeat):
    return statistics.median(_times_ms(fn, repeat))


def _mesh():
    u = np.linspace(-5, 5, MESH)
    U, V = np.meshgrid(u, u)
    return U, V, 3 * np.sin(U * np.cos(V))


def matplotlib_ms(size):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    U, V, W = _mesh()

    def once():
        fig = plt.figure(figsize=(size[0] / 100, size[1] / 100), dpi=100)
        ax = fig.add_subplot(projection="3d")
        ax.plot_surface(U, V, W, cmap="viridis", rstride=1, cstride=1, linewidth=0,
                        antialiased=False)
        ax.view_init(30, -110)
        fig.savefig(io.BytesIO(), format="png")
        plt.close(fig)
    once()
    return _median_ms(once, 3)


def pyvista_ms(size, parallel=False):
    """(new view, new mesh) median ms of PyVista at ``size``; ``parallel``: its
    parallel (orthographic) projection, as floatcol's default."""
    try:
        import pyvista as pv
    except ImportError:
        return None
    U, V, W = _mesh()
    grid = pv.StructuredGrid(U, V, W)
    grid["w"] = W.ravel(order="F")
    pl = pv.Plotter(off_screen=True, window_size=list(size))
    pl.add_mesh(grid, scalars="w", cmap="viridis", show_scalar_bar=False)
    if parallel:
        pl.enable_parallel_projection()
    pl.camera.elevation = 30
    pl.screenshot(return_img=True)                 # warm-up: context and upload

    def once():
        pl.camera.azimuth += 1.0                    # a new view, as floatcol's
        pl.render()                                 # (screenshot alone may reuse the last frame)
        pl.screenshot(return_img=True)
    ms = _median_ms(once, 10)
    # a new surface each time (a new expression): mesh upload included
    def fresh():
        p2 = pv.Plotter(off_screen=True, window_size=list(size))
        p2.add_mesh(pv.StructuredGrid(U, V, W), cmap="viridis", show_scalar_bar=False)
        if parallel:
            p2.enable_parallel_projection()
        p2.screenshot(return_img=True)
        p2.close()
    fresh()
    ms_fresh = _median_ms(fresh, 3)
    pl.close()
    return ms, ms_fresh


def eval_ns():
    """ns per sample for f, f_u and f_v of EXPR together (one fused compiled function,
    sympy cse), on one thread, through the kernels' own evaluation path."""
    from floatcol.kernels.sample import eval_grid
    s = fc.as_surface(EXPR)
    n = 500_000
    rng = np.random.default_rng(1)
    u = rng.uniform(-5, 5, n)
    v = rng.uniform(-5, 5, n)
    out = np.empty((n, 3))
    eval_grid(*s.kernel_args(), u[:10], v[:10], out[:10])
    scalar = _median_ms(lambda: eval_grid(*s.kernel_args(), u, v, out), 5) * 1e6 / n
    # the batch evaluator (SIMD code, orthographic planes), called as the kernels do
    fb = s.batch()
    ptr = ctypes.POINTER(ctypes.c_double)
    flat = np.empty(3 * n)

    def batch():
        fb.ctypes(u.ctypes.data_as(ptr), v.ctypes.data_as(ptr), 0.0, flat.ctypes.data_as(ptr), n)
    batch()
    return scalar, _median_ms(batch, 5) * 1e6 / n


def fidelity(size=(512, 384), elev=30.0, azim=30.0):
    """[(tool, PSNR dB, agreement)] of the three tools against the ray caster, one
    orthographic camera (matplotlib's), the reference lighting model."""
    import sympy
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
    from reference import psnr, raycast
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d import proj3d

    W, H = size
    u, v = sympy.symbols("u v")
    e = sympy.sympify(EXPR)
    f, fu, fv = (sympy.lambdify((u, v), x, "numpy") for x in (e, e.diff(u), e.diff(v)))
    a, b = -math.radians(elev), math.radians(azim)
    ca, sa, cb, sb = math.cos(a), math.sin(a), math.cos(b), math.sin(b)
    ex = np.array([cb, -sb, 0.0])                 # screen x, y, z in world (u, v, w)
    ey = np.array([-sa * sb, -sa * cb, ca])
    ez = np.array([ca * sb, ca * cb, sa])
    U, V, Wm = _mesh()
    cu, cv = (U[:-1, :-1] + U[1:, 1:]) / 2, (V[:-1, :-1] + V[1:, 1:]) / 2
    n = np.stack([-fu(cu, cv), -fv(cu, cv), np.ones_like(cu)], -1)
    shade = np.abs(n @ ez) / np.linalg.norm(n, axis=-1)
    colors = np.zeros(U.shape + (4,))
    colors[..., 3] = 1.0
    colors[:-1, :-1, :3] = shade[..., None]

    fig = plt.figure(figsize=(W / 100, H / 100), dpi=100, facecolor="black")
    ax = fig.add_axes([0, 0, 1, 1], projection="3d")
    ax.set_proj_type("ortho")
    ax.set_axis_off()
    ax.set_facecolor("black")
    ax.view_init(elev, -90.0 - azim)              # plot.py: matplotlib's azimuth
    ax.set_xlim(-5, 5)
    ax.set_ylim(-5, 5)
    ax.set_zlim(-3, 3)
    ax.set_box_aspect((10, 10, 6))                # one scale on all three axes
    ax.plot_surface(U, V, Wm, facecolors=colors, shade=False, rstride=1, cstride=1,
                    linewidth=0, antialiased=False)
    buf = io.BytesIO()
    fig.savefig(buf, format="rgba", dpi=100, facecolor="black")
    mpl_img = np.frombuffer(buf.getvalue(), np.uint8).reshape(H, W, 4)[..., 0] / 255.0
    # matplotlib's pixel of world points against floatcol's screen coordinates
    pts = np.random.default_rng(0).uniform((-5, -5, -3), (5, 5, 3), (64, 3))
    px, py, _ = proj3d.proj_transform(*pts.T, ax.get_proj())
    disp = ax.transData.transform(np.column_stack([px, py]))
    plt.close(fig)
    A = np.column_stack([pts @ ex, pts @ ey, np.ones(len(pts))])
    col_fit = np.linalg.lstsq(A, disp[:, 0] - 0.5, rcond=None)[0]
    row_fit = np.linalg.lstsq(A, H - 0.5 - disp[:, 1], rcond=None)[0]
    resid = max(np.abs(A @ col_fit - (disp[:, 0] - 0.5)).max(),
                np.abs(A @ row_fit - (H - 0.5 - disp[:, 1])).max())
    scale = col_fit[0]
    center = ((W - 1) / 2 - col_fit[2]) / scale * ex + (row_fit[2] - (H - 1) / 2) / scale * ey
    print(f"\nmatplotlib's camera: {scale:.3f} pixels per unit, fit residual {resid:.1e} pixel")

    ref = raycast((f, fu, fv), (-5, 5), (-5, 5), size, elev, azim, "orthographic", None,
                  None, scale, center=tuple(center))
    rows = []

    def row(name, inten, seen):
        rows.append((name, psnr(np.nan_to_num(inten), ref.intensity),
                     float((seen == (ref.side != 0)).mean())))

    r = fc.render(EXPR, size=size, elev=elev, azim=azim, shading="lambert", scale=scale,
                  center=tuple(center), **DOM)
    row("floatcol (default quality, lambert)", r.intensity, r.side != 0)
    row(f"matplotlib plot_surface {MESH}x{MESH}", mpl_img, mpl_img > 0)
    try:
        import pyvista as pv
    except ImportError:
        return rows
    for smooth in (False, True):
        pl = pv.Plotter(off_screen=True, window_size=list(size))
        pl.background_color = "black"
        pl.remove_all_lights()
        pl.add_light(pv.Light(light_type="headlight"))
        pl.add_mesh(pv.StructuredGrid(U, V, Wm), color="white", ambient=0.0, diffuse=1.0,
                    specular=0.0, smooth_shading=smooth)
        pl.enable_parallel_projection()
        pl.camera.focal_point = tuple(center)
        pl.camera.position = tuple(center - 50 * ez)
        pl.camera.up = tuple(ey)
        pl.camera.parallel_scale = H / (2 * scale)
        pl.camera.clipping_range = (1, 100)
        img = pl.screenshot(return_img=True)[..., 0] / 255.0
        pl.close()
        row(f"PyVista {MESH}x{MESH}, {'smooth' if smooth else 'flat'} shading", img, img > 0)
    return rows


def breakdown(size=(1920, 1080), proj="perspective", repeat=11):
    """Where a render's time goes (medians, ms): its passes, timed by wrapping them
    (floatcol.renderer's names), and the column pass against the planes' spacing.
    The column pass at pixel_step 16 is what no thinning of planes can take away:
    painting the picture's pixels (and the corrections' samples on long spans)."""
    from floatcol import renderer
    timed = {}
    passes = (("column pass", renderer.geometry, "column_pass"),
              ("finishing pass", renderer.finish, "finish_pass"),
              ("staircase pass", renderer.antialias, "staircase_pass"))
    originals = []
    for name, mod, attr in passes:
        fn = getattr(mod, attr)
        originals.append((mod, attr, fn))

        def wrapped(*a, _fn=fn, _name=name, **k):
            t = time.perf_counter()
            out = _fn(*a, **k)
            timed.setdefault(_name, []).append((time.perf_counter() - t) * 1e3)
            return out
        setattr(mod, attr, wrapped)
    try:
        rows = []
        for label, kw in (("default (pixel_step 1)", {}), ("pixel_step 2", dict(pixel_step=2)),
                          ("pixel_step 4", dict(pixel_step=4)),
                          ("pixel_step 16", dict(pixel_step=16)),
                          ("pixel_step 16, no corrections, no antialiasing",
                           dict(pixel_step=16, corrections="none", antialias=False))):
            fc.render(EXPR, size=size, projection=proj, **kw, **DOM)
            timed.clear()
            ts = _times_ms(lambda: fc.render(EXPR, size=size, projection=proj, **kw, **DOM),
                           repeat)
            r = fc.render(EXPR, size=size, projection=proj, **kw, **DOM)
            med = {k: statistics.median(v) for k, v in timed.items()}
            rows.append((label, r.stats["planes"], statistics.median(ts), med))
    finally:
        for mod, attr, fn in originals:
            setattr(mod, attr, fn)
    print(f"\n| {size[0]}x{size[1]} {proj} | planes | render ms | column pass | finishing | "
          f"staircase | the rest |")
    print("|---|---|---|---|---|---|---|")
    for label, planes, total, med in rows:
        parts = [med.get(name, 0.0) for name, _, _ in passes]
        print(f"| {label} | {planes} | {total:.1f} | " + " | ".join(f"{x:.1f}" for x in parts)
              + f" | {total - sum(parts):.1f} |")


def main():
    print(f"{os.cpu_count()} cpus, {numba.get_num_threads()} numba threads")
    scalar_ns, batch_ns = eval_ns()
    print(f"f, f_u, f_v of {EXPR}: {scalar_ns:.0f} ns per sample one at a time, "
          f"{batch_ns:.1f} ns in batches (one thread)")
    fc.render(EXPR, size=(64, 48), **DOM)
    fc.render(EXPR, size=(64, 48), projection="perspective", **DOM)
    print("\n| tool | size | projection | samples | median ms | fps | best ms |")
    print("|---|---|---|---|---|---|---|")
    ours = {}

    def with_arrays(**kw):
        # the picture and, asked for, intensity and depth (Render computes them from
        # its G-buffer when first read: the picture does not wait for them)
        r = fc.render(EXPR, **kw, **DOM)
        return r.intensity, r.depth

    for size in ((1920, 1080), (1024, 768)):
        for proj in ("orthographic", "perspective"):
            r = fc.render(EXPR, size=size, projection=proj, **DOM)
            ts = _times_ms(lambda: fc.render(EXPR, size=size, projection=proj, **DOM), 15)
            ms = statistics.median(ts)
            ours[size, proj] = ms
            print(f"| floatcol | {size[0]}x{size[1]} | {proj} | {r.stats['samples']} | {ms:.1f} | "
                  f"{1000 / ms:.1f} | {min(ts):.1f} |")
            ts = _times_ms(lambda: with_arrays(size=size, projection=proj), 9)
            print(f"| floatcol, + intensity and depth read | {size[0]}x{size[1]} | {proj} | | "
                  f"{statistics.median(ts):.1f} | {1000 / statistics.median(ts):.1f} | "
                  f"{min(ts):.1f} |")
    # the same data as matplotlib's: its MESH x MESH mesh, drawn as what
    # plot_surface(X, Y, Z) draws (a height field: bilinear between the points)
    X, Y, Z = _mesh()
    hf = fc.HeightField(Z, u=(X.min(), X.max()), v=(Y.min(), Y.max()))
    mesh_ms = {}
    for size in ((1920, 1080), (1024, 768)):
        for proj in ("orthographic", "perspective"):
            r = fc.render(hf, size=size, projection=proj)
            ts = _times_ms(lambda: fc.render(hf, size=size, projection=proj), 9)
            mesh_ms[size, proj] = ms = statistics.median(ts)
            print(f"| floatcol, the {MESH}x{MESH} mesh (X, Y, Z) | {size[0]}x{size[1]} | {proj} | "
                  f"{r.stats['samples']} | {ms:.1f} | {1000 / ms:.1f} | {min(ts):.1f} |")
    mpl = matplotlib_ms((1024, 768))
    print(f"| matplotlib plot_surface {MESH}x{MESH}, savefig PNG | 1024x768 | persp | "
          f"{MESH * MESH} vertices | {mpl:.0f} | {1000 / mpl:.2f} | |")
    pv_res = {}
    for size in ((1024, 768), (1920, 1080)):
        for proj in ("orthographic", "perspective"):
            res = pyvista_ms(size, parallel=proj == "orthographic")
            if res is None:
                print("| PyVista | - | not installed (pip install -e .[bench]) | | | | |")
                break
            pv_res[size, proj] = res
            for what, ms in zip(("new view", "new mesh"), res):
                print(f"| PyVista {MESH}x{MESH}, {what} + screenshot | {size[0]}x{size[1]} | "
                      f"{proj} | {MESH * MESH} vertices | {ms:.1f} | {1000 / ms:.1f} | |")
    print("\n| ratio | value |")
    print("|---|---|")
    for size in ((1024, 768), (1920, 1080)):
        for proj in ("orthographic", "perspective"):
            print(f"| matplotlib 1024x768 / floatcol {size[0]}x{size[1]} {proj} | "
                  f"{mpl / ours[size, proj]:.1f}x |")
    print("(issue 33's goal: 1920x1080 perspective >= 25x)")
    for size in ((1024, 768), (1920, 1080)):
        for proj in ("orthographic", "perspective"):
            print(f"| matplotlib 1024x768 / floatcol's {MESH}x{MESH} mesh {size[0]}x{size[1]} "
                  f"{proj} | {mpl / mesh_ms[size, proj]:.1f}x |")
    for (size, proj), (view_ms, fresh_ms) in pv_res.items():
        ms = ours[size, proj]           # the same projection on both sides
        print(f"| PyVista new view / floatcol, {size[0]}x{size[1]} {proj} | {view_ms / ms:.2f}x |")
        print(f"| PyVista new mesh / floatcol, {size[0]}x{size[1]} {proj} | {fresh_ms / ms:.2f}x |")
    breakdown()
    rows = fidelity()
    print("\n| tool, orthographic 512x384 against the ray caster | PSNR dB | agreement |")
    print("|---|---|---|")
    for name, db, agree in rows:
        print(f"| {name} | {db:.2f} | {agree * 100:.3f} % |")
    if "--thinning" in sys.argv[1:]:
        thinning()


def thinning(size=(960, 540)):
    """What thinning the perspective planes would cost in fidelity: floatcol's
    perspective picture (shading="lambert") against the ray caster at ``size``, at
    pixel_step 1 (default), 1.5 and 2 and with sampling="adaptive" (section 6.3: the
    step grows with the distance), and how far apart in depth the default view's
    nearest and farthest planes are (a step of a pixel at every plane's depth, instead
    of at the nearest, would leave out a share 1 - ln(R) / (R - 1) of the planes)."""
    sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))
    from reference import numpy_surface, psnr, raycast
    print(f"\n| perspective, planes thinned | PSNR dB against the ray caster at "
          f"{size[0]}x{size[1]} | planes | samples |")
    print("|---|---|---|---|")
    ref = None
    for name, kw in (("pixel_step 1 (default)", {}), ("pixel_step 1.5", dict(pixel_step=1.5)),
                     ("pixel_step 2", dict(pixel_step=2)),
                     ('sampling="adaptive"', dict(sampling="adaptive"))):
        r = fc.render(EXPR, size=size, projection="perspective", shading="lambert", **kw,
                      **DOM)
        vw = r.view
        if ref is None:
            ref = raycast(numpy_surface(EXPR), DOM["u"], DOM["v"], size, vw.elev, vw.azim,
                          "perspective", vw.d1, vw.d2, vw.scale, center=vw.center)
            near = vw.q_near
            far = near + (vw.t_range[1] - vw.t_range[0]) * math.cos(math.radians(vw.elev))
        print(f"| {name} | {psnr(np.nan_to_num(r.intensity), ref.intensity):.2f} | "
              f"{r.stats['planes']} | {r.stats['samples']} |")
    ratio = far / near
    print(f"(depth of the farthest plane / the nearest, about: {ratio:.2f}; planes a pixel "
          f"apart at each depth would be {1 - math.log(ratio) / (ratio - 1):.0%} fewer)")


if __name__ == "__main__":
    main()
