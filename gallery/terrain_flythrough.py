"""A fly-through over a real DEM: read from its file, draped, with trees and a tower.

matplotlib's Jacksboro fault DEM (3 arc-seconds, rows north to south) read with
read_dem (degrees become metres), its colour relief draped as the texture (a stand-in
for an orthophoto), a sun from the north-west casting shadows, trees, a mast and a
house standing on the ground (a z-buffer against the terrain's depth, Szenberg 1997),
and a camera flying north over the valley along a smooth curve through three waypoints
(fc.fly_through; Guedes 1997's tilted view plane). The terrain is area-sampled
(Cohen-Or 1997): dense ridges in the distance do not flicker; lit smooth
(smooth_shading=True): the DEM's 90 m cells near the camera are not facets.
A point-sampled preview of the first frame (antialias=False) is drawn by fc.fly's ray
march (each pixel's ray marched through the same planes, 1.5 to 3 times as fast).
"""
import numpy as np
from matplotlib import colormaps
from matplotlib.cbook import get_sample_data
from matplotlib.colors import LightSource

import floatcol as fc

path = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)
dem = fc.read_dem(path, vert_exag=2.0)          # heights x2: the relief shows from the air

# the "photo": colour relief under a low sun (rows as the HeightField's: south first)
relief = LightSource(azdeg=315, altdeg=30).shade(dem.hf, cmap=colormaps["gist_earth"],
                                                 blend_mode="soft", vert_exag=2)

rng = np.random.default_rng(1)
objects = [fc.tree(u, v, 120.0) for u, v in rng.uniform((13000, 6000), (17000, 11000), (60, 2))]
objects += [fc.pole(15200, 9000, 700.0, color="white"),
            fc.box(14600, 7200, 300, 200, 150, color="firebrick", heading=25)]

# the flight: a smooth curve through three waypoints, 900 m above the ground at each
# (never nearer it than half that between them), looking along the curve
fc.fly_through(dem, [(15000, 2500), (15400, 6000), (17000, 9500)], frames=12,
               size=(320, 180), above=900, pitch=-10, fov=55, vert_exag=1,
               texture=relief, shadows=True, objects=objects, background="lightskyblue",
               ambient=0.4, fps=6, output="terrain_flythrough.gif", progress=False)
fc.render(dem, **fc.fly(dem, (15000.0, 2500.0), heading=15, pitch=-10, fov=55,
                        size=(480, 270), above=900),
          texture=relief, antialias="area", lightsource=(315, 35), shadows=True,
          objects=objects, background="lightskyblue", ambient=0.4,
          smooth_shading=True).save("terrain_fly.png")
# a point-sampled preview (antialias=False): fc.fly's ray march (docs/terrain.md)
preview = fc.fly(dem, (15000.0, 2500.0), heading=15, pitch=-10, fov=55, size=(480, 270),
                 above=900)
fc.render(dem, **preview, texture=relief, antialias=False, lightsource=(315, 35), shadows=True,
          objects=objects, background="lightskyblue", ambient=0.4,
          smooth_shading=True).save("terrain_fly_preview.png")
