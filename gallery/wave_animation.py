"""A time-varying surface: a circular wave, 36 frames written as a GIF.

The expression uses t; animate() compiles it once and renders every frame with one
camera and one colour scale.
"""
import math

import floatcol as fc

fc.animate("exp(-(x^2 + y^2)/10) * cos(2*sqrt(x^2 + y^2) - t)", ("x", -6, 6), ("y", -6, 6),
           t=(0, 2 * math.pi), frames=36, fps=18, size=(400, 300), cmap="magma",
           elev=35, output="wave.gif")
