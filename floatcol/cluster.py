"""Beyond one machine: posters and animation frames on Dask (issue 34).

Columns are independent (Gordon sections 1, 6.1) and so are frames. With a
``dask.distributed`` client (the optional extra ``floatcol[dask]``):

- ``render(..., tiles=N, client=client)`` draws the picture as N bands of columns,
  one task each, and assembles them: every band fits the camera to the whole picture
  (camera.Camera.columns) and draws its columns at exactly the screen positions the
  whole picture's would have (kernels/sample.py column_x0), with MARGIN columns more on
  each side for the passes that read a neighbouring column (the staircases, texture
  and line widths), which are cut off. The colormap's heights are the whole picture's:
  where they are left to the seen range, a band whose own range is not the picture's
  is drawn again with the picture's (vmin, vmax). The poster is the same, array for
  array, as one render() of it.
- ``render_many(..., tiles=N, client=client)``: the same for several surfaces, each
  surface's colormap over the heights it shows in the whole picture.
- ``animate(..., client=client)`` renders the frames as tasks (each worker compiles
  the expression once) and writes them in order.
- ``gallery.build(..., client=client)`` runs the gallery's examples as tasks.

Without a client (``client=None``) the bands are drawn one after the other in this
process: a poster larger than the memory of one render's buffers.
"""
from __future__ import annotations

import dataclasses
import time

import numpy as np

#: columns drawn beyond a band's own on each side (the passes that read neighbours
#: need 4): a whole group of the column kernel's tiles (bands)
MARGIN = 16
#: the most bands of a poster
MAX_TILES = 4096


def _check_client(client):
    if client is None:
        return None
    if not (hasattr(client, "submit") and hasattr(client, "gather")):
        raise ValueError("client must be a dask.distributed Client (pip install "
                         f"'floatcol[dask]'), got {client!r}")
    return client


def _check_tiles(tiles, width):
    if tiles is None:
        return 1
    if isinstance(tiles, bool) or not isinstance(tiles, (int, np.integer)) or \
            not 1 <= tiles <= MAX_TILES:
        raise ValueError(f"tiles must be a whole number of bands in 1..{MAX_TILES}, "
                         f"got {tiles!r}")
    return int(min(tiles, width))


def bands(width, tiles):
    """The bands' columns: [(first, end), ...] of nearly equal widths, each starting at
    a whole group of tiles (kernels/layout.py GROUP; MARGIN is one): a group's columns
    run in order and start their perspective Newton iterations from the ones before
    (kernels/column.py guesses_for), so a band draws a group's columns as the whole
    picture does."""
    from .kernels.layout import GROUP
    n = -(-width // GROUP)
    edges = np.minimum(np.linspace(0, n, tiles + 1).round().astype(int) * GROUP, width)
    return [(int(a), int(b)) for a, b in zip(edges[:-1], edges[1:]) if b > a]


def _band_task(items, options, first, end, width, composite=False):
    """One band: columns first..end - 1 of a ``width`` wide picture, drawn with MARGIN
    columns more each side (``composite``: its layers composited, as render_many).
    Returns its arrays cut to its own columns and what the colormap's heights need."""
    from .passes.tiles import untile
    from .renderer import render_scene
    from .scene import scene_from_options
    a0 = max(0, first - MARGIN)
    a1 = min(width, end + MARGIN)
    scene = scene_from_options(list(items), **options, columns=(a0, a1 - a0))
    r = render_scene(scene, composite=composite)
    cut = slice(first - a0, end - a0)
    gbuf = untile(r._gbuf, a1 - a0)[:, cut] if r._gbuf is not None else None
    out = {"rgba": r.rgba[:, cut].copy(), "side": r.side[:, cut].copy(),
           "intensity": r.intensity[:, cut].copy(), "depth": r.depth[:, cut].copy(),
           "shadow": None if r.shadow is None else r.shadow[:, cut].copy(),
           "gbuf": None if gbuf is None else np.ascontiguousarray(gbuf),
           "seen": r._mask()[:, cut].copy(), "stats": dict(r.stats), "view": r.view,
           "box": r.box, "upper": bool((r.side == 1).any())}
    layers = out["stats"].pop("layers", None)      # (translucent: a count a pixel)
    if isinstance(layers, np.ndarray) and layers.ndim == 2:
        out["layers"] = layers[:, cut].copy()
    surface = out["stats"].pop("surface", None)    # (a composite: the layer a pixel)
    if isinstance(surface, np.ndarray) and surface.ndim == 2:
        out["surface"] = surface[:, cut].copy()
    if "upper_seen" in out["stats"]:               # (a composite: each layer's upper side)
        out["upper"] = list(out["stats"]["upper_seen"])
    return out


def render_tiled(items, options, tiles=None, client=None, composite=False):
    """render()'s picture of ``items`` ((expr, u, v) triples, expressions or Layers)
    with render's ``options``, in ``tiles`` bands of columns on ``client``
    (dask.distributed) or here; ``composite``: render_many's picture (the layers
    composited, as it draws even one). Returns a Render."""
    from .view import check_size
    t0 = time.perf_counter()
    client = _check_client(client)
    W, H = check_size(options.get("size", (400, 300)))
    n = _check_tiles(tiles, W) if tiles is not None else (
        2 * max(len(client.scheduler_info().get("workers", {})), 1) if client else 1)
    spans = bands(W, min(n, W))
    items = list(items)
    if not items:
        raise ValueError("surfaces is empty: give at least one expression")
    composite = composite or len(items) > 1
    if composite:
        return _render_tiled_layers(items, options, spans, W, H, client, t0)
    auto = (options.get("vmin") is None or options.get("vmax") is None) \
        and options.get("norm") is None
    got = _run(items, options, spans, W, client)
    # the colormap's values: the heights of the upper side seen, or a colour field's
    key = "w_limits" if options.get("color") is None else "c_limits"
    if auto:
        ranges = [g["stats"].get(key) for g in got if g["upper"] or key == "c_limits"]
        ranges = [r for r in ranges if r is not None and np.ndim(r) == 1]
        if ranges:
            vmin, vmax = _limits(ranges, options.get("vmin"), options.get("vmax"))
            again = [k for k, g in enumerate(got)
                     if tuple(g["stats"].get(key) or ()) != (vmin, vmax)]
            if again:
                fixed = dict(options, vmin=vmin, vmax=vmax)
                for k, g in zip(again, _run(items, fixed, [spans[k] for k in again], W,
                                            client)):
                    got[k] = g
    return _assemble(got, W, H, t0, len(spans))


def _limits(ranges, vmin, vmax):
    """The picture's (vmin, vmax) from the bands' seen ranges, where not given."""
    lo = min(r[0] for r in ranges)
    hi = max(r[1] for r in ranges)
    return (lo if vmin is None else vmin), (hi if vmax is None else vmax)


def _render_tiled_layers(items, options, spans, W, H, client, t0):
    """render_tiled of several layers (render_many's composite): each layer's
    colormap spans the heights it shows in the whole picture, as in one render_many;
    a band whose layers' ranges are not the picture's is drawn again with every
    layer's limits fixed (the items as Layers of their own materials)."""
    from .scene import scene_from_options
    if options.get("color") is not None:
        if options.get("vmin") is None or options.get("vmax") is None:
            raise ValueError("a poster of several surfaces with a color field needs vmin "
                             "and vmax (the field's colormap limits)")
    layers = scene_from_options(list(items), **_material_only(options)).layers
    got = _run(items, options, spans, W, client, composite=True)
    per = [_per_layer(g, len(layers)) for g in got]     # (limits, upper side seen)
    again = []
    fixed_layers = []
    for k, layer in enumerate(layers):
        m = layer.material
        auto = (m.vmin is None or m.vmax is None) and m.norm is None and m.color is None
        if not auto:
            fixed_layers.append(layer)
            continue
        ranges = [lims[k] for lims, upper in per if upper[k]]
        ranges = [r for r in ranges if r is not None and np.ndim(r) == 1]
        if not ranges:
            fixed_layers.append(layer)
            continue
        vmin, vmax = _limits(ranges, m.vmin, m.vmax)
        again += [b for b, (lims, _) in enumerate(per) if tuple(lims[k] or ()) != (vmin, vmax)]
        fixed_layers.append(dataclasses.replace(
            layer, material=dataclasses.replace(m, vmin=vmin, vmax=vmax)))
    again = sorted(set(again))
    if again:
        rest = {k: x for k, x in options.items() if k not in _material_keys()}  # (Layers')
        for b, g in zip(again, _run(fixed_layers, rest, [spans[b] for b in again], W, client,
                                    composite=True)):
            got[b] = g
    return _assemble(got, W, H, t0, len(spans))


def _per_layer(band, n):
    """(each layer's colormap limits, whether each shows its upper side) of a band of
    n layers; a translucent composite's limits are the fitted view's, the same in
    every band, and it says nothing of sides: its layers count as seen."""
    lims = band["stats"].get("w_limits")
    upper = band["upper"]
    if not isinstance(upper, list):
        upper = [True] * n
    if not isinstance(lims, list):
        lims = [lims] * n
    return lims, upper


def _material_keys():
    from .scene import MATERIAL_OPTIONS
    return set(MATERIAL_OPTIONS)


def _material_only(options):
    """The options a scene needs to give its layers their materials (and the
    variables' names)."""
    keys = _material_keys() | {"vars"}
    return {k: x for k, x in options.items() if k in keys}


def _run(items, options, spans, W, client, composite=False):
    if client is None:
        return [_band_task(items, options, a, b, W, composite) for a, b in spans]
    futures = [client.submit(_band_task, items, options, a, b, W, composite, pure=False)
               for a, b in spans]
    return client.gather(futures)


def _assemble(got, W, H, t0, n_bands):
    """The Render of the bands' arrays side by side."""
    from .kernels.layout import TILE
    from .result import Render

    def cat(key):
        return np.concatenate([g[key] for g in got], axis=1)

    view = dataclasses.replace(got[0]["view"], width=W, first_column=0, x_offset=0.0)
    gbuf = None
    if got[0]["gbuf"] is not None:
        flat = cat("gbuf")
        n_tiles = -(-W // TILE)
        padded = np.zeros((H, n_tiles * TILE) + flat.shape[2:], dtype=flat.dtype)
        padded[:, :W] = flat
        gbuf = np.ascontiguousarray(
            padded.reshape(H, n_tiles, TILE, *flat.shape[2:]).transpose(1, 0, 2, 3))
    stats = dict(got[0]["stats"])
    stats["samples"] = sum(int(g["stats"]["samples"]) for g in got)
    stats["seconds"] = time.perf_counter() - t0
    stats["bands"] = n_bands
    for key in ("kernel_seconds", "setup_seconds", "shadow_seconds"):
        stats.pop(key, None)
    if "layers" in got[0]:
        stats["layers"] = cat("layers")
    if "surface" in got[0]:
        stats["surface"] = cat("surface")
    if "upper_seen" in stats:
        stats["upper_seen"] = [any(g["upper"][k] for g in got)
                               for k in range(len(stats["upper_seen"]))]
    side = cat("side")
    seen = cat("seen")
    return Render(cat("rgba"), cat("intensity"), side, cat("depth"), stats, view, gbuf, None,
                  None if np.array_equal(seen, side != 0) else seen, None, got[0]["box"],
                  shadow=None if got[0]["shadow"] is None else cat("shadow"))


def render_frames(tasks, client):
    """Animation frames on ``client``: each task (frame_task's arguments) a future, the
    pictures fetched in order (_in_order)."""
    return _in_order([client.submit(frame_task, *task, pure=False) for task in tasks])


def flight_frames(hf, cameras, options, client):
    """A flight's frames (fc.fly_through) on ``client``: the height field sent to
    every worker once (scattered: a worker keeps its pyramid and its shadow texture
    from one frame to the next, as here), each frame a task; (rgba, samples) fetched
    in order (_in_order)."""
    held = client.scatter(hf, broadcast=True)
    return _in_order([client.submit(flight_task, held, camera, options, pure=False)
                      for camera in cameras])


def _in_order(futures):
    """The futures' results in order, each fetched when its turn comes and then let go
    (the cluster forgets it), so that a long clip written as it comes is not held whole
    here or on the workers."""
    for k in range(len(futures)):
        future, futures[k] = futures[k], None
        yield future.result()
        future.release()


def flight_task(hf, camera, options):
    """One frame of fc.fly_through: fc.terrain's fly picture (the heights already
    exaggerated). Returns (rgba, samples)."""
    from .terrain import terrain
    from .warmup import full_quality
    with full_quality():                         # (a clip's frames: no drafts)
        r = terrain(hf, vert_exag=1.0, fly=camera, **options).draw()
    return r.rgba, int(r.stats["samples"])


_SURFACES = {}


def frame_task(expr, names, t_name, tk, ranges, options):
    """One frame of animate(): the surface at time tk (compiled once per worker and
    expression) drawn by plot_surface with the clip's fixed camera and colours.
    Returns (rgba, samples)."""
    from .plot import plot_surface
    from .surface import as_surface
    key = (str(expr), tuple(names), t_name)
    base = _SURFACES.get(key)
    if base is None:
        from .surface import sympy_expression
        base = as_surface(sympy_expression(expr, tuple(names) + (t_name,)), tuple(names),
                          time=t_name)
        _SURFACES[key] = base
    from .warmup import full_quality
    with full_quality():                         # (a clip's frames: no drafts)
        r = plot_surface(base.at(tk), *ranges, **options).draw()
    return r.rgba, int(r.stats["samples"])
