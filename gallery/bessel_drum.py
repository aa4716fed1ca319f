"""A drum's vibration modes J_m(k r) cos(m phi) on the unit disk, k a zero of J_m so
that the rim stays still: Bessel functions of a whole order in a formula (besselj, as
sympy and scipy's jv), the disk cut out with where(...), four modes in mplot3d's axes.
"""
import matplotlib.pyplot as plt

import floatcol as fc

# (m, the n-th zero of J_m): the mode with m nodal diameters and n nodal circles
MODES = [(0, 2.404826), (0, 5.520078), (1, 3.831706), (2, 5.135622)]

fig = plt.figure(figsize=(10, 8))
for i, (m, k) in enumerate(MODES):
    ax = fig.add_subplot(2, 2, i + 1, projection="3d")
    r = "sqrt(x^2 + y^2)"
    mode = f"where(x^2 + y^2 <= 1, besselj({m}, {k}*{r}) * cos({m}*atan2(y, x)), nan)"
    fc.plot_surface(mode, ("x", -1, 1), ("y", -1, 1), ax=ax, cmap="RdBu_r", vmin=-0.6,
                    vmax=0.6)
    ax.set_zlim(-1, 1)
    ax.set_box_aspect((1, 1, 0.6), zoom=1.3)
    ax.set_title(f"$J_{m}({k:.4f}\\,r)\\,\\cos {m}\\phi$")
    ax.set_axis_off()
fig.tight_layout()
fig.savefig("bessel_drum.png")
