"""floatcol: shaded pictures of w = f(u, v) by Gordon's floating column algorithm."""
from .animate import Animation, animate
from .compose import composite, render_many
from .plot import SurfacePlot, plot_surface
from .render import Render, render
from .surface import HeightField, Surface, as_surface
from .view import View

__version__ = "0.2.0"


def __getattr__(name):
    # the sympy backend subclasses sympy's Plot: import it only when asked for
    if name == "SympyBackend":
        from .sympy_backend import SympyBackend
        return SympyBackend
    raise AttributeError(f"module 'floatcol' has no attribute {name!r}")


__all__ = ["Animation", "HeightField", "Render", "Surface", "SurfacePlot", "SympyBackend",
           "View", "__version__", "animate", "as_surface", "composite", "plot_surface", "render",
           "render_many"]
