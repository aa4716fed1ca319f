"""floatcol: shaded pictures of w = f(u, v) by Gordon's floating column algorithm."""
from .render import Render, render
from .surface import HeightField, Surface, as_surface
from .view import View

__version__ = "0.1.0"
__all__ = ["render", "Render", "Surface", "HeightField", "as_surface", "View", "__version__"]
