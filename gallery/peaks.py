"""MATLAB's peaks function, with matplotlib's default view and colormap.

plot_surface takes sympy plot3d's ranges and matplotlib's option names.
"""
import sympy as sp

import floatcol as fc

x, y = sp.symbols("x y")
peaks = (3 * (1 - x)**2 * sp.exp(-x**2 - (y + 1)**2)
         - 10 * (x / 5 - x**3 - y**5) * sp.exp(-x**2 - y**2)
         - sp.exp(-(x + 1)**2 - y**2) / 3)

fc.plot_surface(peaks, (x, -3, 3), (y, -3, 3), cmap="viridis").save("peaks.png")
