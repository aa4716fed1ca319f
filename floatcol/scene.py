"""Scene: what a picture shows (pyrender's scene): layers (a surface, its domain and
its material), one light, a camera, quality settings and a background.

>>> import floatcol as fc
>>> scene = fc.Scene([fc.Layer("u*v/3", material=fc.Material(cmap="magma")),
...                   fc.Layer("2*exp(-u**2-v**2)", ((-2, 2), (-2, 2)),
...                            fc.Material(cmap="Blues"))],
...                  camera=fc.Camera(size=(160, 120), elev=30, azim=30))
>>> fc.render_scene(scene).rgba.shape
(120, 160, 4)

``render`` and ``render_many`` build a Scene from their keywords and run it
(floatcol/renderer.py).
"""
from __future__ import annotations

import inspect
from dataclasses import dataclass, field
from typing import Any

from .camera import Camera
from .material import Material
from .quality import Quality


@dataclass
class Layer:
    """One surface of a scene: ``surface`` (an expression, a callable, a Surface or a
    HeightField), its ``domain`` ((u_low, u_high), (v_low, v_high)); None: (-10, 10)
    each, or a HeightField's extent) and its ``material``."""
    surface: Any
    domain: Any = None
    material: Material = field(default_factory=Material)


@dataclass
class Scene:
    """``layers`` (a list of Layer), ``camera``, ``light`` (a floatcol.Light, a screen
    direction, or None: each material's shading's own), ``quality``, ``background``
    (None: white, black behind shading="lambert"), and ``vars``: the names of the
    expressions' two variables (default u and v)."""
    layers: list
    camera: Camera = field(default_factory=Camera)
    light: Any = None
    quality: Quality = field(default_factory=Quality)
    background: Any = None
    vars: Any = None
    #: objects standing on the first surface (floatcol.objects: box, pole, tree,
    #: marker or a Mesh), drawn by z-buffer against its depth (Szenberg 1997)
    objects: Any = ()


#: render()'s keywords that are a material's, a camera's and a quality's
MATERIAL_OPTIONS = frozenset(inspect.signature(Material).parameters)
CAMERA_OPTIONS = frozenset(inspect.signature(Camera).parameters)
QUALITY_OPTIONS = frozenset(inspect.signature(Quality).parameters)


def scene_from_options(surfaces, **options):
    """The Scene of render()'s flat keywords: ``surfaces`` a list of Layers or of
    (expr, u, v) triples or expressions (those take the material the keywords
    describe); the keywords split into material, camera, quality, light, background
    and vars. ``opacity`` may be a list, one value a surface. An unknown keyword is a
    TypeError, as a function's."""
    material = {k: options.pop(k) for k in list(options) if k in MATERIAL_OPTIONS}
    camera = {k: options.pop(k) for k in list(options) if k in CAMERA_OPTIONS}
    quality = {k: options.pop(k) for k in list(options) if k in QUALITY_OPTIONS}
    light = options.pop("light", None)
    lightsource = options.pop("lightsource", None)
    shadows = options.pop("shadows", False)
    radius = options.pop("light_radius", 0.0)
    if lightsource is not None or shadows or radius:
        from .light import as_light
        light = as_light(light, material.get("shading", "default"), lightsource, shadows,
                         radius)
    background = options.pop("background", None)
    vars = options.pop("vars", None)
    objects = options.pop("objects", ())
    if options:
        raise TypeError(f"unexpected options {', '.join(sorted(options))}")
    opacities = _per_surface("opacity", material.pop("opacity", 1.0), len(surfaces))
    shared = Material(**material, opacity=opacities[0] if opacities else 1.0)
    layers = []
    for item, opacity in zip(surfaces, opacities):
        mat = shared if opacity is shared.opacity else Material(**material, opacity=opacity)
        if isinstance(item, Layer):
            layers.append(item)
        elif isinstance(item, tuple) and len(item) == 3:
            layers.append(Layer(item[0], (item[1], item[2]), mat))
        else:
            layers.append(Layer(item, None, mat))
    return Scene(layers, camera=Camera(**camera), light=light, quality=Quality(**quality),
                 background=background, vars=vars, objects=objects or ())


def _per_surface(name, value, n):
    """A keyword given once for all surfaces or as a list of one value each."""
    if isinstance(value, (list, tuple)) or (hasattr(value, "__len__") and
                                            not isinstance(value, (str, bytes))):
        values = list(value)
        if len(values) != n:
            raise ValueError(f"{name} must be one value or a list of one per surface "
                             f"({n}), got {len(values)} values")
        return [v.item() if hasattr(v, "item") else v for v in values]
    return [value] * n
