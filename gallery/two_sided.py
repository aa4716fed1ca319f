"""A two-sided surface: the upper side in one colour, the lower side in another.

w = sin(x) cos(y) seen from below the rim, so both sides show.
"""
import floatcol as fc

fc.plot_surface("2*sin(x)*cos(y)", ("x", -4, 4), ("y", -4, 4), color="#4c78a8",
                lower_color="#f58518", elev=8, azim=-70).save("two_sided.png")
