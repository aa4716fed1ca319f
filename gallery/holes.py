"""Holes: where f is NaN, infinite or complex there is no surface, and edges stay clean.

The annulus sqrt(4 - r^2) + sqrt(r^2 - 1) - 2 is complex inside r = 1 and outside
r = 2, with vertical walls at both rims; drawn in true proportions (aspect="equal").
"""
import floatcol as fc

fc.plot_surface("sqrt(4 - x^2 - y^2) + sqrt(x^2 + y^2 - 1) - 2", ("x", -2.2, 2.2),
                ("y", -2.2, 2.2), cmap="viridis", elev=40, aspect="equal").save("holes.png")
