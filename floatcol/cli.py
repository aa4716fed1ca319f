"""The ``floatcol`` command. It calls the public API only (never a kernel)."""
from __future__ import annotations

import argparse
import os
import sys

EXAMPLES = """examples:
  floatcol render "3*sin(u*cos(v))" -o surface.png
  floatcol render "u**2 - v**2" --u=-2:2 --v=-2:2 --proj perspective --elev 40 -o saddle.png
  floatcol render "sin(x*y)" --vars x,y --method horizon --size 800x600 -o lines.png
"""


class UsageError(Exception):
    pass


class _Parser(argparse.ArgumentParser):
    def error(self, message):          # one line, exit 2, no usage dump
        raise UsageError(message)


def _range(text):
    try:
        lo, hi = (float(x) for x in text.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"range {text!r} must be LOW:HIGH, e.g. -5:5") from None
    return lo, hi


def _size(text):
    try:
        w, h = (int(x) for x in text.lower().split("x"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"size {text!r} must be WIDTHxHEIGHT, e.g. 800x600") from None
    return w, h


def build_parser():
    from . import __version__
    p = _Parser(prog="floatcol", description="Shaded pictures of w = f(u, v) by the floating "
                "column algorithm (Gordon 2001).", epilog=EXAMPLES,
                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--version", action="version", version=f"floatcol {__version__}")
    sub = p.add_subparsers(dest="command", parser_class=_Parser)
    r = sub.add_parser("render", help="render an expression to a PNG", epilog=EXAMPLES,
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    r.add_argument("expr", help="the height w as a formula, e.g. '3*sin(u*cos(v))'")
    r.add_argument("-o", "--output", default="surface.png", help="PNG file to write (default surface.png)")
    r.add_argument("--u", type=_range, default=None, metavar="LOW:HIGH", help="u range (default -10:10)")
    r.add_argument("--v", type=_range, default=None, metavar="LOW:HIGH", help="v range (default -10:10)")
    r.add_argument("--vars", default=None, metavar="X,Y", help="names of the two variables (default u,v)")
    r.add_argument("--size", type=_size, default=(800, 600), metavar="WxH", help="pixels (default 800x600)")
    r.add_argument("--elev", type=float, default=30.0, help="degrees above the surface (default 30)")
    r.add_argument("--azim", type=float, default=30.0, help="turn about the vertical, degrees (default 30)")
    r.add_argument("--proj", default="orthographic", choices=["orthographic", "perspective", "ortho", "persp"])
    r.add_argument("--d1", type=float, default=None, help="perspective: viewpoint to screen")
    r.add_argument("--d2", type=float, default=None, help="perspective: screen to origin")
    r.add_argument("--scale", type=float, default=None, help="pixels per unit (default: fit)")
    r.add_argument("--method", default="column", choices=["column", "horizon"])
    r.add_argument("--shading", default="default", choices=["default", "lambert"])
    r.add_argument("--interpolation", default="normal", choices=["normal", "intensity"])
    r.add_argument("--cmap", default="viridis", help="matplotlib colormap for the upper side")
    r.add_argument("--center", default="auto", help="'auto' (middle of the picture), 'origin', or U,V,W")
    return p


def _fix_negative_ranges(argv):
    """Let '--u -5:5' work: argparse would take '-5:5' for an option."""
    out = []
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in ("--u", "--v") and i + 1 < len(argv) and argv[i + 1].startswith("-"):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


def main(argv=None):
    argv = sys.argv[1:] if argv is None else list(argv)
    try:
        args = build_parser().parse_args(_fix_negative_ranges(argv))
        if args.command is None:
            raise UsageError("say what to do, e.g. floatcol render \"3*sin(u*cos(v))\" -o surface.png")
        return _render(args)
    except UsageError as exc:
        print(f"floatcol: error: {exc}", file=sys.stderr)
        return 2
    except ValueError as exc:
        print(f"floatcol: error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:
        print(f"floatcol: error: cannot write {getattr(exc, 'filename', '') or 'output'}: "
              f"{exc.strerror or exc}", file=sys.stderr)
        return 2


def _render(args):
    out = args.output
    if not out.lower().endswith(".png"):
        raise UsageError(f"output {out!r} must end in .png")
    folder = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(folder):
        raise UsageError(f"cannot write {out}: folder {folder} does not exist")
    if not os.access(folder, os.W_OK):
        raise UsageError(f"cannot write {out}: folder {folder} is not writable")
    center = args.center
    if center == "origin":
        center = None
    elif center != "auto":
        try:
            center = tuple(float(x) for x in center.split(","))
        except ValueError:
            raise UsageError(f"--center {center!r} must be auto, origin or U,V,W") from None
    vars_ = tuple(args.vars.split(",")) if args.vars else None
    import floatcol as fc
    r = fc.render(args.expr, u=args.u, v=args.v, size=args.size, elev=args.elev, azim=args.azim,
                  projection=args.proj, d1=args.d1, d2=args.d2, scale=args.scale,
                  method=args.method, shading=args.shading, interpolation=args.interpolation,
                  vars=vars_, center=center, cmap=args.cmap)
    r.save(out)
    s = r.stats
    print(f"wrote {out} ({args.size[0]}x{args.size[1]}, {s['samples']} samples, "
          f"{s['seconds'] * 1e3:.0f} ms)")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
