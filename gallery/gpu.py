"""The column pass on an NVIDIA GPU: device="cuda", the same picture as the CPU's.

Each pixel column runs on a GPU thread of its own, with the very column code the CPU
runs compiled for the GPU (docs/cuda.md). On a machine without a GPU (or without
``pip install "floatcol[cuda]"``) the CPU draws it, and the picture says which did.
"""
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
