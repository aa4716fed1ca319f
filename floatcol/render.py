"""render(): the paper's door. It builds a Scene of one layer from its keywords and
runs the renderer's passes (floatcol/renderer.py)."""
from __future__ import annotations

from . import color
from .camera import Camera, NO_BOX, box_factors, box_point, in_box  # noqa: F401 (re-exported)
from .light import DEFAULT_LIGHT, as_light  # noqa: F401
from .material import (  # noqa: F401
    DEFAULT_AMBIENT, DEFAULT_SHININESS, DEFAULT_SPECULAR, INTERPOLATIONS, SHADINGS, Material)
from .passes.geometry import BATCH_MIN_SAMPLES  # noqa: F401
from .output import save_image
from .quality import (  # noqa: F401
    CORRECTIONS, DEFAULT_CORRECTIONS, DEFAULT_JUMP, DEFAULT_LINES, DEFAULT_RATE, DETECTORS,
    METHODS, Quality)
from .renderer import DEFAULT_RANGE, default_background, layer_domain, render_scene  # noqa: F401
from .result import Render
from .scene import Layer, Scene

__all__ = ["Render", "render"]


def save_png(rgba, path):
    """Write an RGBA array as a PNG, atomically (kept for callers of 0.1)."""
    save_image(rgba, path)


def render(expr, u=None, v=None, size=(400, 300), elev=30.0, azim=30.0,
           projection="orthographic", d1=None, d2=None, scale=None, method="column",
           shading="default", *, interpolation="normal", smooth_shading=False, step=None,
           lines=DEFAULT_LINES, vars=None, center=None, cmap="viridis", upper_color=None,
           lower_color=color.DEFAULT_LOWER, vmin=None, vmax=None, norm=None, background=None,
           light=None, ambient=None, focal_length=None, pixel_step=1.0,
           placement="exact", specular=None, shininess=None,
           corrections=DEFAULT_CORRECTIONS, detect=None, jump_threshold=DEFAULT_JUMP,
           supersample_rate=DEFAULT_RATE, spline_tolerance=None,
           antialias=None, sampling="uniform", aspect="equal", box=None, lightsource=None,
           shadows=False, light_radius=0.0, opacity=1.0, texture=None, texture_extent=None,
           texture_filter="mipmap", color=None, contours=None, contour_color="black",
           contour_width=1.0, wireframe=None, edgecolor="black", linewidth=0.75,
           fill=True, wire_coords=None, objects=None, tiles=None, client=None,
           device="cpu") -> Render:
    """Render w = f(u, v) with the floating column algorithm (Gordon 2001).

    Parameters
    ----------
    expr : sympy expression, str, callable f(u, v), Surface or HeightField, or a 2-D
        array of heights (a HeightField over its columns' and rows' indices).
        Free symbols are u and v unless ``vars=(x, y)`` names others.
    u, v : (low, high)
        The domain rectangle; default (-10, 10), or a HeightField's own extent.
    size : (width, height) in pixels.
    elev, azim : degrees. elev > 0 looks down on the surface; alpha = -elev, beta = azim.
    projection : "orthographic" or "perspective" (d1: viewpoint-to-screen distance,
        d2: screen-to-origin distance, as in eqs. (9)-(10)).
    scale : pixels per unit (the paper's Ratio); None fits the surface in the image.
    method : "column" (shaded) or "horizon" (monochrome line drawing, ``lines`` lines).
    shading : "default" (ambient + diffuse key light, height colormap, two-coloured
        sides) or "lambert" (I = |L.N|/(|L||N|), light at the viewpoint, no ambient).
    interpolation : "normal" (nis, per-pixel lighting) or "intensity" (iis, Gouraud).
    smooth_shading : a height field lit by normals interpolated between its nodes
        (central differences), as a hillshade, instead of its bilinear cells' own:
        no lit facets on a coarse DEM seen up close (where a pixel is at most half a
        cell wide; fading out up to a cell, where the pixels are wider than the facets).
        The geometry is the same. Opaque, shaded pictures (not sub-columns); a function
        surface is smooth already (passes/normals.py).
    cmap, vmin, vmax : the upper side's colormap (a matplotlib name or Colormap) and the
        heights at its ends (default: the range of w where the upper side is seen).
    norm : instead of vmin/vmax, a matplotlib norm (LogNorm, PowerNorm, ...; any
        monotonic w -> [0, 1] with an ``inverse``), unscaled ends scaled to the seen
        range; the colormap's rows begin at norm.inverse(k / 255); a BoundaryNorm's,
        a row a band. Or a scale's name ("log", "symlog", "asinh", "logit", "linear"),
        as matplotlib's mappables take it, with vmin/vmax as its ends.
    step : distance between sampling planes; default ``pixel_step`` (1) pixels on screen
        (at the nearest point in perspective).
    specular, shininess : Phong highlights on top of the diffuse light (default
        shading only; default 0.2 and 30; ``specular=0`` turns them off). They are
        added to ``rgba``; ``intensity`` stays the ambient + diffuse term.
    placement : perspective only: "exact" puts every sample on its column's plane
        (ERRATA 2, the default); "paper" uses Gordon's approximate eq. (9) point,
        which lies off the plane when elev != 0 (to reproduce the paper's figures).
    corrections : the artifact corrections of section 5, applied between two samples
        where a problem is detected: "none", "spline" (ridges: the extremum of a
        cubic spline, eqs. 13-22, becomes a sample), "supersample" (``supersample_rate``
        samples across the span), "adaptive" (halve the span while the problem
        persists, down to 1/``supersample_rate``), or "spline+supersample" /
        "spline+adaptive" (splines for ridges, the other for shading problems).
    detect : which problems to look for, any of "ridge" (V.N changes sign),
        "intensity" (a jump above ``jump_threshold``), "bump" (section 5.3) and
        "wall" (a discontinuity of f, end of section 5: located by halving and shaded
        as a vertical wall). Default: ridge, intensity and wall, plus bump with
        interpolation="intensity". corrections="none" turns all of them off.
    spline_tolerance : iterate the spline (end of section 5.2) until |V.N| at its
        extremum is at most this; None: one step, as in the paper.
    sampling : section 6.3. "adaptive": per column, the distance between sampling
        planes grows with the distance from the viewer in perspective (up to 16
        times), grows where the normal turns slowly (up to 4 times, while spans stay
        within 2 pixel rows) and shrinks to a quarter where it turns fast; "uniform"
        (default): planes ``step`` apart everywhere, as the paper and the line drawings;
        "lod" (fc.fly's): the level-of-detail engine of fly-throughs (passes/lod.py,
        docs/terrain.md): planes a pixel's footprint apart, each sampling the height
        field's pyramid at that footprint, one floating horizon per column; where it
        cannot draw the view (orthographic, looking down past the nadir, the eye
        below the ground) the adaptive planes. Antialiased by area weights along
        the columns (antialias=True or "area"), or at pixel centres (False).
        "march": point-sampled fly-throughs of a height field (antialias=False) by
        each pixel's ray marched through the lod engine's planes (passes/march.py):
        faster, no Newton iteration; any other view as "lod".
    antialias : section 6.4. True: coverage-weighted blending along columns (the
        floating interval's float ends give each silhouette pixel its coverage, and
        where the surface reappears beyond an extremum the pixel blends both
        surfaces), and across columns the staircase of an edge steeper than a row
        per column where the side seen changes (a silhouette against the background,
        the lower side in front of the upper), from the columns' ends
        (kernels/silhouette.py); 2, 3 or 4: the coverage along columns and as many
        sub-columns per pixel, averaged (instead of the staircases' pass); False:
        off. Default: True for shading="default", False for "lambert" and the
        horizon. Only ``rgba`` is blended; ``intensity``, ``side``, ``depth`` and the
        G-buffer describe the surface at each pixel centre. "area": Cohen-Or's exact
        area sampling along the columns (kernels/area.py): every visible part of the
        surface in a pixel weighted by the part of the pixel it covers, a height
        field sampled through a level-of-detail pyramid; then ``intensity`` and the
        G-buffer are those weighted means (docs/terrain.md).
    focal_length : perspective only, instead of d1/d2: matplotlib's focal length
        (the surface's bounding sphere fills a field of view of 2 atan(1/f)).
    center : world point (u, v, w) at the image centre. None: the middle of the
        domain and of the range of f when scale is fitted, the origin (as in the
        paper and DESIGN.md's pixel convention) when scale is given; or "auto".
    aspect : the proportions of the picture's box, as matplotlib's 3-D axes.
        "equal" (default): u, v and w in true proportions, as the paper. "auto"
        (matplotlib's default, and plot_surface's): the domain's u and v ranges and
        the range of f stretched to a box of proportions 4 : 4 : 3, so a surface
        much flatter or taller than its domain is wide as much as it is high;
        "equalxy": u and v in true proportions, w stretched to 3/4 of the longer
        side; or (bu, bv, bw): a box of those proportions. ``scale`` then counts
        pixels per unit of u; ``center``, vmin/vmax and the Render's u, v, w stay in
        the surface's units; ``depth``, ``normal`` and ``view`` are the box's.
    box : (a, b, c), instead of aspect: stretch u, v and w by these factors (a
        picture's ``stats["box"]``, to draw another in the same box).
    lightsource : (azdeg, altdeg) in degrees or a matplotlib LightSource: a light fixed
        to the surface (its direction is LightSource.direction in (u, v, w)) instead
        of the default shading's screen-fixed key light.
    shadows : section 6.2: the light casts shadows (attached: a side facing away from
        it gets ambient light only; cast: a point with the surface between it and the
        light). ``Render.shadow`` says where (1 shadow, 0 lit, between at the
        antialiased edges, NaN where nothing is seen). The light is ``lightsource``,
        ``light`` or the default key light. ``True`` (or "texture") finds cast
        shadows in a shadow texture over the domain (section 6.2.1: one for every
        surface, so several surfaces shadow each other); "on-the-fly" by section
        6.2.2's sweep without a texture (O(lines) memory; one surface).
    light_radius : the light's angular radius in degrees (the sun's: 0.27): soft
        shadows, the part of the light's disk each point sees (penumbrae about 2 D
        tan(radius) wide behind an edge at distance D); 0 (the default) hard,
        antialiased shadows. Needs shadows=True.
    opacity : sections 6.5-6.6: below 1 the surface is translucent: every layer of it
        along each pixel's ray (its hidden folds, its lower side) shows, lit and
        coloured as the opaque surface would be, composited front to back.
        ``intensity`` is then the composite sum_k a (1 - a)^k I_k of the layers'
        intensities over black; ``side``, ``depth``, ``shadow`` and the G-buffer are
        the nearest layer's, ``stats["layers"]`` the number of layers met at each
        pixel. The default shading's antialiasing covers each layer's silhouettes
        (the part of a pixel a layer covers along the column, and 3 sub-columns
        across); 1 (default) is the opaque surface.
    texture : section 6.7: an image over the domain: an array (h, w, 3|4) of uint8 or
        floats in [0, 1] indexed as HeightField's heights (``img[j, i]`` the colour at
        (u_i, v_j)), an image file's path, or a function T(u, v) -> RGB(A) of arrays;
        both sides take it (lit as the surface), its alpha lays it over the surface's
        own colour. ``texture_extent`` (u0, u1, v0, v1): where it lies (default: the
        domain); ``texture_filter``: "mipmap" (trilinear: each pixel averages the
        texels it covers, no shimmer; default), "linear" or "point".
    color : colour from data: a second expression of u and v (or a 2-D array indexed
        as heights over ``texture_extent``) coloured through cmap and norm/vmin/vmax
        instead of the height (``stats["c_limits"]`` its range on the colormap).
    contours : contour lines of f (of ``color`` when given): N evenly spaced levels
        or the levels; ``contour_color``, ``contour_width`` in pixels (default 1).
        Antialiased, of constant width, hidden where the surface hides them.
    wireframe : lines at u = const and v = const: N each way or (nu, nv), spread
        over the domain from edge to edge (matplotlib's rcount, ccount), or (us, vs)
        the lines' positions (an unevenly spaced mesh's lines); ``edgecolor``,
        ``linewidth`` in pixels (default 0.75).
    wire_coords : (grid, extent): the wireframe's lines at the positions ``wireframe``
        gives of two other coordinates than u and v, bilinear from ``grid`` (ny, nx, 2)
        over ``extent`` (u0, u1, v0, v1): a curvilinear mesh's column and row index,
        which plot_surface(X, Y, Z, edgecolor=...) gives.
    fill : False draws the lines (wireframe, contours) alone over the background, the
        surface itself not drawn but hiding the lines behind it: a hidden-line drawing
        (matplotlib's plot_wireframe, with the hidden lines removed).
    objects : objects standing on the surface (Szenberg 1997): ``fc.box``,
        ``fc.pole``, ``fc.tree``, ``fc.marker`` or any ``fc.Mesh``, drawn by a
        z-buffer against the surface's depth, lit flat by the picture's light.
    tiles, client : a poster in ``tiles`` bands of columns, drawn one after the other,
        or as tasks on ``client`` (a dask.distributed Client; ``pip install
        'floatcol[dask]'``), assembled into the same picture, array for array, as
        without (floatcol/cluster.py). A client alone: two bands a worker.
    device : where the column pass (area sampling's, the translucent layers', the
        fly-through's ray march and level-of-detail engine) runs:
        "cpu" (default) or "cuda", an NVIDIA GPU, a thread a pixel column, the same
        column code compiled for the GPU (the same picture; ``pip install
        'floatcol[cuda]'``; kernels/cuda.py, docs/cuda.md). A ValueError says so on a
        machine without a GPU. The passes after it (shadows, finishing, textures) run
        on the CPU.

    Returns
    -------
    Render
        with ``rgba``, ``intensity``, ``side``, ``depth`` and ``stats``.

    Examples
    --------
    >>> import floatcol as fc
    >>> r = fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(160, 120))
    >>> r.rgba.shape, r.side.dtype
    ((120, 160, 4), dtype('int8'))
    """
    if tiles is not None or client is not None:
        options = {k: x for k, x in locals().items()
                   if k not in ("expr", "u", "v", "tiles", "client")}
        from .cluster import render_tiled
        return render_tiled([(expr, u, v)], options, tiles, client)
    return render_scene(Scene(
        [Layer(expr, (u, v), Material(
            shading=shading, cmap=cmap, norm=norm, vmin=vmin, vmax=vmax, upper_color=upper_color,
            lower_color=lower_color, ambient=ambient, specular=specular, shininess=shininess,
            interpolation=interpolation, smooth_shading=smooth_shading, opacity=opacity,
            texture=texture, texture_extent=texture_extent, texture_filter=texture_filter,
            color=color,
            contours=contours, contour_color=contour_color, contour_width=contour_width,
            wireframe=wireframe, edgecolor=edgecolor, linewidth=linewidth, fill=fill,
            wire_coords=wire_coords))],
        camera=Camera(size=size, elev=elev, azim=azim, projection=projection, d1=d1, d2=d2,
                      scale=scale, center=center, focal_length=focal_length, aspect=aspect,
                      box=box),
        light=light if lightsource is None and not shadows and not light_radius else
        as_light(light, shading, lightsource, shadows, light_radius),
        quality=Quality(method=method, lines=lines, step=step, pixel_step=pixel_step,
                        sampling=sampling, placement=placement, corrections=corrections,
                        detect=detect, jump_threshold=jump_threshold,
                        supersample_rate=supersample_rate, spline_tolerance=spline_tolerance,
                        antialias=antialias, device=device),
        background=background, vars=vars, objects=objects or ()), stacklevel=2)
