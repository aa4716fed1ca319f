"""The column pass on an NVIDIA GPU: device="cuda", the same picture as the CPU's.

Each pixel column runs on a GPU thread of its own, with the very column code the CPU
runs compiled for the GPU (docs/cuda.md): a function surface, and a fly-through over
matplotlib's Jacksboro DEM (the ray march's point samples and the level-of-detail
engine's area weights). On a machine without a GPU (or without
``pip install "floatcol[cuda]"``) the CPU draws them, and the file names say which did.
"""
from matplotlib.cbook import get_sample_data

import floatcol as fc
from floatcol.kernels.cuda import check_device

try:
    check_device()
    device = "cuda"
except ValueError as exc:
    print(f"drawing on the CPU: {exc}")
    device = "cpu"

r = fc.render("exp(-(u**2 + v**2)/8)*cos(u)*sin(v)*3", u=(-6, 6), v=(-6, 6), size=(960, 540),
              projection="perspective", elev=35, azim=-30, cmap="viridis", device=device)
r.save(f"gpu_{device}.png")

# a fly-through's frame: the ray march (point sampled) and the lod engine (area sampled)
dem = fc.read_dem(get_sample_data("jacksboro_fault_dem.npz", asfileobj=False), vert_exag=2.0)
cam = fc.fly(dem, (15000.0, 2500.0), heading=15, pitch=-10, fov=55, size=(960, 540), above=900)
for aa in (False, "area"):
    r = fc.render(dem, **cam, antialias=aa, cmap="gist_earth", lightsource=(315, 35),
                  background="lightskyblue", device=device)
    r.save(f"gpu_fly_{r.stats['geometry']}_{device}.png")
