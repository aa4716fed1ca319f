"""Translucency (Gordon sections 6.5-6.6): a surface that shows its own hidden folds,
a function and its Taylor polynomial meeting, sympy's plot3d(f, g) with alpha,
matplotlib's translucent mesh with its edges, and trees seen through a translucent
hill, their soft shadows on it.

``opacity`` below 1 (matplotlib's ``alpha`` in plot_surface and plot3d) draws every
layer of the surface along each pixel's ray, lit and coloured as the opaque surface
would be, composited front to back; several surfaces are merged by depth, so where
f = g the crossing is exact to the pixel, whatever order they are given in.
"""
import math

import sympy

import floatcol as fc
from floatcol.sympy_backend import SympyBackend

# Gordon's test function, half transparent: the folds behind the ridges show
fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(800, 600), elev=35, azim=30,
          opacity=0.45, cmap="plasma").save("gordon_translucent.png")

# sin(u) cos(v) and its Taylor polynomial of degree 3 at the origin, both translucent:
# they agree near the origin and part ways toward the corners
u, v = sympy.symbols("u v")
f = sympy.sin(u) * sympy.cos(v)
taylor = sympy.series(sympy.sin(u), u, 0, 4).removeO() * sympy.series(
    sympy.cos(v), v, 0, 3).removeO()
fc.render_many([fc.Layer(f, ((-2.5, 2.5), (-2.5, 2.5)),
                         fc.Material(cmap="viridis", opacity=0.55)),
                fc.Layer(sympy.expand(taylor), ((-2.5, 2.5), (-2.5, 2.5)),
                         fc.Material(upper_color="tomato", lower_color="firebrick",
                                     opacity=0.55))],
               size=(800, 600), elev=25, azim=-40).save("taylor_translucent.png")

# sympy's own call form: two surfaces, alpha for both
x, y = sympy.symbols("x y")
p = sympy.plotting.plot3d(sympy.cos(x * y), x ** 2 / 8 - y ** 2 / 8, (x, -3, 3), (y, -3, 3),
                          backend=SympyBackend, show=False, alpha=0.6, cmap="coolwarm",
                          title="cos(xy) and (x^2 - y^2)/8, alpha = 0.6")
p.save("plot3d_alpha.png")

# matplotlib's own call form and idiom: a translucent mesh with its edges, every
# layer's lines showing through
from mpl_toolkits.mplot3d import axes3d  # noqa: E402

X, Y, Z = axes3d.get_test_data(0.05)
fc.plot_surface(X, Y, Z, edgecolor="royalblue", lw=0.5, rstride=8, cstride=8, alpha=0.3,
                size=(800, 600)).save("mesh_alpha_edges.png")

# a glass hill in a ring of trees: those behind it show through, their shadows fall on
# it, soft under a sun 1 degree in radius
trees = [fc.tree(2.4 * math.cos(k * math.pi / 5), 2.4 * math.sin(k * math.pi / 5), 1.5)
         for k in range(10)] + [fc.box(0, 0, 0.8, 0.8, 0.6, color="firebrick")]
fc.render("2.5*exp(-(u**2 + v**2)/2.5)", u=(-3.5, 3.5), v=(-3.5, 3.5), size=(800, 500),
          elev=18, azim=25, opacity=0.45, cmap="cividis", objects=trees, shadows=True,
          lightsource=(300, 35), light_radius=1.0).save("glass_hill.png")
