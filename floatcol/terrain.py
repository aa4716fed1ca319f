"""Terrains from files: digital elevation models (DEMs) as HeightFields, and their
picture with landscape defaults in one call.

``read_dem(path)`` reads .npy, .npz (matplotlib's sample DEMs: ``elevation`` with
``xmin``/``xmax``/``ymin``/``ymax``), 16-bit (or 8-bit) greyscale PNG, and GeoTIFF
(with the optional extra ``floatcol[geotiff]``: tifffile, a pure-Python reader with
numpy as its only dependency; rasterio/GDAL would bring a C library stack for what
is here three tags). Image-like files keep their rows north-up (row 0 the northern
edge), as DEMs are stored; the HeightField turns them to run south to north.
Geographic extents (degrees) become metres from the south-west corner, so heights
and distances share a unit; nodata values become holes.

``terrain(source)`` draws one with defaults that make a DEM look like a landscape:
true proportions with a vertical exaggeration chosen so the relief shows
(``vert_exag="auto"``), an earth colormap, a sun from the north-west as matplotlib's
LightSource and a view from the south.
"""
from __future__ import annotations

import math
import numbers
import os
import weakref

import numpy as np

from ._memory import fits
from .quality import antialias
from .surface import HeightField

#: DEM files read_dem takes (suffix -> kind)
SUFFIXES = {".npy": "npy", ".npz": "npz", ".png": "png", ".tif": "tiff", ".tiff": "tiff"}
#: vert_exag="auto" stretches the heights until the relief is this part of the longer
#: side of the extent (and never flattens them)
AUTO_RELIEF = 0.08
#: names of the height array in an .npz, in the order they are looked for
NPZ_NAMES = ("elevation", "z", "dem", "heights", "height", "Z")
#: bytes a DEM's height takes at most from its file to its first picture (`floatcol
#: terrain` of 4097^2 heights peaked at 1.32-1.43 GB: 79-85 bytes a height, the
#: process's own ~0.12 GB included), which each reader checks from the file's header
#: before it decodes the heights: a 1.8 MB zlib-compressed TIFF of 30000 x 30000
#: zeros took the whole machine's memory
BYTES_PER_HEIGHT = 96


def read_dem(path, *, extent=None, nodata=None, vert_exag=1.0, geographic=None):
    """A HeightField from a DEM file (or a 2-D array, north-up).

    extent: (west, east, south, north) of the first and last columns and rows'
        centres, overriding the file's (default: the file's, else the indices).
    nodata: a height that means "no data" (besides the file's own and NaN): holes.
    vert_exag: heights times this (as matplotlib's LightSource's vert_exag).
    geographic: whether the extent is in degrees of longitude and latitude (then
        converted to metres from the south-west corner); None: as the file says, or
        guessed from an extent inside +-180 x +-90 with cells under a tenth of a degree.
    """
    if isinstance(path, (str, os.PathLike)):
        z, meta = _read(os.fspath(path))
    elif isinstance(path, np.lib.npyio.NpzFile):
        # an .npz already open: matplotlib's get_sample_data("jacksboro_fault_dem.npz")
        z, meta = _read(path)
    else:
        z, meta = _array(path), {}
    vert_exag = _positive("vert_exag", vert_exag)
    with np.errstate(invalid="ignore"):
        # (a damaged file may hold signalling NaNs: every operation on them warns, a
        # second line on the CLI's stderr; they are holes, quiet NaNs from here on)
        z = np.array(z, dtype=np.float64)
    z[np.isnan(z)] = np.nan
    for value in (meta.get("nodata"), nodata):
        if value is not None:
            z[z == float(value)] = np.nan
    if extent is not None:
        meta["extent"] = _extent(extent)
    if geographic is not None:
        meta["geographic"] = bool(geographic)
    ny, nx = z.shape
    west, east, south, north = meta.get("extent", (0.0, nx - 1.0, 0.0, ny - 1.0))
    if meta.get("geographic") is None:
        meta["geographic"] = (max(abs(west), abs(east)) <= 180 and max(abs(south), abs(north))
                              <= 90 and abs(east - west) / max(nx - 1, 1) < 0.1
                              and "extent" in meta)
    degrees = None
    if meta["geographic"]:
        degrees = (west, east, south, north)
        west, east, south, north = _metres(west, east, south, north)
    # north-up rows turned to run south to north; a reversed extent flips back
    hf = HeightField(z[::-1] * vert_exag, u=(west, east), v=(south, north))
    hf.dem = {"extent": (west, east, south, north), "geographic": meta["geographic"],
              "vert_exag": vert_exag, "shape": z.shape, "degrees": degrees}
    return hf


def lonlat(dem, lon, lat, *, extent=None, geographic=None):
    """(u, v): where longitude ``lon`` and latitude ``lat`` (degrees; numbers or
    arrays) lie on a DEM whose coordinates were degrees, in its metres from the
    south-west corner (read_dem's), for ``fly=``, a flight's waypoints, objects'
    positions. ``dem``: a HeightField read by read_dem (or fc.terrain's), or a DEM file
    read as fc.terrain reads it (``extent``, ``geographic`` as read_dem's). A point
    outside the DEM is where it would be. ValueError where the DEM's coordinates were
    not degrees."""
    if not isinstance(dem, HeightField):
        dem, _ = _landscape(dem, 1.0, extent, None, geographic)
    info = getattr(dem, "dem", None)
    degrees = info.get("degrees") if info else None
    if degrees is None:
        (ua, ub), (va, vb) = dem.default_domain
        raise ValueError("the DEM's coordinates are not degrees of longitude and latitude: "
                         f"give points in its own units (it spans u {ua:.6g} to {ub:.6g}, "
                         f"v {va:.6g} to {vb:.6g})")
    try:
        lon = np.asarray(lon, dtype=float)
        lat = np.asarray(lat, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"lon and lat must be numbers of degrees, got {lon!r}, {lat!r}") \
            from None
    if not (np.isfinite(lon).all() and np.isfinite(lat).all()):
        raise ValueError("lon and lat must be finite numbers of degrees")
    west, _, south, _ = degrees
    per_lon, per_lat = _per_degree(*degrees)
    u = (lon - west) * per_lon
    v = (lat - south) * per_lat
    if u.ndim == 0 and v.ndim == 0:
        return float(u), float(v)
    return u, v


def _smooth_allowed(kw):
    """smooth_shading's landscape default: on where the picture takes it (shaded, not
    sub-columns, opaque: passes/normals.py), so that those options given need not
    turn it off."""
    method = kw.get("method", "column")
    try:
        _, sub = antialias(kw.get("antialias", "area"), method, "default")
    except ValueError:
        return False                             # (render says what to fix)
    alpha = kw.get("alpha", kw.get("opacity"))
    opaque = alpha is None or (isinstance(alpha, numbers.Real) and alpha >= 1.0)
    return method == "column" and sub == 1 and opaque


def terrain(source, *, vert_exag="auto", extent=None, nodata=None, geographic=None, fly=None,
            **kw):
    """Draw a DEM (a file, a HeightField or a 2-D array north-up) with landscape
    defaults: ``plot_surface``'s picture and options, with aspect="equal", an earth
    colormap, a sun at azimuth 315 and altitude 35 degrees, elev 35, azim -100 (from
    the south), 1000x600 pixels, antialias="area" (Cohen-Or's area sampling and a level
    of detail: a DEM denser than the pixels neither aliases nor flickers, and renders
    faster than the column pass's corrections on its every cell), smooth_shading=True
    (no lit facets where a coarse DEM's cells are wider than the pixels; off where the
    options given exclude it: sub-columns, opacity, line drawings). vert_exag="auto"
    picks the exaggeration that makes the relief 8 % of the longer side (at least 1);
    the one used is the plot's ``vert_exag``. ``fly``: a fly camera instead of the view
    from outside (camera.fly: its ray march point sampled, its lod engine
    antialiased): the eye's position (u, v) or (u, v, w) in the DEM's units (heights
    exaggerated), or a dict of fly()'s keywords (position, heading, pitch, fov, above,
    near); its elev, azim and projection replace those given. Returns plot_surface's
    SurfacePlot (``.save(path)``, ``.render``)."""
    from .plot import plot_surface
    hf, exag = _landscape(source, vert_exag, extent, nodata, geographic)
    defaults = dict(aspect="equal", cmap="gist_earth", lightsource=(315, 35), elev=35,
                    azim=-100, size=(1000, 600), antialias="area",
                    smooth_shading=_smooth_allowed(kw))
    defaults.update(kw)
    if fly is not None:
        from .camera import fly as fly_camera
        camera = dict(fly) if isinstance(fly, dict) else {"position": fly}
        if "position" not in camera:
            raise ValueError("fly must be the eye's position (u, v) or (u, v, w), or a dict "
                             "of fc.fly's keywords with its position")
        if "size" in camera:
            defaults["size"] = camera.pop("size")
        cam = fly_camera(hf, size=defaults["size"], **camera)
        for key in ("elev", "azim", "proj_type", "projection", "focal_length"):
            defaults.pop(key, None)
        if kw.get("sampling") is not None:
            cam["sampling"] = kw["sampling"]
        # plot_surface takes matplotlib's azimuth (plot.mpl_to_paper_angles inverted)
        cam["azim"] = -90.0 - cam["azim"]
        defaults.update(cam)
        defaults["aspect"] = "equal"            # (the camera is in the DEM's units)
    plot = plot_surface(hf, **defaults)
    plot.vert_exag = exag
    return plot


#: the height fields read from files that something still holds (a plot, a clip): a
#: file read again with the same options, unchanged (its path, size and modification
#: time), is the same height field, its pyramid made already (a 4097^2 DEM's
#: fc.terrain again 1.24 -> 0.26 s)
_READ = weakref.WeakValueDictionary()


def _landscape(source, vert_exag, extent, nodata, geographic):
    """(the height field with its heights exaggerated, the exaggeration) of terrain's
    source and options."""
    if isinstance(source, HeightField):
        hf = source
    else:
        key = None
        if isinstance(source, (str, os.PathLike)):
            try:
                st = os.stat(source)
                key = (os.path.realpath(source), st.st_size, st.st_mtime_ns, repr(extent),
                       repr(nodata), geographic)
            except (OSError, ValueError):
                key = None                      # (read_dem says what is wrong)
        hf = _READ.get(key) if key is not None else None
        if hf is None:
            hf = read_dem(source, extent=extent, nodata=nodata, geographic=geographic)
            if key is not None:
                _READ[key] = hf
    if isinstance(vert_exag, str):
        if vert_exag != "auto":
            raise ValueError(f"vert_exag must be a positive number or 'auto', got {vert_exag!r}")
        exag = auto_exaggeration(hf)
    else:
        exag = _positive("vert_exag", vert_exag)
    if exag != 1.0:
        # (a file's or an array's heights too: a number given was once ignored there)
        hf = hf.scaled(1.0, 1.0, exag)
    return hf, exag


def fly_through(source, path, frames=60, *, heading=None, pitch=-10.0, fov=60.0,
                size=(640, 360), above=None, near=None, closed=False, look_ahead=0.0,
                output=None, fps=20, progress=True, client=None, vert_exag="auto",
                extent=None, nodata=None, geographic=None, **options):
    """A flight over a DEM as a clip: ``frames`` pictures of fc.terrain's fly camera
    (its landscape defaults, area-sampled by the level-of-detail engine) moving at a
    steady speed along a smooth curve through the waypoints ``path`` (camera.flight:
    all (u, v), the eye ``above`` the ground there and never nearer it than half that
    in between, or all (u, v, w); ``closed``: round from the last back to the first,
    a clip that loops without a seam), in the DEM's units with its heights exaggerated
    (``vert_exag``, once for the clip), looking along the curve (``heading`` None;
    ``look_ahead``: toward its point that far ahead, turning into sharp corners
    early) or toward one compass heading, ``pitch`` degrees up with a horizontal field of view
    ``fov``. ``output``: a .gif or .mp4 file to write as the frames come (a long
    flight is never held, animate._collect), ``fps`` frames a second; other
    options as fc.terrain's (texture=, shadows=, objects=, antialias=False for the
    ray march's point samples, ...). ``client``: a dask.distributed Client, the frames
    its tasks (the height field sent to each worker once: floatcol/cluster.py), the
    same pictures in the same order. Returns an Animation whose ``times`` are the
    frames' distances along the curve and whose ``stats`` hold the eye's
    ``positions`` and ``headings``, ``vert_exag``, ``samples`` and ``seconds``."""
    import time

    from tqdm.auto import tqdm

    from .animate import ANIMATION_FORMATS, Animation, _check_fps, _check_memory, _collect
    from .camera import flight
    from .output import check_output
    from .view import check_size
    start = time.perf_counter()
    if "fly" in options:
        raise ValueError("fly_through places the fly camera itself along path: give its "
                         "heading=, pitch=, fov=, above= and near=, not fly=")
    size = check_size(size)
    _check_fps(fps)
    if output is not None:
        output, _ = check_output(output, ANIMATION_FORMATS)
    hf, exag = _landscape(source, vert_exag, extent, nodata, geographic)
    positions, headings, along = flight(hf, path, frames, heading=heading, above=above,
                                        closed=closed, look_ahead=look_ahead)
    _check_memory(frames, size, output)
    cameras = [dict(position=tuple(float(x) for x in pos), heading=float(head), pitch=pitch,
                    fov=fov, near=near, size=size) for pos, head in zip(positions, headings)]
    if client is not None:
        from .cluster import _check_client
        _check_client(client)

    def made():
        if client is not None:
            from .cluster import flight_frames
            yield from flight_frames(hf, cameras, options, client)
            return
        for camera in tqdm(cameras, desc="floatcol fly_through", unit="frame", delay=1.0,
                           disable=not progress, leave=False):
            r = terrain(hf, vert_exag=1.0, fly=camera, **options).draw()
            yield r.rgba, r.stats["samples"]
    # (to an .mp4 the frames are written as they come, a long flight never held)
    out, written, samples = _collect(made(), frames, size, output, fps)
    anim = Animation(out, along, fps, {"samples": samples, "positions": positions,
                                       "headings": headings, "vert_exag": exag,
                                       "seconds": time.perf_counter() - start})
    if output is not None and not written:
        anim.save(output)
    return anim


def auto_exaggeration(hf):
    """The vertical exaggeration that makes a height field's relief (its 1st to 99th
    percentile) AUTO_RELIEF of the longer side of its extent; 1 where it already is
    at least that, or flat. Rounded to two significant digits. The percentiles are
    kept with the height field (a 4097^2 DEM's took 0.24 s of each fc.terrain call)."""
    held = hf.__dict__.get("_relief")
    if held is None:
        z = hf.hf[np.isfinite(hf.hf)]
        held = hf.__dict__["_relief"] = (tuple(np.percentile(z, [1, 99])) if z.size
                                          else None)
    if held is None:
        return 1.0
    lo, hi = held
    (ua, ub), (va, vb) = hf.default_domain
    side = max(ub - ua, vb - va)
    if not hi > lo:
        return 1.0
    k = AUTO_RELIEF * float(side) / float(hi - lo)     # (Python floats: inf, no warning)
    if not math.isfinite(k):
        raise ValueError(f"vert_exag='auto': the relief ({hi - lo:g}) is too small against "
                         f"the extent ({side:g}) for a finite exaggeration; give vert_exag")
    if k <= 1.0:
        return 1.0
    digits = 1 - int(math.floor(math.log10(k)))
    return float(round(k, digits))


def _read(path):
    """(heights, meta) of a DEM file's path, or of an .npz already open; what is
    wrong with it a ValueError naming it."""
    if isinstance(path, np.lib.npyio.NpzFile):
        label, kind = "DEM (an open .npz)", "open npz"
    else:
        suffix = os.path.splitext(path)[1].lower()
        if suffix not in SUFFIXES:
            raise ValueError(f"DEM file {path!r}: use .npy, .npz, .png, .tif or .tiff")
        if not os.path.isfile(path):
            raise ValueError(f"DEM file {path!r} does not exist")
        label, kind = f"DEM file {path!r}", SUFFIXES[suffix]
    try:
        if kind == "open npz":
            return _npz_data(path)
        if kind == "npy":
            heights = np.load(path, mmap_mode="r", allow_pickle=False)   # (its header)
            _check_size(heights.shape)
            return _array(np.array(heights)), {}
        if kind == "npz":
            return _npz(path)
        if kind == "png":
            return _png(path)
        return _geotiff(path)
    except _DemError as exc:
        raise ValueError(f"{label}: {exc}") from None
    except Exception as exc:            # (numpy's, PIL's, tifffile's own errors alike)
        raise ValueError(f"{label} cannot be read: {exc}") from None


class _DemError(ValueError):
    """What is wrong with a DEM file that could be read (its message names it)."""


def _check_size(shape):
    """_DemError where heights of this shape (from a file's header) could not be drawn
    in the machine's memory (BYTES_PER_HEIGHT each), before they are decoded."""
    cells = math.prod(int(n) for n in shape)
    need = cells * BYTES_PER_HEIGHT
    if not fits(need):
        size = " x ".join(str(int(n)) for n in shape)
        raise _DemError(f"its {size} heights need about {need / 2**30:.1f} GiB to draw, more "
                         "than this machine has: crop or downsample it first")


def _npz_shape(data, name):
    """The shape of an open NpzFile's array ``name`` from its header (the array itself
    not decompressed)."""
    with data.zip.open(name + ".npy") as f:
        version = np.lib.format.read_magic(f)
        read = (np.lib.format.read_array_header_1_0 if version == (1, 0)
                else np.lib.format.read_array_header_2_0)
        return read(f)[0]


def _array(z):
    try:
        z = np.asarray(z)
    except Exception as exc:                  # (an object numpy cannot take)
        raise _DemError(f"heights must be a 2-D array of numbers: {exc}") from None
    if z.ndim != 2 or min(z.shape) < 2 or z.dtype.kind not in "biuf":
        raise _DemError(f"heights must be a 2-D array of numbers of at least 2 x 2, got "
                         f"shape {z.shape} of {z.dtype}")
    return z


def _npz(path):
    # the file opened here, so that it is closed where np.load fails on it (numpy
    # leaves the file it opened itself open then: a ResourceWarning)
    with open(path, "rb") as fh, np.load(fh, allow_pickle=False) as data:
        return _npz_data(data)


def _npz_data(data):
    """(heights, meta) of an open NpzFile: the heights under one of NPZ_NAMES (or its
    only 2-D array), the extent of matplotlib's sample DEMs or of x and y, nodata."""
    name = next((n for n in NPZ_NAMES if n in data.files), None)
    if name is None:
        two_d = [n for n in data.files if len(_npz_shape(data, n)) == 2]
        if len(two_d) != 1:
            raise _DemError(f"no height array: name it one of {', '.join(NPZ_NAMES)} "
                             f"(found {', '.join(data.files) or 'nothing'})")
        name = two_d[0]
    _check_size(_npz_shape(data, name))
    z = _array(data[name])
    meta = {}
    keys = set(data.files)
    if {"xmin", "xmax", "ymin", "ymax"} <= keys:
        # matplotlib's sample DEMs: x of the first and last columns' outer edges,
        # y of the first and last rows' (jacksboro's rows run north to south: ymin
        # > ymax); with dx, dy the cells' size, the nodes are the cells' centres
        x0, x1, y0, y1 = (float(data[k]) for k in ("xmin", "xmax", "ymin", "ymax"))
        ny, nx = z.shape
        if {"dx", "dy"} <= keys:
            dx, dy = abs(float(data["dx"])), abs(float(data["dy"]))
            if math.isclose(abs(x1 - x0), nx * dx, rel_tol=1e-3):
                x0, x1 = x0 + math.copysign(dx / 2, x1 - x0), x1 - math.copysign(dx / 2, x1 - x0)
            if math.isclose(abs(y1 - y0), ny * dy, rel_tol=1e-3):
                y0, y1 = y0 + math.copysign(dy / 2, y1 - y0), y1 - math.copysign(dy / 2, y1 - y0)
        meta["extent"] = (x0, x1, min(y0, y1), max(y0, y1))
        if y0 < y1:                       # its first row is the southern one
            z = z[::-1]
    elif {"x", "y"} <= keys and data["x"].ndim == 1 and data["y"].ndim == 1:
        x, y = np.asarray(data["x"], float), np.asarray(data["y"], float)
        if x.size != z.shape[1] or y.size != z.shape[0]:
            raise _DemError(f"x and y have {x.size} and {y.size} values for heights of "
                             f"shape {z.shape}")
        if x[0] > x[-1]:
            z, x = z[:, ::-1], x[::-1]
        if y[0] < y[-1]:                  # north-up rows, as read_dem keeps them
            z, y = z[::-1], y[::-1]
        meta["extent"] = (x[0], x[-1], y[-1], y[0])
    if "nodata" in keys:
        meta["nodata"] = float(data["nodata"])
    return z, meta


def _png(path):
    import warnings

    from PIL import Image
    with warnings.catch_warnings():
        # (Pillow warns of pictures over 89 M pixels, past the CLI's one line: the
        # size check says what is too big; it still refuses over 179 M itself)
        warnings.simplefilter("ignore", Image.DecompressionBombWarning)
        im = Image.open(path)
    with im:
        _check_size((im.size[1], im.size[0]))
        if im.mode in ("I;16", "I;16B", "I;16L", "I", "F", "L"):
            z = np.array(im)
        elif im.mode in ("LA", "La", "P", "PA", "RGB", "RGBA"):
            raise _DemError(f"a DEM PNG is greyscale (8 or 16 bits), this one is {im.mode}")
        else:
            z = np.array(im.convert("I"))
    return _array(z), {}


def _geotiff(path):
    try:
        import tifffile
    except ImportError:
        raise _DemError("reading GeoTIFF needs the optional extra: pip install "
                         "'floatcol[geotiff]' (tifffile)") from None
    import logging
    # tifffile logs what it finds wrong in a damaged file (its own names, on stderr
    # past the CLI's one line): the error raised below says it instead
    log = logging.getLogger("tifffile")
    level = log.level
    log.setLevel(logging.CRITICAL + 1)
    try:
        with tifffile.TiffFile(path) as tif:
            if not tif.pages:
                raise _DemError("no image in the file")
            page = tif.pages[0]
            _check_size(page.shape)
            z = page.asarray()
            if z.ndim == 3 and z.shape[-1] == 1:
                z = z[..., 0]
            z = _array(z)
            tags = {t.code: t.value for t in page.tags.values()}
    finally:
        log.setLevel(level)
    meta = {}
    if 42113 in tags:                                 # GDAL_NODATA (text)
        try:
            meta["nodata"] = float(str(tags[42113]).strip().strip("\x00"))
        except ValueError:
            pass
    keys = _geokeys(tags.get(34735))
    if 33550 in tags and 33922 in tags:               # ModelPixelScale, ModelTiepoint
        sx, sy = float(tags[33550][0]), float(tags[33550][1])
        i, j, _, x, y, _ = (float(a) for a in tags[33922][:6])
        if keys.get(1025, 1) == 1:                    # RasterPixelIsArea: corner ties
            i, j = i - 0.5, j - 0.5
        ny, nx = z.shape
        west = x - i * sx
        north = y + j * sy
        meta["extent"] = (west, west + (nx - 1) * sx, north - (ny - 1) * sy, north)
        if 1024 in keys:                              # GTModelTypeGeoKey: 2 geographic
            meta["geographic"] = keys[1024] == 2
    return z, meta


def _geokeys(directory):
    """{key id: value} of a GeoKeyDirectoryTag's keys held in the directory itself."""
    out = {}
    if directory is None:
        return out
    d = [int(a) for a in directory]
    for k in range(d[3] if len(d) >= 4 else 0):
        key, location, _, value = d[4 + 4 * k: 8 + 4 * k]
        if location == 0:
            out[key] = value
    return out


def _metres(west, east, south, north):
    """A geographic extent in degrees as metres from its south-west corner."""
    per_lon, per_lat = _per_degree(west, east, south, north)
    return 0.0, (east - west) * per_lon, 0.0, (north - south) * per_lat


def _per_degree(west, east, south, north):
    """The metres in a degree of longitude and of latitude at a geographic extent's
    middle latitude (WGS 84)."""
    phi = math.radians(0.5 * (south + north))
    per_lat = 111132.954 - 559.822 * math.cos(2 * phi) + 1.175 * math.cos(4 * phi)
    per_lon = 111412.84 * math.cos(phi) - 93.5 * math.cos(3 * phi)
    return per_lon, per_lat


def _extent(extent):
    try:
        w, e, s, n = (float(a) for a in extent)
    except (TypeError, ValueError):
        raise ValueError(f"extent must be (west, east, south, north), got {extent!r}") from None
    if not all(math.isfinite(a) for a in (w, e, s, n)) or w == e or s == n:
        raise ValueError(f"extent must be four finite numbers with west != east and south != "
                         f"north, got {extent!r}")
    return w, e, s, n


def _positive(name, x):
    try:
        x = float(x)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a positive number, got {x!r}") from None
    if not (math.isfinite(x) and x > 0):
        raise ValueError(f"{name} must be a positive number, got {x!r}")
    return x


#: Guedes et al.'s variants (kernels/voxel.py)
GUEDES_VARIANTS = {"standard": 0, "naive": 1, "uncorrected": 2, "corrected": 3, "brute": 4}


def guedes(hf, position, heading=0.0, pitch=-10.0, fov=60.0, size=(640, 360), *,
           variant="corrected", above=None, cmap="gist_earth", background="lightskyblue"):
    """A picture of a height field by one of Guedes et al.'s (1997) voxel renderers, for
    comparison with floatcol's exact perspective (fc.fly + render): "standard" (a
    vertical view plane, the window shifted), "naive" (his 5a), "uncorrected" and
    "corrected" (his 5b without and with the sampling correction of eq. 7), "brute"
    (each ray cast on its own). The camera as fc.fly's. Returns (rgba (H, W, 4) uint8:
    each voxel coloured by its height through ``cmap``, unlit; uv (H, W, 2) the world
    point each pixel shows, NaN where the sky; seconds)."""
    import time

    from . import color
    from .camera import fly
    from .kernels.voxel import voxel_kernel
    if variant not in GUEDES_VARIANTS:
        raise ValueError(f"variant must be one of {', '.join(GUEDES_VARIANTS)}, got "
                         f"{variant!r}")
    if not isinstance(hf, HeightField):
        raise ValueError("guedes draws a HeightField (a DEM: fc.read_dem)")
    cam = fly(hf, position, heading, pitch, fov, size, above=above)
    cam.pop("sampling")
    W, H = cam["size"]
    b = math.radians(heading)
    eye = np.array(cam["center"]) - (cam["d1"] + cam["d2"]) * np.array(
        [math.sin(b) * math.cos(math.radians(pitch)), math.cos(b) * math.cos(math.radians(pitch)),
         math.sin(math.radians(pitch))])
    (ua, ub), (va, vb) = hf.default_domain
    ext = np.array([ua, ub, va, vb], dtype=float)
    focal = 0.5 * max(W - 1, 1) / math.tan(math.radians(fov) / 2)   # (as fly's scale)
    steps = int(2 * max(hf.hf.shape))
    uv = np.empty((H, W, 2))
    t = time.perf_counter()
    voxel_kernel(hf.hf, ext, eye, np.array([math.sin(b), math.cos(b)]),
                 GUEDES_VARIANTS[variant], math.radians(pitch), focal, steps, uv)
    seconds = time.perf_counter() - t
    lut = color.colormap_lut(cmap)
    z = hf.hf[np.isfinite(hf.hf)]
    lo, hi = (float(z.min()), float(z.max())) if z.size else (0.0, 1.0)
    nv, nu = hf.hf.shape
    seen = np.isfinite(uv[..., 0])
    gi = np.clip(np.round((uv[..., 0] - ua) / (ub - ua) * (nu - 1)), 0, nu - 1)
    gj = np.clip(np.round((uv[..., 1] - va) / (vb - va) * (nv - 1)), 0, nv - 1)
    h = hf.hf[np.where(seen, gj, 0).astype(int), np.where(seen, gi, 0).astype(int)]
    idx = np.clip((h - lo) / max(hi - lo, 1e-12) * (len(lut) - 1), 0, len(lut) - 1)
    rgba = np.empty((H, W, 4), np.uint8)
    rgba[...] = color.to_rgba8(background)
    rgba[seen, :3] = np.round(lut[np.nan_to_num(idx).astype(int)][seen, :3] * 255)
    rgba[seen, 3] = 255
    return rgba, uv, seconds
