"""Ripples exp(-r^2) cos(3 r) seen from low down: the rings hide one another.

Occlusion is exact per pixel column; there is no mesh to make facets.
"""
import floatcol as fc

fc.plot_surface("exp(-(x^2 + y^2)/4) * cos(3*sqrt(x^2 + y^2))", ("x", -4, 4), ("y", -4, 4),
                cmap="ocean", vmin=-1.2, vmax=1.0, elev=15, azim=-60,
                size=(900, 500)).save("ripples.png")
