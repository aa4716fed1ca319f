"""Discontinuities: a staircase whose risers are drawn as vertical walls.

floor(x + y/2) jumps by one on the lines x + y/2 = k. The floating column finds each
jump between two samples, halves the span until it is located, and shades the rows
between the two treads as a wall facing its own way (the end of Gordon's section 5,
which the paper left unimplemented). Next to it the same surface with wall detection
off: the risers are smeared with the treads' normals.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import floatcol as fc  # noqa: E402

fig, axes = plt.subplots(1, 2, figsize=(10, 4.6))
for ax, detect, title in ((axes[0], None, "walls detected (default)"),
                          (axes[1], ("ridge", "intensity"), "detect=('ridge', 'intensity')")):
    fc.plot_surface("floor(x + y/2)", ("x", -2, 2), ("y", -2, 2), ax=ax, detect=detect,
                    elev=35, azim=-120, cmap="viridis")
    ax.set_title(title)
    ax.set_axis_off()
fig.savefig("walls.png", dpi=100)
