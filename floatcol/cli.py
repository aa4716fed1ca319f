"""The ``floatcol`` command. It calls the public API only (never a kernel).

User mistakes (a bad expression, range, option or path) print one line on stderr and
exit with status 2, and leave no output file behind: every file is written to a
temporary name and renamed at the end.
"""
from __future__ import annotations

import argparse
import contextlib
import os
import re
import sys
import warnings

EXAMPLES = """examples:
  floatcol render "3*sin(u*cos(v))" --u=-5:5 --v=-5:5 -o surface.png
  floatcol render "x**2 - y**2" --x=-2:2 --y=-2:2 --proj ortho --elev 40 -o saddle.pdf
  floatcol render "sin(x*y)" --method horizon --size 800x600 -o lines.png
  floatcol render "sin(x)*cos(y)" --x -pi:pi --y -pi:pi --aspect equal -o waves.png
  floatcol render "x*y/3" "2*exp(-x^2-y^2) - 0.5" --x=-2:2 --y=-2:2 -o two.png
  floatcol animate "exp(-(x^2+y^2)/8)*cos(2*sqrt(x^2+y^2) - t)" --x=-6:6 --y=-6:6 --t 0:6.283 --frames 48 -o wave.gif
  floatcol terrain dem.tif --vert-exag 2 -o dem.png
  floatcol gallery build -o site/gallery
"""
TERRAIN_EXAMPLES = """examples:
  floatcol terrain dem.tif -o dem.png
  floatcol terrain heights.png --extent 0:30000:0:20000 --vert-exag 3 --shadows -o relief.png
  floatcol terrain dem.npz --antialias area --elev 20 --azim -80 -o low.png
  floatcol terrain dem.tif --fly 15000:2500 --heading 15 --pitch -10 --above 900 -o fly.png
  floatcol terrain dem.tif --fly 15000:2500 --fly 15500:9000 --frames 90 -o flight.gif
"""

RENDER_OUTPUTS = (".png", ".jpg", ".jpeg", ".tif", ".tiff", ".webp", ".pdf", ".svg", ".eps", ".ps")
ANIMATION_OUTPUTS = (".gif", ".mp4")


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def __init__(self, *args, **kw):
        super().__init__(*args, **kw)
        # a value that starts with a minus and a digit is a value, not an option (as
        # Python 3.13's argparse has it): --fly -84.3:36.5, --u -5:5
        self._negative_number_matcher = re.compile(r"^-\.?\d")

    def error(self, message):          # one line, exit 2, no usage dump
        raise UsageError(message)


def _pair(text, sep, message):
    """Two numbers or constant formulas joined by ``sep``; ``message`` if not."""
    try:
        a, b = (_number(x) for x in text.split(sep))
    except ValueError:
        raise argparse.ArgumentTypeError(message) from None
    return a, b


def _range(text):
    return _pair(text, ":", f"range {text!r} must be LOW:HIGH, e.g. -5:5 or -pi:2*pi")


def _number(text):
    """A bound: a number, or a constant expression such as 2*pi or sqrt(2) (read by
    floatcol's parser, which never evaluates the text)."""
    from .expression import constant
    return constant(text)


def _count(name, lo, hi):
    """An argparse type: a whole number from lo to hi."""
    def parse(text):
        try:
            n = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a whole number, got {text!r}")
        if not lo <= n <= hi:
            raise argparse.ArgumentTypeError(f"{name} must be from {lo} to {hi}, got {n}")
        return n
    return parse


def _value(name):
    """An argparse type: a number or constant expression (floatcol's parser)."""
    def convert(text):
        try:
            return _number(text)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(f"--{name}: {exc}") from None
    return convert


def _sun(text):
    """--light AZ/ALT: two numbers or constant formulas (floatcol's parser)."""
    return _pair(text, "/", f"light {text!r} must be AZ/ALT in degrees, e.g. 315/25")


def _aspect(text):
    if text in ("auto", "equal", "equalxy"):
        return text
    try:
        box = tuple(float(x) for x in text.split(":"))
    except ValueError:
        box = ()
    if len(box) != 3 or not all(0 < x < float("inf") for x in box):
        raise argparse.ArgumentTypeError(f"aspect {text!r} must be auto, equal, equalxy or a "
                                         "box BX:BY:BZ of positive numbers, e.g. 1:1:0.5")
    return box


def _exaggeration(text):
    if text == "auto":
        return text
    try:
        x = _number(text)
    except ValueError:
        x = -1.0
    if not 0 < x < float("inf"):
        raise argparse.ArgumentTypeError(f"vert-exag {text!r} must be auto or a positive number")
    return x


def _eye(text):
    """--fly U:V or U:V:W: two or three numbers or constant formulas."""
    try:
        vals = tuple(_number(x) for x in text.split(":"))
    except ValueError:
        vals = ()
    if len(vals) not in (2, 3):
        raise argparse.ArgumentTypeError(f"fly {text!r} must be U:V or U:V:W, e.g. "
                                         "15000:2500 or 15000:2500:1200")
    return vals


def _four(text):
    try:
        vals = tuple(_number(x) for x in text.split(":"))
    except ValueError:
        vals = ()
    if len(vals) != 4:
        raise argparse.ArgumentTypeError(f"extent {text!r} must be W:E:S:N, e.g. 0:1000:0:800")
    return vals


def _size(text):
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size {text!r} must be WIDTHxHEIGHT, e.g. 800x600") from None
    return w, h


def _surface_options(p, default_size="800x600", many=False, terrain=False):
    """Options shared by render, animate and terrain; they mirror plot_surface's."""
    if terrain:
        p.add_argument("file", help="a DEM: .npy, .npz, .png (16-bit grey), .tif/.tiff "
                       "(GeoTIFF, with the extra floatcol[geotiff])")
    elif many:
        p.add_argument("expr", nargs="+", help="the height as a formula, e.g. '3*sin(u*cos(v))' "
                       "(^ is power); several: one picture where they hide each other")
    else:
        p.add_argument("expr", help="the height as a formula, e.g. '3*sin(u*cos(v))' (^ is power)")
    if not terrain:
        p.add_argument("--u", "--x", dest="u", type=_range, default=None, metavar="LOW:HIGH",
                       help="range of the first variable (default -10:10)")
        p.add_argument("--v", "--y", dest="v", type=_range, default=None, metavar="LOW:HIGH",
                       help="range of the second variable (default -10:10)")
        p.add_argument("--vars", default=None, metavar="X,Y",
                       help="the two variables, in order (default: the formula's symbols "
                            "sorted, as sympy)")
    p.add_argument("--size", type=_size, default=_size(default_size), metavar="WxH",
                   help=f"pixels (default {default_size})")
    p.add_argument("--elev", type=float, default=30.0, help="degrees above the surface (default 30, as matplotlib)")
    p.add_argument("--azim", type=float, default=-60.0, help="azimuth of the eye in degrees (default -60, as matplotlib)")
    p.add_argument("--proj", default="persp", choices=["persp", "ortho", "perspective", "orthographic"],
                   help="projection (default persp, as matplotlib)")
    p.add_argument("--focal-length", type=float, default=None, help="perspective focal length, as matplotlib")
    p.add_argument("--aspect", type=_aspect, default="auto",
                   metavar="{auto,equal,equalxy,BX:BY:BZ}",
                   help="the box's proportions: auto (default, as matplotlib: the ranges of "
                        "x, y and the height fill 4:4:3), equal (true proportions), equalxy, "
                        "or a box BX:BY:BZ")
    p.add_argument("--method", default="column", choices=["column", "horizon"],
                   help="shaded floating column or monochrome floating horizon")
    p.add_argument("--shading", default="default", choices=["default", "lambert"])
    p.add_argument("--interpolation", default="normal", choices=["normal", "intensity"],
                   help="normal (nis, per pixel) or intensity (iis, Gouraud)")
    p.add_argument("--corrections", default=None,
                   choices=["none", "spline", "supersample", "adaptive", "spline+supersample",
                            "spline+adaptive"],
                   help="the paper's artifact corrections (default spline+adaptive)")
    p.add_argument("--antialias", default=None, choices=["on", "off", "2", "3", "4", "area"],
                   help="on: coverage along columns; 2-4: also that many sub-columns; area: "
                        "exact area sampling along columns, a height field's level of detail "
                        "(Cohen-Or 1997; no flicker on dense terrain) (default on, off with "
                        "--shading lambert)")
    p.add_argument("--device", default=None, choices=["cpu", "cuda"],
                   help="where the column pass runs: cpu (default) or cuda, an NVIDIA GPU "
                        "(pip install 'floatcol[cuda]')")
    p.add_argument("--sampling", default=None, choices=["uniform", "adaptive", "lod", "march"],
                   help="adaptive: planes grow with distance and where the normal turns slowly; "
                        "lod: a fly-through's level of detail; march: its pixel rays marched "
                        "through the same planes (faster; point sampled, --antialias off; else "
                        "as lod: --fly's default)")
    p.add_argument("--lines", type=int, default=None, help="horizon: number of lines (default 160)")
    p.add_argument("--cmap", default=None, help="matplotlib colormap of the upper side (default viridis)")
    p.add_argument("--color", default=None, help="one colour for the upper side instead of a colormap")
    p.add_argument("--lower-color", default=None,
                   help="colour of the lower side (\"same\": the upper side's at its height)")
    p.add_argument("--vmin", type=_value("vmin"), default=None,
                   help="height at the colormap's start (a number or a constant such as pi/2)")
    p.add_argument("--vmax", type=_value("vmax"), default=None,
                   help="height at the colormap's end (a number or a constant such as pi/2)")
    p.add_argument("--norm", default=None, choices=["linear", "log", "symlog", "asinh", "logit"],
                   help="the colormap's scale of the heights, as matplotlib's norm=\"log\" "
                        "(default linear; with --vmin/--vmax its ends)")
    p.add_argument("--no-shade", action="store_true", help="flat colours, no lighting")
    p.add_argument("--smooth-shading", action=argparse.BooleanOptionalAction, default=None,
                   help="a height field lit by normals interpolated between its nodes, as a "
                        "hillshade, not its cells' own: no facets on a coarse DEM seen up "
                        "close (default: off; on for terrain)")
    p.add_argument("--ambient", type=_value("ambient"), default=None, metavar="A",
                   help="the ambient share of the light, 0 to 1 (default 0.25)")
    p.add_argument("--specular", type=_value("specular"), default=None, metavar="S",
                   help="the highlights' strength (default 0.2; 0: none)")
    p.add_argument("--shininess", type=_value("shininess"), default=None, metavar="N",
                   help="the highlights' Phong exponent (default 30: larger, smaller spots)")
    p.add_argument("--pixel-step", type=_value("pixel-step"), default=None, metavar="PX",
                   help="pixels between sampling planes (default 1; larger: faster, coarser)")
    p.add_argument("--texture-filter", choices=("mipmap", "linear", "point"), default=None,
                   help="how --texture is read: mipmap (default, no shimmer), linear or point")
    p.add_argument("--light", type=_sun, default=None, metavar="AZ/ALT",
                   help="a sun fixed to the surface: azimuth clockwise from north and altitude, "
                        "in degrees, as matplotlib's LightSource (e.g. 315/25)")
    p.add_argument("--shadows", action="store_true",
                   help="the light casts shadows (Gordon 6.2): with --light, or the default light")
    p.add_argument("--shadow-method", choices=("texture", "on-the-fly"), default=None,
                   help="how cast shadows are found: a shadow texture (Gordon 6.2.1, the "
                        "default) or on the fly (6.2.2: no texture; one surface); with --shadows")
    p.add_argument("--light-radius", type=_value("light-radius"), default=None, metavar="DEG",
                   help="soft shadows from a light of this angular radius in degrees (the sun: "
                        "0.27); with --shadows")
    p.add_argument("--opacity", type=_value("opacity"), default=None,
                   help="below 1 the surfaces are translucent, every layer showing (Gordon 6.5), "
                        "e.g. 0.5 (default 1)")
    p.add_argument("--texture", default=None, metavar="IMAGE",
                   help="an image file draped over the domain (section 6.7; mip-mapped)")
    p.add_argument("--color-by", default=None, metavar="EXPR",
                   help="colour from data: a second formula of the variables, coloured "
                        "by --cmap instead of the height")
    p.add_argument("--contours", type=_count("contours", 1, 1000), default=None,
                   metavar="N", help="N contour lines (of the height, or of --color-by)")
    p.add_argument("--wireframe", type=_count("wireframe", 2, 10000), default=None,
                   metavar="N", help="N lines at x = const and N at y = const")
    p.add_argument("--lines-only", action="store_true",
                   help="the --wireframe and --contours lines alone, the surface not drawn "
                        "but hiding the lines behind it (a hidden-line drawing)")
    p.add_argument("--background", default=None, help="background colour, e.g. white or none")
    p.add_argument("--dpi", type=float, default=100.0, help="dots per inch of PDF/SVG output (default 100)")


def build_parser():
    from . import __version__
    p = _Parser(prog="floatcol", description="Shaded pictures of w = f(u, v) by the floating "
                "column algorithm (Gordon 2001).", epilog=EXAMPLES,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version", version=f"floatcol {__version__}")
    sub = p.add_subparsers(dest="command", parser_class=_Parser, metavar="{render,animate,terrain,gallery}")
    r = sub.add_parser("render", help="render an expression to an image (png, jpg, pdf, svg)",
                       epilog=EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    _surface_options(r, many=True)
    r.add_argument("-o", "--output", default="surface.png",
                   help="file to write: .png, .jpg, .tif, .webp, .pdf, .svg, .eps or .ps (default surface.png)")
    a = sub.add_parser("animate", help="render w = f(u, v, t) to a GIF or MP4",
                       epilog=EXAMPLES, formatter_class=argparse.RawDescriptionHelpFormatter)
    _surface_options(a, default_size="480x360")
    a.add_argument("-o", "--output", default="surface.gif", help="file to write: .gif or .mp4")
    a.add_argument("--t", dest="t", type=_range, default=(0.0, 6.283185307179586),
                   metavar="LOW:HIGH", help="time range (default 0:2pi)")
    a.add_argument("--time-var", default="t", help="name of the time variable (default t)")
    a.add_argument("--frames", type=int, default=60, help="number of frames (default 60)")
    a.add_argument("--fps", type=float, default=20.0,
                   help="frames per second, 0.01 to 120 (default 20)")
    t = sub.add_parser("terrain", help="render a DEM file (a terrain) to an image",
                       epilog=TERRAIN_EXAMPLES,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    _surface_options(t, default_size="1000x600", terrain=True)
    t.set_defaults(elev=35.0, azim=-100.0, aspect="equal", cmap="gist_earth", light=(315.0, 35.0),
                   antialias="area")
    t.add_argument("--vert-exag", type=_exaggeration, default="auto", metavar="X",
                   help="heights times X (default auto: the relief 8%% of the longer side)")
    t.add_argument("--extent", type=_four, default=None, metavar="W:E:S:N",
                   help="west, east, south, north of the first and last columns and rows "
                        "(default: the file's, else the indices)")
    t.add_argument("--nodata", type=_value("nodata"), default=None,
                   help="a height that means no data (a hole), besides the file's own")
    t.add_argument("--fly", type=_eye, default=None, action="append", metavar="U:V[:W]",
                   help="fly: the eye inside the scene at (u, v), --above the ground there, "
                        "or at (u, v, w) (the DEM's units, heights exaggerated); replaces "
                        "--elev, --azim and --proj (Guedes 1997; sampling march). Given "
                        "again: waypoints of a flight, written as a .gif or .mp4 clip of "
                        "--frames frames along a smooth curve through them")
    t.add_argument("--degrees", action="store_true",
                   help="--fly's U:V are longitude:latitude in degrees (a DEM whose "
                        "coordinates are degrees: fc.lonlat); W stays a height")
    t.add_argument("--heading", type=_value("heading"), default=None,
                   help="fly: compass heading in degrees clockwise from north (default 0; "
                        "a flight's: along its curve)")
    t.add_argument("--frames", type=int, default=None,
                   help="a flight's number of frames (default 60)")
    t.add_argument("--fps", type=float, default=None,
                   help="a flight's frames per second, 0.01 to 120 (default 20)")
    t.add_argument("--closed", action="store_true",
                   help="a flight goes on from its last waypoint back to its first: a clip "
                        "that loops without a seam")
    t.add_argument("--look-ahead", type=_value("look-ahead"), default=None, metavar="D",
                   help="a flight looks toward its curve's point D ahead (the DEM's units) "
                        "instead of along it: it turns into sharp corners early")
    t.add_argument("--pitch", type=_value("pitch"), default=-10.0,
                   help="fly: degrees up (negative: down; default -10)")
    t.add_argument("--fov", type=_value("fov"), default=60.0,
                   help="fly: horizontal field of view in degrees (default 60)")
    t.add_argument("--above", type=_value("above"), default=None,
                   help="fly: the eye's height above the ground (default 5%% of the DEM's "
                        "longer side)")
    t.add_argument("-o", "--output", default="terrain.png",
                   help="file to write: .png, .jpg, .tif, .webp, .pdf, .svg, .eps or .ps "
                        "(default terrain.png)")
    g = sub.add_parser("gallery", help="build the example gallery")
    gsub = g.add_subparsers(dest="gallery_command", parser_class=_Parser, metavar="{build}")
    gb = gsub.add_parser("build", help="run the gallery scripts; write images, thumbnails and index.html")
    gb.add_argument("-o", "--output", default="gallery-build", help="folder to write (default gallery-build)")
    gb.add_argument("--source", default=None, help="folder of example scripts (default: the gallery/ of this checkout)")
    gb.add_argument("--only", nargs="+", default=None, metavar="NAME", help="build only these examples")
    gb.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run the examples on the workers of this dask.distributed scheduler "
                         "(e.g. tcp://host:8786; pip install 'floatcol[dask]')")
    return p


_RANGES = ("--u", "--v", "--x", "--y", "--t")
_NEGATIVE_OK = _RANGES + ("--vmin", "--vmax", "--elev", "--azim", "--light", "--extent",
                          "--nodata")


def _fix_negative_values(argv):
    """Let '--u -5:5', '--u -pi:pi' and '--azim -60' work: argparse would take '-5:5'
    for an option."""
    out = []
    i = 0
    while i < len(argv):
        a = argv[i]
        nxt = argv[i + 1] if i + 1 < len(argv) else ""
        if a in _NEGATIVE_OK and nxt[:1] == "-" and (nxt[1:2] in "0123456789." or (
                a in _RANGES + ("--extent",) and ":" in nxt)
                or (a == "--light" and "/" in nxt)):  # -5, -pi:pi
            out.append(f"{a}={nxt}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    with warnings.catch_warnings():
        warnings.showwarning = _show_warning
        return _main(argv)


def _show_warning(message, category, filename, lineno, file=None, line=None):
    """A warning (an empty picture, say) as one line on stderr."""
    print(f"floatcol: warning: {message}", file=sys.stderr)


def _main(argv):
    try:
        args = build_parser().parse_args(_fix_negative_values(argv))
        if args.command is None:
            raise UsageError("say what to do, e.g. floatcol render \"3*sin(u*cos(v))\" -o surface.png")
        if args.command == "render":
            return _render(args)
        if args.command == "animate":
            return _animate(args)
        if args.command == "terrain":
            return _terrain(args)
        if args.gallery_command is None:
            raise UsageError("say what to do: floatcol gallery build -o DIR")
        return _gallery(args)
    except UsageError as exc:
        print(f"floatcol: error: {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"floatcol: error: {cli_words(str(exc))}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"floatcol: error: cannot write {getattr(exc, 'filename', '') or 'output'}: "
              f"{exc.strerror or exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("floatcol: interrupted", file=sys.stderr)
        return 130


#: the library's keywords (and keyword=value forms) that the command line spells as
#: options of its own (_options)
_API_TO_CLI = {
    "fill=False": "--lines-only", "shade=False": "--no-shade", "shadows=True": "--shadows",
    "smooth_shading": "--smooth-shading",
    "alpha": "--opacity", "lightsource": "--light", "color_field": "--color-by",
    "proj_type": "--proj", "projection": "--proj", "focal_length": "--focal-length",
    "lower_color": "--lower-color", "light_radius": "--light-radius",
    "vert_exag": "--vert-exag", "pixel_step": "--pixel-step", "texture_filter": "--texture-filter",
    "look_ahead": "--look-ahead",
}
#: keywords spelled the same way, --NAME
_SAME = ("opacity", "wireframe", "contours", "shading", "shadows", "antialias", "sampling",
         "corrections", "interpolation", "aspect", "vmin", "vmax", "cmap", "texture",
         "background", "device", "method", "lines", "size", "elev", "azim", "dpi", "pitch",
         "fov", "heading", "above", "extent", "nodata", "frames", "fps", "ambient", "specular",
         "shininess", "norm")


def cli_words(message):
    """An error message of the library in the command line's words: its keywords as
    the options that set them ("fill=False draws ... give wireframe= or contours=" ->
    "--lines-only draws ... give --wireframe or --contours"). A keyword is replaced
    where it cannot be a plain word: as ``name=`` (``name='value'`` becomes
    ``--name value``, and so does advice such as "give opacity=1"), with an
    underscore, or starting the message ("opacity must be ..."). What the message
    quotes (the user's expression, a value given) stays as it is."""
    if "\x00" in message:              # (the marks of the quoted parts, below)
        return message
    names = [n for n in list(_API_TO_CLI) + list(_SAME) if "=" not in n and "_" not in n]
    flag_of = {n: _API_TO_CLI.get(n, "--" + n) for n in names}
    pattern = "|".join(sorted(names, key=len, reverse=True))
    # name='value' -> --name value (the library's own advice)
    message = re.sub(rf"(?<![\w-])({pattern})='([\w -]*)'",
                     lambda m: f"{flag_of[m.group(1)]} {m.group(2)}", message)
    message = re.sub(r"\bvars=\('(\w+)', '(\w+)'\)", r"--vars \1,\2", message)
    message = message.replace("(give a range (symbol, low, high) for each variable)",
                              "(name the two with --vars X,Y)")
    # the rest of what is quoted is kept: out of the way while the words are replaced
    quoted = []

    def keep(m):
        quoted.append(m.group(0))
        return f"\x00{len(quoted) - 1}\x00"
    # (a quote opens after no letter: "the surface's" is a possessive)
    message = re.sub(r"(?<!\w)'[^']*'(?!\w)|\"[^\"]*\"", keep, message)
    for api, flag in _API_TO_CLI.items():
        if "=" in api or "_" in api:
            message = re.sub(rf"\b{re.escape(api)}\b", flag, message)
    message = re.sub(rf"(?<![\w-])({pattern})=(?=\s|[,;:)]|$)", lambda m: flag_of[m.group(1)],
                     message)
    # advice with a value: "give opacity=1" -> "give --opacity 1" (not a value reported
    # back: "got vmin=3")

    def advice(m):
        flag, value = flag_of[m.group(2)], m.group(3)
        if flag == "--antialias":
            value = {"True": "on", "False": "off"}.get(value, value)
        elif value == "True":
            return f"{m.group(1)} {flag}"
        return f"{m.group(1)} {flag} {value}"
    message = re.sub(rf"\b(give|use|with|set|pass|or) ({pattern})=([\w.+-]+)", advice,
                     message)
    message = re.sub(rf"^({pattern})(?= )", lambda m: flag_of[m.group(1)], message)
    return re.sub(r"\x00(\d+)\x00", lambda m: quoted[int(m.group(1))], message)


def _check_output(path, allowed):
    """Refuse a bad output path before any work (the same checks the writers make)."""
    from .output import check_output
    check_output(path, dict.fromkeys(allowed))


def _ranges(args):
    names = None
    if args.vars:
        names = [n.strip() for n in args.vars.split(",")]
        if len(names) != 2 or not all(n.isidentifier() for n in names):
            raise UsageError(f"--vars {args.vars!r} must name two variables, e.g. x,y")
    if names is None:
        if args.u is None and args.v is None:
            return ()
        from .plot import parse_ranges
        expr = args.expr if isinstance(args.expr, str) else " + ".join(f"({e})" for e in args.expr)
        names, _ = parse_ranges(expr, (), extra=(getattr(args, "time_var", None),))
    return tuple((n, *(r if r is not None else (-10.0, 10.0)))
                 for n, r in zip(names, (args.u, args.v)))


def _options(args):
    opts = dict(size=args.size, elev=args.elev, azim=args.azim, proj_type=args.proj,
                method=args.method, shading=args.shading, interpolation=args.interpolation,
                dpi=args.dpi, aspect=args.aspect)
    if args.antialias is not None:
        opts["antialias"] = {"on": True, "off": False, "2": 2, "3": 3, "4": 4,
                             "area": "area"}[args.antialias]
    for name in ("focal_length", "cmap", "color", "vmin", "vmax", "lines", "corrections",
                 "sampling", "device", "ambient", "specular", "shininess", "pixel_step",
                 "texture_filter", "norm"):
        value = getattr(args, name)
        if value is not None:
            opts[name] = value
    if args.lower_color is not None:
        opts["lower_color"] = args.lower_color
    if args.no_shade:
        opts["shade"] = False
    if args.smooth_shading is not None:
        opts["smooth_shading"] = args.smooth_shading
    if args.light is not None:
        opts["lightsource"] = args.light
    if args.shadows:
        opts["shadows"] = args.shadow_method or True
    elif args.shadow_method is not None:
        raise ValueError("--shadow-method says how shadows are cast: give --shadows too")
    if args.light_radius is not None:
        opts["light_radius"] = args.light_radius
    if args.opacity is not None:
        opts["alpha"] = args.opacity
    if args.background is not None:
        opts["background"] = None if args.background.lower() == "none" else args.background
    if args.texture is not None:
        opts["texture"] = args.texture
    if args.color_by is not None:
        opts["color_field"] = args.color_by
    if args.contours is not None:
        opts["contours"] = args.contours
    if args.wireframe is not None:
        opts["wireframe"] = args.wireframe
    if getattr(args, "lines_only", False):
        opts["fill"] = False
    return opts


def _render(args):
    _check_output(args.output, RENDER_OUTPUTS)
    import floatcol as fc
    plot = fc.plot_surface(list(args.expr), *_ranges(args), **_options(args))
    plot.save(args.output)
    s = plot.render.stats
    print(f"wrote {args.output} ({args.size[0]}x{args.size[1]}, {s['samples']} samples, "
          f"{s['seconds'] * 1e3:.0f} ms)")
    return 0


def _animate(args):
    _check_output(args.output, ANIMATION_OUTPUTS)
    import floatcol as fc
    anim = fc.animate(args.expr, *_ranges(args), t=(args.time_var, *args.t), frames=args.frames,
                      fps=args.fps, output=args.output, **_options(args))
    print(f"wrote {args.output} ({len(anim)} frames, {args.size[0]}x{args.size[1]}, "
          f"{anim.stats['seconds']:.1f} s)")
    return 0


def _terrain(args):
    if args.degrees:
        if args.fly is None:
            raise UsageError("--degrees says --fly's U:V are longitude:latitude: give --fly")
        import floatcol as fc
        args.fly = [fc.lonlat(args.file, p[0], p[1], extent=args.extent) + tuple(p[2:])
                    for p in args.fly]
    if args.fly is not None and len(args.fly) > 1:
        return _flight(args)
    if os.path.splitext(args.output)[1].lower() in ANIMATION_OUTPUTS:
        raise UsageError(f"{args.output!r} would be a flight's clip: give --fly two or more "
                         "times, its waypoints (one --fly is a picture: .png, .jpg, ...)")
    given = [f for f, v in (("--frames", args.frames), ("--fps", args.fps),
                            ("--closed", args.closed), ("--look-ahead", args.look_ahead))
             if v not in (None, False)]
    if given:
        raise UsageError(f"{given[0]} is a flight's: give --fly two or more times, its "
                         "waypoints, and write a .gif or .mp4")
    _check_output(args.output, RENDER_OUTPUTS)
    import floatcol as fc
    fly = None
    if args.fly is not None:
        fly = dict(position=args.fly[0], heading=args.heading or 0.0, pitch=args.pitch,
                   fov=args.fov, above=args.above)
    plot = fc.terrain(args.file, vert_exag=args.vert_exag, extent=args.extent,
                      nodata=args.nodata, fly=fly, **_options(args))
    plot.save(args.output)
    s = plot.render.stats
    print(f"wrote {args.output} ({args.size[0]}x{args.size[1]}, heights x{plot.vert_exag:g}, "
          f"{s['seconds'] * 1e3:.0f} ms)")
    if not (plot.render.side != 0).any():
        (ua, ub), (va, vb) = plot.surface.default_domain
        print(f"floatcol: note: nothing of the DEM is in view; it spans u {ua:.6g} to "
              f"{ub:.6g}, v {va:.6g} to {vb:.6g} (metres where its coordinates were "
              "degrees)", file=sys.stderr)
    return 0


def _flight(args):
    """floatcol terrain with --fly given more than once: a flight's clip."""
    if os.path.splitext(args.output)[1].lower() not in ANIMATION_OUTPUTS:
        raise UsageError(f"several --fly waypoints make a flight: write it as .gif or .mp4, "
                         f"not {args.output!r}")
    if len({len(p) for p in args.fly}) != 1:
        raise UsageError("a flight's --fly waypoints must be all U:V (the eye --above the "
                         "ground) or all U:V:W")
    _check_output(args.output, ANIMATION_OUTPUTS)
    import floatcol as fc
    opts = _options(args)                   # (fc.terrain's fly drops elev, azim, proj)
    size = opts.pop("size")
    anim = fc.fly_through(args.file, args.fly,
                          frames=60 if args.frames is None else args.frames,
                          heading=args.heading, pitch=args.pitch, fov=args.fov, size=size,
                          above=args.above, closed=args.closed, output=args.output,
                          look_ahead=args.look_ahead or 0.0,
                          fps=20.0 if args.fps is None else args.fps, progress=True,
                          vert_exag=args.vert_exag, extent=args.extent, nodata=args.nodata,
                          **opts)
    print(f"wrote {args.output} ({len(anim)} frames, {size[0]}x{size[1]}, heights "
          f"x{anim.stats['vert_exag']:g}, {anim.stats['seconds']:.1f} s)")
    return 0


def _client(address):
    """A dask.distributed Client of the scheduler at ``address``, or UsageError."""
    try:
        from distributed import Client
    except ImportError:
        raise UsageError("--scheduler needs dask.distributed: pip install "
                         "'floatcol[dask]'") from None
    try:
        return Client(address, timeout=10)
    except Exception as exc:
        # (any failure to connect: a wrong address, no answer, or something there that
        # is not a dask scheduler: a stranger's bytes read as a message length made
        # distributed ask for 3 EiB, a MemoryError and its traceback)
        reason = (str(exc).strip().splitlines() or [type(exc).__name__])[0]
        if not isinstance(exc, (OSError, TimeoutError, ValueError)):
            reason = f"it did not answer as a dask scheduler ({type(exc).__name__}: {reason})"
        _close_half_made(exc, Client)
        raise UsageError(f"cannot reach the scheduler {address!r}: {reason}") from None


def _close_half_made(exc, client_type):
    """Close the Client whose constructor raised ``exc`` (found in its traceback's
    frames) now: left to the garbage collector, its Client.__del__ stopped
    distributed's shared event loop whenever a collection happened, once while another
    Client was starting it, a deadlock (a LocalCluster made after it in the same
    process hung)."""
    tb = exc.__traceback__
    while tb is not None:
        half = tb.tb_frame.f_locals.get("self")
        if isinstance(half, client_type):
            with contextlib.suppress(Exception):
                half.close()
            break
        tb = tb.tb_next


def _gallery(args):
    from .gallery import build
    out = args.output
    parent = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(parent):
        raise UsageError(f"cannot write {out}: folder {parent} does not exist")
    client = None
    if args.scheduler is not None:
        client = _client(args.scheduler)
    try:
        result = build(out, source=args.source, only=args.only, client=client)
    finally:
        if client is not None:
            client.close()
    print(f"wrote {result.index} ({len(result.examples)} examples)")
    if result.failed:
        for name, err in result.failed.items():
            print(f"floatcol: error: example {name} failed: {err}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
