"""Draw the pictures the docs use (small PNGs committed under docs/img).

Run: python docs/make_figures.py
"""
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import floatcol as fc  # noqa: E402

IMG = Path(__file__).parent / "img"


def camera():
    """The paper's camera: viewpoint, screen, one pixel column's plane Pi and the
    sampling planes t = const cutting the surface in the column's curve."""
    fig = plt.figure(figsize=(7, 5), dpi=100)
    ax = fig.add_subplot(projection="3d")
    ax.view_init(22, -58)
    u = np.linspace(-3, 3, 41)
    U, V = np.meshgrid(u, u)
    W = 0.6 * np.sin(U * np.cos(V / 1.5))
    ax.plot_surface(U, V, W, color="#9ecae1", alpha=0.45, linewidth=0)
    # the view: looking along +v from far back, a column plane Pi at u = 0.8
    eye = np.array([0.8 * 0.2, -9.0, 3.2])
    ax.scatter(*eye, color="k", s=20)
    ax.text(*(eye + [0, 0, 0.4]), "viewpoint", fontsize=9)
    # screen rectangle between the viewpoint and the surface
    sv = -6.0
    sx, sz = np.meshgrid([-1.6, 1.6], [0.2, 2.4])
    ax.plot_surface(sx, np.full_like(sx, sv), sz, color="#fdd0a2", alpha=0.5)
    ax.text(1.2, sv, 2.7, "screen", fontsize=9)
    # the column: a vertical line on the screen; Pi = the plane through it and the eye
    cx = 0.35
    ax.plot([cx, cx], [sv, sv], [0.2, 2.4], color="#d62728", lw=2)
    tt = np.linspace(-3, 3, 200)
    k = (cx - eye[0]) / (sv - eye[1])          # Pi: u - eye_u = k (v - eye_v)
    cu = eye[0] + k * (tt - eye[1])
    cw = 0.6 * np.sin(cu * np.cos(tt / 1.5))
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    ends = [eye[0] + k * (v - eye[1]) for v in (sv, 3.0)]
    pi = [(ends[0], sv, -1.2), (ends[1], 3.0, -1.2), (ends[1], 3.0, 2.4), (ends[0], sv, 2.4)]
    ax.add_collection3d(Poly3DCollection([pi], color="#d62728", alpha=0.08))
    ax.text(ends[1], 3.0, 2.5, "Π", fontsize=12, color="#d62728")
    ax.plot(cu, tt, cw, color="#d62728", lw=2.2, label="the column's curve (Π ∩ surface)")
    for t in np.linspace(-2.7, 2.7, 10):       # sampling planes t = const, front to back
        uu = eye[0] + k * (t - eye[1])
        ww = 0.6 * np.sin(uu * np.cos(t / 1.5))
        ax.plot([uu, uu], [t, t], [-1.2, 1.6], color="#555", lw=0.6, alpha=0.6)
        ax.scatter(uu, t, ww, color="#d62728", s=8)
    ax.set_xlabel("u")
    ax.set_ylabel("v")
    ax.set_zlabel("w")
    ax.set_box_aspect((1, 2, 0.7))
    ax.legend(loc="upper left", fontsize=8)
    ax.set_title("One pixel column: plane Π, sampling planes, samples front to back", fontsize=10)
    fig.savefig(IMG / "camera.png", dpi=100, bbox_inches="tight")
    plt.close(fig)


def examples():
    fc.plot_surface("3*sin(x*cos(y))", ("x", -5, 5), ("y", -5, 5), size=(480, 360),
                    cmap="viridis").save(IMG / "demo.png")
    fc.plot_surface("sin(x*y)", ("x", -3, 3), ("y", -3, 3), method="horizon", lines=90,
                    size=(480, 360), proj_type="ortho").save(IMG / "horizon.png")


def mplot3d():
    """matplotlib's surface3d example: mplot3d's mesh, and floatcol in the same Axes."""
    from matplotlib import cm
    X, Y = np.meshgrid(np.arange(-5, 5, 0.25), np.arange(-5, 5, 0.25))
    Z = np.sin(np.sqrt(X ** 2 + Y ** 2))
    fig = plt.figure(figsize=(9, 3.6), dpi=80)
    for k, title in enumerate(("mplot3d: ax.plot_surface(X, Y, Z, ...)",
                               "floatcol: fc.plot_surface(X, Y, Z, ax=ax, ...)")):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        kw = dict(cmap=cm.coolwarm, linewidth=0, antialiased=False)
        s = ax.plot_surface(X, Y, Z, **kw) if k == 0 else fc.plot_surface(X, Y, Z, ax=ax, **kw)
        ax.set_zlim(-1.01, 1.01)
        ax.set_title(title, fontsize=9)
        fig.colorbar(s, ax=ax, shrink=0.5, aspect=5)
    fig.savefig(IMG / "mplot3d.png")
    plt.close(fig)


def translucency():
    """Gordon's function opaque and at opacity 0.45: the folds behind the ridges."""
    from PIL import Image
    kw = dict(u=(-5, 5), v=(-5, 5), size=(400, 300), elev=35, azim=30, cmap="plasma")
    pair = [fc.render("3*sin(u*cos(v))", opacity=a, **kw).rgba for a in (1.0, 0.45)]
    Image.fromarray(np.concatenate(pair, axis=1)).save(IMG / "translucency.png",
                                                       optimize=True)


def shadows():
    """Gordon's function under a sun at 40 degrees, without and with its shadows."""
    kw = dict(u=(-5, 5), v=(-5, 5), size=(360, 270), elev=50, azim=30, lightsource=(200, 40),
              cmap="cividis", ambient=0.35)
    pair = [fc.render("3*sin(u*cos(v))", shadows=s, **kw).rgba for s in (False, True)]
    from PIL import Image
    Image.fromarray(np.concatenate(pair, axis=1)).save(IMG / "shadows.png", optimize=True)


def textures():
    """A checkerboard texture, colour by a second field with contours, a wireframe."""
    from PIL import Image
    kw = dict(u=(-5, 5), v=(-5, 5), size=(300, 225), elev=40, azim=30)
    k = (np.add.outer(np.arange(256) // 32, np.arange(256) // 32) % 2).astype(np.uint8)
    checker = np.stack([k * 200 + 40, 255 - k * 140, np.full_like(k, 90)], axis=-1)
    E = "3*sin(u*cos(v))"
    three = [fc.render(E, texture=checker, **kw).rgba,
             fc.render(E, color="sqrt(u**2+v**2)", cmap="plasma", contours=10,
                       contour_color="white", **kw).rgba,
             fc.render(E, wireframe=21, linewidth=0.6, cmap="cividis", **kw).rgba]
    Image.fromarray(np.concatenate(three, axis=1)).save(IMG / "textures.png", optimize=True)


def smooth_shading():
    """matplotlib's Jacksboro DEM flown over: its cells' own normals, and smooth
    shading (the normals interpolated between the nodes)."""
    from matplotlib.cbook import get_sample_data
    from PIL import Image
    dem = fc.read_dem(get_sample_data("jacksboro_fault_dem.npz", asfileobj=False),
                      vert_exag=2.0)
    cam = fc.fly(dem, (15000.0, 2500.0), heading=15, pitch=-10, fov=55, size=(400, 225),
                 above=900)
    pair = [fc.render(dem, **cam, antialias="area", cmap="gist_earth", lightsource=(315, 35),
                      background="lightskyblue", smooth_shading=s).rgba[..., :3]
            for s in (False, True)]
    Image.fromarray(np.concatenate(pair, axis=1)).save(IMG / "smooth_shading.jpg", quality=85)


def terrain_fly():
    """The terrain guide's picture: the gallery's fly-through still (draped, shadowed,
    area-sampled, smooth-shaded, with trees, a mast and a house), run in a scratch
    folder."""
    import os
    import runpy
    import tempfile
    from PIL import Image
    script = Path(__file__).parent.parent / "gallery" / "terrain_flythrough.py"
    here = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        os.chdir(tmp)
        try:
            runpy.run_path(str(script), run_name="__main__")
            Image.open("terrain_fly.png").convert("RGB").save(IMG / "terrain_fly.jpg",
                                                              quality=85)
        finally:
            os.chdir(here)


def flight_strip():
    """Four frames of a flight along a curve through three waypoints over the Jacksboro
    DEM (fc.fly_through), side by side."""
    from matplotlib.cbook import get_sample_data
    from PIL import Image
    dem = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)
    clip = fc.fly_through(dem, [(15000, 2500), (15400, 6000), (17000, 9500)], frames=4,
                          size=(240, 135), above=900, vert_exag=2, pitch=-10, fov=55,
                          background="lightskyblue", shadows=True, progress=False)
    strip = np.concatenate([f[..., :3] for f in clip.frames], axis=1)
    Image.fromarray(strip).save(IMG / "flight_strip.jpg", quality=85)


if __name__ == "__main__":
    IMG.mkdir(exist_ok=True)
    flight_strip()
    terrain_fly()
    smooth_shading()
    camera()
    examples()
    shadows()
    translucency()
    textures()
    mplot3d()
