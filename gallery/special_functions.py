"""Special functions of physics in formulas, with scipy's and sympy's names: an Airy
beam Ai(x) Ai(y) (airyai); light behind a straight edge, Fresnel's diffraction
pattern over the distance behind it (fresnelc, fresnels); the sine integral Si(x y)
(a filter's step response); and a pendulum's period against its amplitude and
length, 4 sqrt(L/g) K(sin^2(theta/2)) (ellipk, the complete elliptic integral).
Four panels in mplot3d's axes.
"""
import matplotlib.pyplot as plt

import floatcol as fc

PANELS = [
    ("an Airy beam  Ai(x) Ai(y)", "airyai(x) * airyai(y)", (-9, 3), (-9, 3), "viridis"),
    ("a straight edge's diffraction  |E|^2 (Fresnel)",
     "((fresnelc(x / sqrt(y)) + 0.5)^2 + (fresnels(x / sqrt(y)) + 0.5)^2) / 2",
     (-3, 4), (1, 4), "inferno"),
    ("the sine integral  Si(x y)", "Si(x * y)", (-4, 4), (-4, 4), "RdBu_r"),
    ("a pendulum's period (s) by amplitude (rad) and length (m)",
     "4 * sqrt(y / 9.81) * ellipk(sin(x / 2)^2)", (0, 3), (0.2, 2), "cividis"),
]

fig = plt.figure(figsize=(10, 8))
for i, (title, expr, xr, yr, cmap) in enumerate(PANELS):
    ax = fig.add_subplot(2, 2, i + 1, projection="3d")
    fc.plot_surface(expr, ("x", *xr), ("y", *yr), ax=ax, cmap=cmap)
    ax.view_init(30, -60 if i != 1 else -110)
    ax.set_title(title, fontsize=10)
fig.tight_layout()
fig.savefig("special_functions.png")
