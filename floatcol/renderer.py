"""The renderer: a scene in, a Render out, as a sequence of passes (floatcol/passes/).

    render_scene(scene)
      fit       camera.fit: one View per layer, the same camera for all
      draft      a fresh install's first pictures, while the kernels compile
                 (passes/draft.py, warmup.py)
      per layer:
        geometry   the column pass (passes/geometry.py)
        horizon    method="horizon": the line drawing (passes/horizon.py)
        finish     its material's light and colour (passes/finish.py)
        antialias  staircases or sub-columns (passes/antialias.py)
      composite  several layers merged by depth (passes/composite.py)

A new pass goes in passes/ and is called here; a light kind in light.py; a material
field in material.py and the pass that reads it (docs/architecture.md).
"""
from __future__ import annotations

import time
import warnings
from dataclasses import dataclass

from . import color
from .camera import fit
from .light import as_light
from .passes import (antialias, area, colour, draft, finish, geometry, horizon, lod, march,
                     normals, overlays, shadow as shadows)
from .passes.composite import composite as merge
from .passes.translucency import render_translucent
from .kernels import layout as L
from .kernels.shade import INTERP_INTENSITY
from .result import Render
from .surface import as_surface, check_range
from .view import nowhere_finite

DEFAULT_RANGE = (-10.0, 10.0)   # as sympy's plot3d


@dataclass
class _Prepared:
    """A layer checked and ready for its passes."""
    surface: object             # as given (the warning's units)
    domain: tuple
    material: object
    light: object               # the Light
    light_dir: object
    terms: tuple                # (ambient, specular, shininess)
    source: object = None       # the texture or colour field (passes/colour.py)


def render_scene(scene, stacklevel=2, composite=False) -> Render:
    """Run a Scene's passes: one layer is a picture of its own; several (or one with
    ``composite``) are rendered from one camera over a transparent background and
    composited by depth (Render.stats["surface"]: the layer seen at each pixel); then
    the scene's objects, by z-buffer (floatcol/objects.py)."""
    t_start = time.perf_counter()
    objects = _objects(scene.objects)            # (checked before the work)
    out, texture = _render_layers(scene, stacklevel + 1, composite, t_start, objects)
    if objects:
        from .objects import objects_pass
        first = scene.layers[0]
        light = as_light(scene.light, first.material.shading)
        objects_pass(out, objects, as_surface(first.surface, scene.vars),
                     _screen_light(light, scene.camera.elev, scene.camera.azim), texture,
                     scene.quality.antialiasing(first.material.shading)[0])
        out.stats["seconds"] = time.perf_counter() - t_start
    return out


def _objects(objects):
    """A scene's objects as a list of Mesh, or ValueError."""
    from .objects import Mesh
    if objects is None or (hasattr(objects, "__len__") and len(objects) == 0):
        return []
    bad = ValueError("objects must be a list of fc.box, fc.pole, fc.tree, fc.marker or "
                     "fc.Mesh")
    if isinstance(objects, (str, bytes, Mesh)) or not hasattr(objects, "__iter__"):
        raise bad
    objects = list(objects)
    if not all(isinstance(o, Mesh) for o in objects):
        raise bad
    return objects


def _render_layers(scene, stacklevel, composite, t_start, objects):
    """render_scene's layers: (Render, the light's shadow texture or None). With shadows
    the ``objects`` cast theirs on the layers (the texture's occluders)."""
    quality = scene.quality
    quality.check_method()
    quality.check_device()
    if not scene.layers:
        raise ValueError("surfaces is empty: give at least one expression")
    layers = [_prepare(layer, scene) for layer in scene.layers]
    many = composite or len(layers) > 1
    if len(layers) > 1 and any(not p.material.fill for p in layers):
        raise ValueError("fill=False draws one surface's lines alone: render it by itself "
                         "(several surfaces hide each other with their faces)")
    views, drawn, box = fit([(p.surface, p.domain) for p in layers], scene.camera, quality,
                            layers[0].light_dir, joint=many)
    if scene.camera.columns is not None:
        views = _band(views, scene.camera.columns)
    first = layers[0].material
    background = scene.background
    if background is None:
        background = default_background(quality.method, first.shading)
    light = layers[0].light
    translucent = any(p.material.opacity < 1.0 for p in layers)
    if translucent:
        _check_translucent(layers, quality, light)
    # a fresh install's draft (passes/draft.py) while the kernels compile: decided
    # before the shadow texture, which a draft makes in numpy (passes/draft_shadow.py,
    # a layer per surface); a translucent one (passes/draft_layers.py, every layer's
    # crossings merged by depth, objects seen through them, textures and lines on each
    # crossing); several opaque surfaces are drafted one by one and merged by depth
    drafted = (quality.device == "cpu" and scene.camera.columns is None
               and all(draft.supports(quality, v, d[0]) for v, d in zip(views, drawn))
               and _drafting(quality, first, drawn[0][0], views[0], light))
    texture = _shadow_texture(light, scene.camera, quality, drawn, views[0],
                              sweep=not drafted)
    if texture is not None and objects:
        texture.occluders = _occluders(texture, objects, layers[0].surface, box)
    if drafted and translucent and (many or objects or first.overlaid):
        # several surfaces, one at least translucent, or translucency with objects or
        # lines (each crossing's own alpha)
        stop = None
        if objects:
            from .objects import depth_map
            stop = depth_map(objects, as_surface(scene.layers[0].surface, scene.vars), box,
                             views[0], texture)
        return _draft_translucent(layers, views, drawn, box, background, texture, t_start,
                                  stop), texture
    if drafted and not many:
        return _draft_layer(layers[0], views[0], drawn[0], box, quality, background, t_start,
                            stacklevel + 1, texture), texture
    if translucent:
        stop = None
        if objects:
            # (the objects' depth: where the layers over them stop composing)
            from .objects import depth_map
            stop = depth_map(objects, as_surface(scene.layers[0].surface, scene.vars), box,
                             views[0], texture)
        return render_translucent(layers, views, drawn, box, quality, background, texture,
                                  t_start, stop), texture
    if not many:
        return _layer(layers[0], views[0], drawn[0], box, quality, background, t_start,
                      stacklevel + 1, texture), texture
    renders = []
    for k, (p, view, (s, dom)) in enumerate(zip(layers, views, drawn)):
        if p.light_dir is not layers[0].light_dir:
            view = _relit(view, p.light_dir)
        if drafted:
            renders.append(_draft_layer(p, view, (s, dom), box, quality, (0, 0, 0, 0),
                                        time.perf_counter(), stacklevel + 1, texture, k))
            continue
        renders.append(_layer(p, view, (s, dom), box, quality, (0, 0, 0, 0),
                              time.perf_counter(), stacklevel + 1, texture, k))
    out = merge(renders, color.to_rgba8(background))
    out.stats["seconds"] = time.perf_counter() - t_start
    out.stats["engine"] = "draft" if drafted else "kernels"
    return out, texture


def _check_translucent(layers, quality, light):
    """ValueError for what a translucent picture cannot take."""
    if any(p.material.smooth_shading for p in layers):
        raise ValueError("smooth_shading lights opaque surfaces: use opacity=1 (translucent "
                         "layers are lit by their cells' own normals)")
    if quality.method != "column":
        raise ValueError("opacity below 1 needs shaded pictures: method='column' (a line "
                         "drawing has no layers to blend)")
    if quality.area:
        raise ValueError("antialias='area' needs opaque surfaces: opacity=1 (translucent "
                         "layers are antialiased by their own coverage)")
    if light.shadows and light.shadow_method == "on-the-fly":
        # (every layer looks its shadow up: section 6.2.2's sweep answers the seen
        # pixels of one opaque surface; it was an AttributeError)
        raise ValueError("opacity below 1 takes its shadows from the shadow texture: "
                         "use shadows=True (shadows='on-the-fly' draws one opaque "
                         "surface)")


def _prepare(layer, scene):
    material = layer.material.check()
    surface = as_surface(layer.surface, scene.vars)
    u, v = None, None
    if layer.domain is not None:
        try:
            u, v = layer.domain
        except (TypeError, ValueError):
            raise ValueError("a layer's domain must be ((u_low, u_high), (v_low, v_high)) or "
                             f"None, got {layer.domain!r}") from None
    domain = layer_domain(surface, u, v)
    light = as_light(scene.light, material.shading)
    view_angles = (scene.camera.elev, scene.camera.azim)
    light_dir = _screen_light(light, *view_angles)
    return _Prepared(surface, domain, material, light, light_dir, material.light_terms(),
                     colour.prepare(material, domain, scene.vars or surface.variables))


def _shadow_texture(light, camera, quality, drawn, view, sweep=True):
    """The light's shadow texture over every layer (passes/shadow.py), or None where
    the light casts no shadows; with sweep=False its grid alone (a draft's)."""
    if not light.shadows:
        return None
    if quality.method != "column":
        raise ValueError("shadows need shaded pictures: method='column' (a line drawing "
                         "has no light)")
    from .view import _number
    direction = light.world_direction(_number("elev", camera.elev), _number("azim", camera.azim))
    return shadows.Texture(drawn, view, direction, light.radius, light.shadow_method,
                           sweep=sweep)


def _occluders(texture, objects, surface, box):
    """The objects as casters of the texture's light (objects.Occluders), or None."""
    from .objects import occluders
    if texture.on_the_fly:
        raise ValueError("objects take their shadows from the shadow texture: use "
                         "shadows=True (shadows='on-the-fly' draws one surface's)")
    return occluders(objects, surface, box, texture.light, texture.rho)


def _band(views, columns):
    """The views of columns (first, count) of theirs (a band of a tiled poster,
    floatcol/cluster.py): the same camera, ``count`` columns wide, column c of the band
    at column first + c of the picture (kernels/sample.py column_x0: exactly, the
    offsets being whole and half numbers)."""
    import dataclasses
    try:
        first, count = (int(c) for c in columns)
    except (TypeError, ValueError):
        raise ValueError(f"columns must be (first, count), got {columns!r}") from None
    width = views[0].width
    if not (0 <= first and 1 <= count and first + count <= width):
        raise ValueError(f"columns {first}..{first + count - 1} must lie in the picture's "
                         f"0..{width - 1}")
    return [dataclasses.replace(v, width=count, first_column=first,
                                x_offset=first + 0.5 * (count - width)) for v in views]


def _screen_light(light, elev, azim):
    if light.kind == "directional":
        from .view import _number
        elev, azim = _number("elev", elev), _number("azim", azim)
    return light.screen_direction(elev, azim)


def _relit(view, light_dir):
    """A View of another layer's light (the camera fit's are the first layer's)."""
    import dataclasses

    import numpy as np
    if light_dir is None:
        light = (0.0, 0.0, 0.0)
    else:
        lv = np.array(light_dir, dtype=float)
        light = tuple(lv / np.linalg.norm(lv))
    return dataclasses.replace(view, light=light)


def _textured_columns(surface, view, vp, column, material, source, box, colours, c_limits,
                      bg8, lit):
    """picture(offset) -> (rgba, evals) for antialias.subcolumn_pass: a textured (or
    colour field's) surface's whole picture at a sub-column offset in pixels (vp's
    VP_XOFF), by the column pass (``column``: its lines, their stride, batch evaluator
    and device) and coloured as the centre's picture: its colour field's range
    (c_limits), the light its points take (lit)."""
    n_lines, hstride, fb, device = column
    W, H = view.width, view.height

    def picture(offset):
        sub_vp = vp.copy()
        sub_vp[L.VP_XOFF] = offset
        g = geometry.column_pass(surface, view, sub_vp, geometry.allocate(W, H, n_lines, 1),
                                 hstride, fb, device=device)
        base, _ = colour.base_colours(material, source, g, W, H, box, colours, c_limits)
        return finish.finish_pass(g, H, W, colours, bg8, lit, base)[0], g.evals
    return picture


#: what smooth shading lights (ValueError's message elsewhere)
SMOOTH_SHADED = ("smooth_shading lights shaded pictures antialiased along the columns: use "
                 "method='column' and antialias=True, 'area' or False (not sub-columns)")


def _line_planes(material, view, quality):
    """A line drawing's (view on its planes, hstride, lines) (geometry.horizon_planes),
    or ValueError for a material it cannot draw; a shaded picture's (view, 0, 1)."""
    if quality.method != "horizon":
        return view, 0, 1
    if material.colored or material.overlaid:
        raise ValueError("a texture, color field, contours or wireframe need shaded "
                         "pictures: method='column'")
    n_lines = quality.n_lines()
    view, hstride = geometry.horizon_planes(view, n_lines)
    return view, hstride, n_lines


def _layer(p, view, drawn, box, quality, background, t_start, stacklevel, texture=None,
           index=0):
    """One layer's passes: a Render of its own."""
    surface, domain = drawn
    material = p.material
    method = quality.method
    view, hstride, n_lines = _line_planes(material, view, quality)
    material.check_limits()
    fixes = quality.fixes(material.interpolation)
    aa_cov, sub_columns = quality.antialiasing(material.shading)
    if material.smooth_shading and (method == "horizon" or sub_columns > 1):
        raise ValueError(SMOOTH_SHADED)
    t_setup = time.perf_counter()

    W, H = view.width, view.height
    quality.check_sampling()
    vp = geometry.view_params(view, method, quality.sampling, fixes, aa_cov, surface)
    buffers = geometry.allocate(W, H, n_lines, sub_columns)
    # sampling="lod": the fly-through's level-of-detail pass where it can draw the
    # view (antialiased: by Cohen-Or's area weights along the columns); "march": its
    # ray march where that can draw it (point sampled), else as "lod"
    kind = geometry_kind(quality, material, surface, view)
    by_march = kind == "march"
    by_lod = kind == "lod"
    by_area = quality.area or (by_lod and aa_cov)
    fb = None                           # (the column pass's batch evaluator, if any)
    if by_march:
        geom = march.march_pass(surface, view, vp, buffers, device=quality.device)
    elif by_lod:
        geom = lod.lod_pass(surface, view, vp, buffers, by_area, device=quality.device)
    elif quality.area:
        geom = area.area_pass(surface, view, vp, buffers, device=quality.device)
    elif quality.device == "cuda":
        geom = geometry.column_pass(surface, view, vp, buffers, hstride, None, device="cuda")
    else:
        fb = geometry.batch_evaluator(surface, view, method, quality.sampling)
        geom = geometry.column_pass(surface, view, vp, buffers, hstride, fb)
    if material.smooth_shading:
        normals.smooth_pass(surface, view, geom)
    evals = geom.evals
    t_kernel = time.perf_counter()
    shadow = None
    lit = shadows.empty()
    if texture is not None:
        shadow, lit = shadows.shadow_pass(texture, view, geom, W, H, index)
    t_shadow = time.perf_counter()
    line_t = None
    w_limits = None
    c_limits = None
    seen = None
    light_args = None
    if method == "horizon":
        rgba, side, intensity, depth, seen, line_t = horizon.line_pass(geom, W, H, background)
    else:
        # area sampling averages the intensities it sees (kernels/area.py): lit at
        # the samples, as the paper's iis
        colours = material.table(geom.wrange, box[2], INTERP_INTENSITY if by_area else None)
        w_limits = colours.w_limits
        bg8 = color.to_rgba8(background)
        intensity = depth = None        # Render computes them when asked (centre_kernel)
        light_args = (vp, colours.mp, lit)
        base = finish.NO_BASE
        if p.source is not None:
            base, c_limits = colour.base_colours(material, p.source, geom, W, H, box, colours)
        rgba, side = finish.finish_pass(geom, H, W, colours, bg8, lit, base)
        if aa_cov and sub_columns == 1 and not by_area:
            antialias.staircase_pass(geom, side, rgba)
        if sub_columns > 1:
            picture = None if p.source is None else _textured_columns(
                surface, view, vp, (n_lines, hstride, fb, quality.device), material,
                p.source, box, colours, c_limits, bg8, lit)
            rgba, ev2 = antialias.subcolumn_pass(surface, geom, sub_columns, rgba, colours,
                                                 bg8, lit, picture)
            evals += ev2
        if material.overlaid:
            overlays.overlay_pass(rgba, material, p.source, geom, W, box, w_limits, c_limits,
                                  p.domain, bg8)  # (the surface's domain, not the box's)
    t_end = time.perf_counter()
    if nowhere_finite(surface, domain) and not (side != 0 if seen is None else seen).any():
        warnings.warn(empty_message(p.surface, p.domain), RuntimeWarning,
                      stacklevel=stacklevel + 1)
    stats = {
        "samples": int(evals.sum()),
        "seconds": t_end - t_start,
        "kernel_seconds": t_kernel - t_setup,
        "setup_seconds": t_setup - t_start,
        "planes": view.planes,
        "step": view.step,
        "scale": view.scale,
        "lines": n_lines if method == "horizon" else 0,
        "method": method,
        "derivatives": surface.derivatives,
        "w_limits": w_limits,      # the colormap's height range (column method)
        "box": box,                # aspect's stretch of u, v and w (1, 1, 1: none)
        "engine": "kernels",       # (a fresh install's first pictures: "draft")
        # the geometry pass that drew it: "column", "area", "lod" or "march" (passes/)
        "geometry": ("march" if by_march else "lod" if by_lod
                     else "area" if quality.area else "column"),
    }
    if c_limits is not None:
        stats["c_limits"] = c_limits   # the colour field's range on the colormap
    if texture is not None:
        stats["shadow_seconds"] = t_shadow - t_kernel
        stats["shadow_texels"] = texture.texels
    return Render(rgba, intensity, side, depth, stats, view, geom.gbuf, line_t, seen,
                  light_args, box, shadow=shadow)


def _draft_layer(p, view, drawn, box, quality, background, t_start, stacklevel, texture=None,
                 index=0):
    """One layer's draft picture (passes/draft.py): a Render as _layer's; with the
    light's shadow ``texture`` (not swept), its shadows as layer ``index`` of the
    texture's (passes/draft_shadow.py); a line drawing's by passes/draft_horizon.py."""
    surface, domain = drawn
    material = p.material
    if quality.method == "horizon":
        return _draft_lines(p, view, drawn, box, quality, background, t_start, stacklevel + 1)
    material.check_limits()
    t_setup = time.perf_counter()
    shadows = None if texture is None else (texture, index)
    extra = {}
    if material.opacity < 1.0:
        from .passes.draft_layers import draft_translucent
        rgba, side, intensity, depth, gbuf, evals, w_limits, shadow, seen = draft_translucent(
            surface, view, material, p.terms, box, color.to_rgba8(background), shadows,
            p.source)
        c_limits = None
        extra = {"translucent": True, "layers": seen}
    else:
        rgba, side, intensity, depth, gbuf, evals, w_limits, c_limits, shadow = \
            draft.draft_pass(surface, view, material, p.terms, box, color.to_rgba8(background),
                             p.source, shadows)
        if material.overlaid:           # contours and wireframes, drawn in numpy
            planes = draft.planes(gbuf, side, view, box)
            if material.fill:
                overlays.overlay_planes(rgba, material, p.source, planes, w_limits, c_limits,
                                        p.domain, draw=overlays.draw_lines)
            else:                       # (the lines alone, hidden where the surface is)
                overlays.lines_alone(rgba, material, p.source, planes, w_limits, c_limits,
                                     p.domain, color.to_rgba8(background),
                                     draw=overlays.draw_lines)
    stats = _draft_stats(p, view, drawn, box, evals, side != 0, t_start, t_setup,
                         stacklevel + 1, w_limits=w_limits, **extra)
    if c_limits is not None:
        stats["c_limits"] = c_limits   # the colour field's range on the colormap
    return Render(rgba, intensity, side, depth, stats, view, gbuf, box=box, shadow=shadow)


def _draft_translucent(layers, views, drawn, box, background, texture, t_start, stop=None):
    """The draft of several surfaces, one at least translucent, or of translucency with
    objects (``stop`` their depth: objects.depth_map's) (passes/draft_layers.py
    draft_translucent_layers): a Render as render_translucent's."""
    from .passes.draft_layers import draft_translucent_layers
    for p in layers:
        p.material.check_limits()
    if texture is not None and texture.occluders is not None:
        # (the objects pass reads the surfaces' shadows on the objects in the planes)
        from .passes.draft_shadow import adopt
        adopt(texture)
    rgba, side, intensity, depth, gbuf, evals, w_limits, shadow, met, which, front = \
        draft_translucent_layers(layers, views, drawn, box, color.to_rgba8(background),
                                 texture, stop)
    view = views[0]
    stats = {"samples": int(evals.sum()), "seconds": time.perf_counter() - t_start,
             "translucent": True, "layers": met, "w_limits": w_limits, "method": "column",
             "engine": "draft", "box": box, "planes": view.planes, "step": view.step,
             "scale": view.scale, "surfaces": len(layers)}
    if len(layers) > 1:
        stats["surface"] = which
    else:
        stats["w_limits"] = w_limits[0]
    return Render(rgba, intensity, side, depth, stats, view, gbuf, box=box, shadow=shadow,
                  _front=front)


def _draft_lines(p, view, drawn, box, quality, background, t_start, stacklevel):
    """_draft_layer of a line drawing (method="horizon")."""
    from .passes.draft_horizon import draft_line_pass
    surface, domain = drawn
    material = p.material
    view, hstride, n_lines = _line_planes(material, view, quality)
    material.check_limits()
    if material.smooth_shading:
        raise ValueError(SMOOTH_SHADED)
    t_setup = time.perf_counter()
    rgba, side, intensity, depth, seen, line_t, gbuf, evals = draft_line_pass(
        surface, view, hstride, n_lines, background)
    stats = _draft_stats(p, view, drawn, box, evals, seen, t_start, t_setup, stacklevel + 1,
                         lines=n_lines, method="horizon", w_limits=None)
    return Render(rgba, intensity, side, depth, stats, view, gbuf, line_t, seen, box=box)


def _draft_stats(p, view, drawn, box, evals, seen, t_start, t_setup, stacklevel, **fields):
    """A drafted layer's stats (as _layer's, engine "draft"; ``fields`` over them), once
    it warned where f is nowhere finite and nothing is ``seen``."""
    surface, domain = drawn
    t_end = time.perf_counter()
    if nowhere_finite(surface, domain) and not seen.any():
        warnings.warn(empty_message(p.surface, p.domain), RuntimeWarning,
                      stacklevel=stacklevel + 1)
    return {"samples": int(evals.sum()), "seconds": t_end - t_start,
            "kernel_seconds": t_end - t_setup, "setup_seconds": t_setup - t_start,
            "planes": view.planes, "step": view.step, "scale": view.scale, "lines": 0,
            "method": "column", "derivatives": surface.derivatives, "box": box,
            "engine": "draft", **fields}


def default_background(method, shading):
    """Black behind the reference model's shaded pictures, white otherwise."""
    black = method == "column" and shading == "lambert"
    return (0, 0, 0, 255) if black else (255, 255, 255, 255)


def layer_domain(surface, u, v):
    """A layer's checked domain: u and v, or the surface's own, or DEFAULT_RANGE."""
    default = surface.default_domain
    if u is None:
        u = default[0] if default else DEFAULT_RANGE
    if v is None:
        v = default[1] if default else DEFAULT_RANGE
    return check_range(surface.variables[0], u), check_range(surface.variables[1], v)


def empty_message(surface, domain):
    (ua, ub), (va, vb) = domain
    a, b = surface.variables
    if surface.expr is None:
        what = "f"
    else:
        import sympy
        text = sympy.sstr(surface.expr, full_prec=False)
        what = f"f = {text if len(text) <= 60 else text[:57] + '...'}"
    return (f"{what} is NaN, infinite or complex everywhere on {a} in [{ua:g}, {ub:g}], "
            f"{b} in [{va:g}, {vb:g}]: the picture is empty (check the expression and the "
            "ranges)")


def _drafting(quality, material, surface, view, light):
    """warmup.drafting of this picture's kernels (its geometry pass's, smooth shading's,
    its shadows'), warmup imported here: ``python -m floatcol.warmup`` runs that module
    as __main__, which Python warns about where the package imported it first."""
    from . import warmup
    kind = "layers" if material.opacity < 1.0 else geometry_kind(quality, material, surface,
                                                                   view)
    return warmup.drafting(kind, material.smooth_shading, warmup.shadow_kind(light))


def geometry_kind(quality, material, surface, view):
    """The geometry pass that draws a layer (passes/): "march" (the ray march: a fly
    camera's point-sampled view of a height field), "lod" (the level-of-detail engine:
    a fly camera's other views), "area" (area sampling) or "column"."""
    aa_cov, _ = quality.antialiasing(material.shading)
    if quality.method == "column" and quality.sampling == "march" \
            and march.supports(surface, view, aa_cov or quality.area):
        return "march"
    if quality.method == "column" and quality.sampling in ("lod", "march") \
            and lod.supports(surface, view):
        return "lod"
    return "area" if quality.area else "column"
