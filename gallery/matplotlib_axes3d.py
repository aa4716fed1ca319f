"""floatcol in matplotlib's own 3-D Axes: the surface3d example with only its
plot_surface call changed, markers hidden behind a hill, two crossing surfaces in one
Axes, a terrain with matplotlib's LightSource, a surface clipped at the Axes' limits
(axlim_clip), plot_wireframe with the hidden lines removed, beside mplot3d's own, and
the surface3d_radial example's polar grid (resampled onto an even one; its edges, and an
unevenly spaced mesh's, mplot3d's lines), the
checkerboard example's facecolors beside a plane of mplot3d's cut where it passes
through the surface, the trisurf3d example's scattered points (fc.plot_trisurf), and an
animation made as matplotlib's are (remove the last frame's plot, plot the next) under
a translucent lid, with a legend.

``fc.plot_surface(X, Y, Z, ax=ax, ...)`` takes matplotlib's call form and keywords;
inside ``fig.add_subplot(projection="3d")`` the Axes keep their panes, ticks, labels
and limits, and the surface lies exactly where mplot3d would draw the mesh.
mplot3d's own ``ax.scatter``, ``ax.plot``, ``ax.text`` and ``ax.quiver`` in that Axes
are drawn depth-tested against the surface (as ``plot.scatter`` and ``plot.plot``),
which mplot3d alone cannot do: it sorts whole artists.
"""
import matplotlib.pyplot as plt
import numpy as np
from matplotlib import cm
from matplotlib.cbook import get_sample_data
from matplotlib.colors import LightSource
from matplotlib.ticker import LinearLocator

import floatcol as fc

# matplotlib's surface3d example: only the plot_surface line differs
fig, ax = plt.subplots(subplot_kw={"projection": "3d"})
X = np.arange(-5, 5, 0.25)
Y = np.arange(-5, 5, 0.25)
X, Y = np.meshgrid(X, Y)
R = np.sqrt(X**2 + Y**2)
Z = np.sin(R)
surf = fc.plot_surface(X, Y, Z, ax=ax, cmap=cm.coolwarm, linewidth=0, antialiased=False)
ax.set_zlim(-1.01, 1.01)
ax.zaxis.set_major_locator(LinearLocator(10))
ax.zaxis.set_major_formatter('{x:.02f}')
fig.colorbar(surf, shrink=0.5, aspect=5)
fig.savefig("surface3d.png")

# markers and a path around a hill: hidden where the hill is in front of them
fig = plt.figure(figsize=(7, 5))
ax = fig.add_subplot(projection="3d")
fc.plot_surface("2*exp(-(x**2 + y**2)/2)", ("x", -3, 3), ("y", -3, 3), ax=ax,
                cmap="summer")
rng = np.random.default_rng(3)
pts = rng.uniform([-3, -3, 0.2], [3, 3, 2.4], (250, 3))
ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], color="crimson", s=14)
t = np.linspace(0, 2 * np.pi, 400)
ax.plot(2.2 * np.cos(t), 2.2 * np.sin(t), 0.6 + 0.5 * np.sin(3 * t), color="k", linewidth=2)
ax.set_title("mplot3d's scatter and plot, depth-tested against the surface")
fig.savefig("occluded_objects.png")

# two plot_surface calls in one Axes: they hide each other a pixel at a time (mplot3d
# draws each of its own surfaces whole, one over the other)
fig = plt.figure(figsize=(7, 5))
ax = fig.add_subplot(projection="3d")
fc.plot_surface("sin(x) * cos(y)", ("x", -3, 3), ("y", -3, 3), ax=ax, cmap="coolwarm")
fc.plot_surface("x / 4", ("x", -3, 3), ("y", -3, 3), ax=ax, color="gold", alpha=0.8)
ax.set_title("two surfaces in one Axes, crossing")
fig.savefig("two_surfaces.png")

# matplotlib's custom hillshading example, in floatcol
dem = get_sample_data("jacksboro_fault_dem.npz")
z = dem["elevation"]
nrows, ncols = z.shape
x = np.linspace(dem["xmin"], dem["xmax"], ncols)
y = np.linspace(dem["ymin"], dem["ymax"], nrows)
x, y = np.meshgrid(x, y)
region = np.s_[5:50, 5:50]
x, y, z = x[region], y[region], z[region]
fig, ax = plt.subplots(subplot_kw=dict(projection="3d"))
ls = LightSource(270, 45)
fc.plot_surface(x, y, z, ax=ax, cmap=cm.gist_earth, lightsource=ls, linewidth=0,
                antialiased=False, shade=True)
fig.savefig("hillshading.png")

# axlim_clip=True (matplotlib 3.10): what lies outside the Axes' limits is not drawn,
# the expression cut exactly where it leaves them
fig = plt.figure(figsize=(7, 5))
ax = fig.add_subplot(projection="3d")
fc.plot_surface("sin(sqrt(x**2 + y**2))", ("x", -5, 5), ("y", -5, 5), ax=ax, cmap="viridis",
                axlim_clip=True)
ax.set_xlim(-3, 5)
ax.set_zlim(-0.6, 0.8)
ax.set_title("axlim_clip=True: clipped at x = -3, z = -0.6 and 0.8")
fig.savefig("axlim_clip.png")

# plot_wireframe: the mesh's lines with those behind the surface hidden (mplot3d's own
# draws every line, right)
from mpl_toolkits.mplot3d import axes3d  # noqa: E402

X, Y, Z = axes3d.get_test_data(0.05)
fig = plt.figure(figsize=(10, 4.5))
ax = fig.add_subplot(1, 2, 1, projection="3d")
fc.plot_wireframe(X, Y, Z, ax=ax, rstride=10, cstride=10)
ax.set_title("fc.plot_wireframe: hidden lines removed")
ax = fig.add_subplot(1, 2, 2, projection="3d")
ax.plot_wireframe(X, Y, Z, rstride=10, cstride=10)
ax.set_title("mplot3d's plot_wireframe")
for a in fig.axes:
    a.view_init(15, -60)
fig.savefig("wireframe_hidden_lines.png")

# matplotlib's surface3d_radial example: a polar grid, not an evenly spaced one, is
# resampled (each quad two flat triangles, as mplot3d draws it; docs/matplotlib.md);
# the lip's outside, its lower side, coloured from the colour map as mplot3d does
r = np.linspace(0, 1.25, 50)
p = np.linspace(0, 2 * np.pi, 50)
R, P = np.meshgrid(r, p)
Z = ((R**2 - 1)**2)
X, Y = R * np.cos(P), R * np.sin(P)
fig = plt.figure(figsize=(10, 4.5))
ax = fig.add_subplot(1, 2, 1, projection="3d")
fc.plot_surface(X, Y, Z, ax=ax, cmap=plt.cm.YlGnBu_r, lower_color="same")   # as mplot3d
ax.set_zlim(0, 1)
ax.set_xlabel(r"$\phi_\mathrm{real}$")
ax.set_ylabel(r"$\phi_\mathrm{im}$")
ax.set_zlabel(r"$V(\phi)$")
# ... and with the mesh's own edges (every other circle and ray: rcount, ccount), and
# an unevenly spaced mesh's (x along np.geomspace): mplot3d's lines, drawn on the
# resampled surface a pixel at a time
ax = fig.add_subplot(1, 2, 2, projection="3d")
fc.plot_surface(X, Y, Z, ax=ax, cmap=plt.cm.YlGnBu_r, lower_color="same", edgecolor="k",
                linewidth=0.3, rcount=25, ccount=25)
XG, YG = np.meshgrid(np.geomspace(1.4, 3, 12), np.linspace(-1.25, 1.25, 10))
fc.plot_surface(XG, YG, 0.5 + 0.3 * np.sin(3 * YG) / XG, ax=ax, color="tab:orange",
                edgecolor="k", linewidth=0.5)
ax.set_zlim(0, 1)
fig.savefig("surface3d_radial.png")

# matplotlib's checkerboard example (surface3d_3): facecolors colour whole faces; a
# plane drawn by mplot3d's own plot_surface, cut where it passes through the surface
fig = plt.figure(figsize=(10, 4.5))
ax = fig.add_subplot(1, 2, 1, projection="3d")
XC, YC = np.meshgrid(np.arange(-5, 5, 0.25), np.arange(-5, 5, 0.25))
ZC = np.sin(np.sqrt(XC**2 + YC**2))
colors = np.where(np.add.outer(np.arange(40), np.arange(40)) % 2 == 0, "y", "b")
fc.plot_surface(XC, YC, ZC, ax=ax, facecolors=colors, linewidth=0)
ax.set_zlim(-1, 1)
ax = fig.add_subplot(1, 2, 2, projection="3d")
fc.plot_surface(XC, YC, ZC, ax=ax, cmap="viridis")
ax.plot_surface(XC, YC, 0 * ZC + 0.3, color="tab:red", rcount=10, ccount=10, edgecolor="k",
                linewidth=0.3)
fig.savefig("faces_and_planes.png")

# matplotlib's trisurf3d example: scattered points, linear on their Delaunay triangles
# (fc.plot_trisurf), the triangles' edges drawn as mplot3d's lines, depth-tested
radii = np.linspace(0.125, 1.0, 8)
angles = np.linspace(0, 2 * np.pi, 36, endpoint=False)[..., np.newaxis]
xs = np.append(0, (radii * np.cos(angles)).flatten())
ys = np.append(0, (radii * np.sin(angles)).flatten())
fig, ax = plt.subplots(subplot_kw={"projection": "3d"})
fc.plot_trisurf(xs, ys, np.sin(-xs * ys), ax=ax, cmap="viridis", edgecolor="k",
                linewidth=0.2)
fig.savefig("trisurf3d.png")

# matplotlib's way to animate a surface: each frame removes the last frame's plot and
# plots the next (plot.remove(), as an mplot3d artist's); a label puts it in the legend
# beside a translucent plot, which shows the moving one through it
from matplotlib.animation import FuncAnimation, PillowWriter  # noqa: E402

fig = plt.figure(figsize=(4.8, 3.6), dpi=80)
ax = fig.add_subplot(projection="3d")
x = np.linspace(-4, 4, 61)
X, Y = np.meshgrid(x, x)
fc.plot_surface(X, Y, 0 * X + 0.9, ax=ax, color="lightsteelblue", alpha=0.45,
                label="a translucent lid")
ax.set(xlim=(-4, 4), ylim=(-4, 4), zlim=(-1.2, 1.2))
wave = [fc.plot_surface(X, Y, np.cos(np.hypot(X, Y)), ax=ax, cmap="viridis",
                        vmin=-1, vmax=1, label="cos(r - t)")]
ax.legend(loc="upper left")


def frame(k):
    wave[0].remove()
    t = 2 * np.pi * k / 12
    wave[0] = fc.plot_surface(X, Y, np.cos(np.hypot(X, Y) - t), ax=ax, cmap="viridis",
                              vmin=-1, vmax=1, label="cos(r - t)")


FuncAnimation(fig, frame, frames=12).save("mplot3d_animation.gif", writer=PillowWriter(fps=8))
