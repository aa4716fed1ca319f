"""floatcol inside a matplotlib figure: subplots, titles and a colorbar; heights
that span decades on a log colour scale (norm="log").

Each surface is an artist in an ordinary Axes; it is rendered again at the Axes'
pixel size whenever the figure is drawn, so savefig(dpi=200) is sharp.
"""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import floatcol as fc

fig, axes = plt.subplots(1, 3, figsize=(12, 4), layout="constrained")
specs = [("sin(x)*cos(y)", "sin x cos y"), ("x*y*exp(-(x^2 + y^2)/8)", "x y exp(-r²/8)"),
         ("cos(sqrt(x^2 + y^2))", "cos r")]
for ax, (expr, title) in zip(axes, specs):
    plot = fc.plot_surface(expr, ("x", -4, 4), ("y", -4, 4), ax=ax, cmap="viridis",
                           vmin=-1, vmax=1)
    ax.set_title(title)
fig.colorbar(plot, ax=axes, shrink=0.8, label="height w")
fig.savefig("matplotlib_subplots.png", dpi=100)

# heights that span decades, coloured on a log scale: matplotlib's norm="log" (a
# scale's name, or a LogNorm), its colorbar logarithmic too; a NumPy-style formula
fig, ax = plt.subplots(figsize=(6, 4.5), layout="constrained")
plot = fc.plot_surface("np.exp(np.hypot(x, y))", ("x", -4, 4), ("y", -4, 4), ax=ax,
                       cmap="magma", norm="log")
ax.set_title("exp(r), norm=\"log\"")
fig.colorbar(plot, ax=ax, shrink=0.8, label="height w (log scale)")
fig.savefig("matplotlib_log_norm.png", dpi=100)
