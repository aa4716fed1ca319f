"""Lighting: the default key light, matplotlib's LightSource, and no shading.

One surface drawn three ways; `shade=False` gives flat colours as in matplotlib.
"""
from matplotlib.colors import LightSource

import floatcol as fc

expr, rng = "cos(x)*cos(y)*exp(-(x^2 + y^2)/16)", (("x", -7, 7), ("y", -7, 7))
fc.plot_surface(expr, *rng, size=(480, 360)).save("light_default.png")
fc.plot_surface(expr, *rng, size=(480, 360),
                lightsource=LightSource(azdeg=90, altdeg=20)).save("light_east.png")
fc.plot_surface(expr, *rng, size=(480, 360), shade=False).save("light_none.png")
