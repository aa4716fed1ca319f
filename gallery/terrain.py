"""A real terrain from its file in one call: matplotlib's Jacksboro fault DEM.

fc.terrain reads the .npz (rows north to south, 3 arc-second cells: degrees become
metres), exaggerates the heights until the relief shows (vert_exag="auto": 3.7x here),
and draws it in true proportions with an earth colormap, a sun from the north-west
(matplotlib's LightSource) and Cohen-Or's exact area sampling. The second picture
lights it low from the west with shadows, and puts a sea level at 350 m through a
TwoSlopeNorm on the "terrain" colormap (its coast at the norm's centre).
"""
from matplotlib.cbook import get_sample_data
from matplotlib.colors import TwoSlopeNorm

import floatcol as fc

path = get_sample_data("jacksboro_fault_dem.npz", asfileobj=False)
fc.terrain(path).save("terrain.png")

# heights x3: the sea level at 350 m is at 1050 on the colormap
plot = fc.terrain(path, vert_exag=3, cmap="terrain", norm=TwoSlopeNorm(vcenter=350 * 3),
                  lightsource=(270, 20), shadows=True, elev=25, azim=-130, size=(800, 480))
plot.save("terrain_shadows.png")
