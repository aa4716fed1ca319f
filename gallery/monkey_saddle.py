"""The monkey saddle w = x^3 - 3 x y^2: three valleys, for two legs and a tail."""
import floatcol as fc

fc.plot_surface("x^3 - 3*x*y^2", ("x", -1.5, 1.5), ("y", -1.5, 1.5), cmap="cividis",
                elev=35, azim=-35).save("monkey_saddle.png")
