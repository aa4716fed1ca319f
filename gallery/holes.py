"""Holes: where f is NaN, infinite or complex there is no surface, and edges stay clean.

w = sqrt(4 - x^2 - y^2) is complex outside the disc, and log|x y| is -inf on the axes.
"""
import floatcol as fc

fc.plot_surface("sqrt(4 - x^2 - y^2) + sqrt(x^2 + y^2 - 1) - 2", ("x", -2.2, 2.2),
                ("y", -2.2, 2.2), cmap="viridis", elev=40).save("holes_ring.png")
fc.plot_surface("log(abs(x*y))", ("x", -2, 2), ("y", -2, 2), cmap="cividis",
                elev=30).save("holes_log.png")
