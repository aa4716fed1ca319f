"""A real terrain: the Jacksboro fault DEM shipped with matplotlib, as a HeightField.

344 x 403 heights at 3 arc-second spacing, read as a bilinear function and drawn
with 3x vertical exaggeration (in true proportions otherwise: aspect="equal") and a
matplotlib LightSource from the north-west.
"""
import numpy as np
from matplotlib.cbook import get_sample_data
from matplotlib.colors import LightSource

import floatcol as fc

dem = get_sample_data("jacksboro_fault_dem.npz")
z = dem["elevation"][::-1].astype(float)            # rows from south to north
lat = np.radians(0.5 * (dem["ymin"] + dem["ymax"]))
km_x = dem["dx"] * 111.32 * np.cos(lat)               # km per column
km_y = dem["dy"] * 110.57                             # km per row
ny, nx = z.shape
terrain = fc.HeightField(3 * z / 1000.0, u=(0, (nx - 1) * km_x), v=(0, (ny - 1) * km_y))

fc.plot_surface(terrain, cmap="gist_earth", lightsource=LightSource(azdeg=315, altdeg=35),
                elev=35, azim=-110, size=(1000, 600), aspect="equal").save("terrain.png")
