"""Shadows (Gordon section 6.2): a low sun over the Jacksboro fault DEM, Gordon's test
function lit from the side, a pillar's soft shadow, and a sun that moves over a bump.

``shadows=True`` adds the attached shadows (a side facing away from the sun gets
ambient light only) and the cast ones (section 6.2.1's shadow texture: floating-horizon
sweeps over the domain along the sun's ground direction). The sun is matplotlib's
LightSource(azdeg, altdeg), fixed to the surface: it stays where it is as the camera
turns. ``light_radius`` makes the sun a disk of that angular radius (soft shadows);
``shadows="on-the-fly"`` is section 6.2.2's method, without a texture. Objects standing
on the surface (fc.box, fc.pole, fc.tree, fc.marker) cast shadows and take them.
"""
import numpy as np
from matplotlib.cbook import get_sample_data

import floatcol as fc

# a terrain at low sun: 10 degrees above the horizon, from the west
dem = get_sample_data("jacksboro_fault_dem.npz")
z = dem["elevation"][::-1].astype(float)            # rows from south to north
lat = np.radians(0.5 * (dem["ymin"] + dem["ymax"]))
km_x = dem["dx"] * 111.32 * np.cos(lat)
km_y = dem["dy"] * 110.57
ny, nx = z.shape
terrain = fc.HeightField(3 * z / 1000.0, u=(0, (nx - 1) * km_x), v=(0, (ny - 1) * km_y))
fc.plot_surface(terrain, cmap="gist_earth", lightsource=(270, 10), shadows="on-the-fly",
                elev=40, azim=-110, size=(1000, 600), aspect="equal").save("terrain_low_sun.png")

# Gordon's test function: its ridges cast their shadows on the valleys
for shadows in (False, True):
    fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(800, 600), elev=50, azim=30,
              lightsource=(200, 40), shadows=shadows, cmap="cividis", ambient=0.35).save(
        "gordon_shadows.png" if shadows else "gordon_no_shadows.png")

# a pillar on a plain at a 22 degree sun, 2.5 degrees in radius: the shadow is sharp at
# the pillar's foot and blurs with the distance from it
pillar = "Piecewise((2, (Abs(u) < 0.25) & (Abs(v) < 0.25)), (0.6*exp(-((u+1.5)**2 + (v-1)**2)), True))"
fc.render(pillar, u=(-3, 3), v=(-2, 2.5), size=(800, 600), elev=55, azim=20,
          lightsource=(250, 22), shadows=True, light_radius=2.5, upper_color="0.85",
          ambient=0.3, specular=0.0).save("soft_shadow.png")

# objects on a gentle surface: each casts its shadow on the ground and on the others
# (the small tree stands in the big one's shadow)
objects = [fc.box(-1, 0, 1, 1, 1.5, color="firebrick"), fc.pole(1.5, 1, 2.0, color="white"),
           fc.tree(0, -2, 2.0), fc.marker(2, -1, 0.5), fc.tree(0.6, -1.0, 1.2)]
fc.render("0.2*sin(u)*cos(v)", u=(-4, 4), v=(-4, 4), size=(800, 500), elev=35, azim=20,
          projection="perspective", lightsource=(300, 30), shadows=True,
          objects=objects).save("object_shadows.png")

# a moving sun: a day over two bumps
fc.animate("2*exp(-((x-1)**2+y**2)) + exp(-((x+1.5)**2+(y-1)**2)/0.5) + 0*t",
           ("x", -4, 4), ("y", -4, 4), t=(60, 300), frames=24, size=(400, 300),
           lightsource=lambda t: (t, 15 + 30 * np.sin(np.radians(t - 60) * 0.75)),
           shadows=True, output="moving_sun.gif", progress=False)
