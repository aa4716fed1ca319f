"""A floating horizon line drawing (Gordon's App. A.1): 120 hidden-line-removed curves.

Lines on the upper side are dark, on the lower side red.
"""
import floatcol as fc

fc.plot_surface("sin(x*y)", ("x", -3, 3), ("y", -3, 3), method="horizon", lines=120,
                proj_type="ortho", elev=35, azim=-60).save("horizon_lines.png")
