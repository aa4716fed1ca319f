"""floatcol inside a matplotlib figure: subplots, titles and a colorbar.

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
