"""Several surfaces in one picture: one camera for all, composited by depth.

render_many builds a Scene of several layers (floatcol/scene.py) and runs it: each
layer is rendered from the same camera (the scale, centre and, in perspective, d1/d2
fitted to all of them together, camera.fit) over a transparent background, with its
own material; the composite pass (passes/composite.py) then combines them per pixel
front to back by the depth of the surface seen at the pixel's centre, so the surfaces
hide each other correctly where they overlap or cross.
"""
from __future__ import annotations

from .passes.composite import composite  # noqa: F401 (public: fc.composite)
from .renderer import render_scene
from .result import Render
from .scene import scene_from_options

def render_many(surfaces, size=(400, 300), elev=30.0, azim=30.0, projection="orthographic",
                d1=None, d2=None, scale=None, center=None, *, background=None, vars=None,
                focal_length=None, tiles=None, client=None, **options) -> Render:
    """Render several surfaces w = f(u, v) into one picture.

    Parameters
    ----------
    surfaces : a list of expressions (strings, sympy expressions, callables, Surfaces
        or HeightFields), of (expr, u, v) triples giving each its own domain, or of
        :class:`floatcol.Layer` giving each its own domain and material (its own
        colormap, colours, lighting terms).
    size, elev, azim, projection, d1, d2, scale, center, focal_length : the one camera,
        as :func:`floatcol.render`; left as None they are fitted to all the surfaces.
    background : the picture's background (default white, black for
        shading="lambert").
    **options : any other :func:`floatcol.render` option: the material of every surface
        not given as a Layer (shading, cmap, vmin, vmax, ...), and the light, quality
        and box of all (light, antialias, corrections, aspect, ...). Each surface takes
        the colormap over its own seen heights unless vmin/vmax say otherwise.
    tiles, client : the picture in ``tiles`` bands of columns, drawn one after the
        other or as tasks on ``client`` (a dask.distributed Client), as
        :func:`floatcol.render`'s: the same picture, array for array, each surface's
        colormap over the heights it shows in the whole picture (floatcol/cluster.py).

    Returns
    -------
    Render
        the composite: ``rgba``, and ``intensity``, ``side``, ``depth``, ``u``, ``v``,
        ``w``, ``normal`` of the nearest surface at each pixel; ``stats["samples"]``
        and ``["seconds"]`` of all of them, ``stats["surface"]`` (H, W) int8 the index of
        the surface seen at each pixel (-1: none).
    """
    if isinstance(surfaces, (str, bytes)) or not hasattr(surfaces, "__iter__"):
        raise ValueError("surfaces must be a list of expressions or of (expr, u, v) triples, "
                         f"got {surfaces!r}")
    if tiles is not None or client is not None:
        from .cluster import render_tiled
        options = dict(options, size=size, elev=elev, azim=azim, projection=projection,
                       d1=d1, d2=d2, scale=scale, center=center, background=background,
                       vars=vars, focal_length=focal_length)
        return render_tiled(list(surfaces), options, tiles, client, composite=True)
    try:
        scene = scene_from_options(list(surfaces), size=size, elev=elev, azim=azim,
                                   projection=projection, d1=d1, d2=d2, scale=scale,
                                   center=center, background=background, vars=vars,
                                   focal_length=focal_length, **options)
    except TypeError as exc:
        raise TypeError(f"render_many() got {exc}") from None
    return render_scene(scene, stacklevel=2, composite=True)
