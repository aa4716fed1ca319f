"""floatcol: shaded pictures of w = f(u, v) by Gordon's floating column algorithm."""
from .animate import Animation, animate
from .camera import Camera, fly
from .compose import composite, render_many
from .light import Light
from .material import Material
from .quality import Quality
from .renderer import render_scene
from .scene import Layer, Scene
from .plot import SurfacePlot, plot_surface, plot_trisurf, plot_wireframe
from .render import Render, render
from .surface import HeightField, Surface, as_surface
from .terrain import fly_through, lonlat, read_dem, terrain
from .objects import Mesh, box, marker, pole, tree
from .view import View

__version__ = "0.2.0"


def __getattr__(name):
    # the sympy backend subclasses sympy's Plot: import it only when asked for
    if name == "SympyBackend":
        from .sympy_backend import SympyBackend
        return SympyBackend
    raise AttributeError(f"module 'floatcol' has no attribute {name!r}")


__all__ = ["Animation", "Camera", "HeightField", "Layer", "Light", "Material", "Mesh", "Quality",
           "Render", "Scene", "Surface", "SurfacePlot", "SympyBackend", "View", "__version__",
           "animate", "as_surface", "box", "composite", "fly", "fly_through", "lonlat", "marker",
           "pole", "tree", "plot_surface", "plot_trisurf", "plot_wireframe", "read_dem", "render",
           "render_many", "render_scene", "terrain"]
