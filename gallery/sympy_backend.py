"""sympy's plot3d drawn by floatcol: pass backend=floatcol.SympyBackend."""
import sympy as sp
from sympy.plotting import plot3d

import floatcol as fc

x, y = sp.symbols("x y")
p = plot3d(sp.cos(x) * sp.sin(y) * sp.exp(-(x**2 + y**2) / 20), (x, -6, 6), (y, -6, 6),
           backend=fc.SympyBackend, show=False, title="plot3d(..., backend=SympyBackend)",
           cmap="viridis", elev=40)
p.save("sympy_backend.png")
