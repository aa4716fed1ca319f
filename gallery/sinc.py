"""The 2-D sinc, sin(r)/r: the removable singularity at r = 0 is no hole.

sympy's sinc evaluates to 1 at the origin, so the peak is drawn whole.
"""
import sympy as sp

import floatcol as fc

x, y = sp.symbols("x y")
r = sp.sqrt(x**2 + y**2)
fc.plot_surface(sp.sinc(r), (x, -12, 12), (y, -12, 12), cmap="plasma", elev=25,
                azim=-50).save("sinc.png")
