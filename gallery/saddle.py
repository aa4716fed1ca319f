"""The saddle w = x^2 - y^2 in an orthographic view, coloured by height."""
import floatcol as fc

fc.plot_surface("x^2 - y^2", ("x", -2, 2), ("y", -2, 2), proj_type="ortho",
                cmap="coolwarm", elev=35, azim=-55).save("saddle.png")
