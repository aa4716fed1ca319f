"""Textures, colour from data and lines on the surface (Gordon section 6.7).

A photograph draped over a wave, a DEM draped with an image made from it (its
hillshaded colour relief, as an orthophoto would be), Gordon's function coloured by its
slope with a colorbar, its contour lines, and matplotlib's own call form with the mesh's
lines drawn on the exact surface. Textures are read through mip-maps (each pixel
averages the texels it covers; with sub-columns, ``antialias=3``, across the pixel
too), lines are drawn from the G-buffer: antialiased, a constant width in pixels, hidden
wherever the surface hides them.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import sympy as sp  # noqa: E402
from matplotlib import cm  # noqa: E402
from matplotlib.cbook import get_sample_data  # noqa: E402
from matplotlib.colors import LightSource  # noqa: E402

import floatcol as fc  # noqa: E402

# a photograph on a wave: the image's first row is its top, the texture's row 0 is v's low end;
# antialias=3: each pixel averages three sub-columns across it, the photograph's too
with get_sample_data("grace_hopper.jpg") as f:
    photo = plt.imread(f)[::-1]
fc.render("0.4*sin(1.5*u)*cos(v)", u=(-4, 4), v=(-3, 3), size=(800, 560), elev=35, azim=20,
          texture=photo, ambient=0.45, specular=0.1, antialias=3).save("texture_photo.png")

# a DEM draped with an image of itself: colour relief under a low sun
dem = get_sample_data("jacksboro_fault_dem.npz")
z = dem["elevation"][::-1].astype(float)
relief = LightSource(azdeg=315, altdeg=30).shade(z, cmap=cm.gist_earth, blend_mode="soft",
                                                 vert_exag=0.05)
lat = np.radians(0.5 * (dem["ymin"] + dem["ymax"]))
km_x, km_y = dem["dx"] * 111.32 * np.cos(lat), dem["dy"] * 110.57
ny, nx = z.shape
terrain = fc.HeightField(3 * z / 1000.0, u=(0, (nx - 1) * km_x), v=(0, (ny - 1) * km_y))
fc.render(terrain, size=(900, 560), elev=40, azim=20, projection="perspective",
          texture=relief, ambient=0.6, specular=0.0).save("texture_dem.png")

# colour by slope |grad f|, with its colorbar (plot_surface's color_field)
x, y = sp.symbols("x y")
f = 3 * sp.sin(x * sp.cos(y))
slope = sp.sqrt(sp.diff(f, x) ** 2 + sp.diff(f, y) ** 2)
fig = plt.figure(figsize=(8, 6))
ax = fig.add_subplot(projection="3d")
p = fc.plot_surface(f, (x, -5, 5), (y, -5, 5), ax=ax, color_field=slope, cmap="inferno",
                    vmin=0, vmax=10)
fig.colorbar(p, ax=ax, shrink=0.6, label="|grad f|")
fig.savefig("texture_slope.png", dpi=100)
plt.close(fig)

# contour lines on Gordon's function, seen from above
fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(800, 600), elev=55, azim=20,
          contours=12, contour_color="white", contour_width=1.2, cmap="cividis"
          ).save("texture_contours.png")

# matplotlib's call form: its coolwarm example with the mesh's lines, on the exact surface
X, Y = np.meshgrid(np.linspace(-5, 5, 80), np.linspace(-5, 5, 80))
Z = np.sin(np.sqrt(X ** 2 + Y ** 2))
fig = plt.figure(figsize=(8, 6))
ax = fig.add_subplot(projection="3d")
s = fc.plot_surface(X, Y, Z, ax=ax, cmap=cm.coolwarm, edgecolor="k", linewidth=0.4,
                    rcount=20, ccount=20)
fig.colorbar(s, ax=ax, shrink=0.5, aspect=5)
fig.savefig("texture_wireframe.png", dpi=100)
plt.close(fig)
