"""Where a render's CPU time goes, by function, Numba's kernels included: a sampling
profile by Linux perf with the kernels' names.

perf sees Numba's compiled code as anonymous memory ("[JIT]" addresses). This script
keeps the object code of every kernel Numba loads from its cache or compiles (its
object-cache hook, patched before anything is compiled), reads their symbols
(readelf), looks each one's address up in Numba's engine and writes perf's map file
(/tmp/perf-PID.map), so that `perf report` names them. It warms up, then attaches
`perf record` to itself for the timed loop of renders only, and prints the top
symbols: a kernel's inlined helpers count as the kernel (the column pass's painting
is _column_pass's). ``--lines`` also counts the samples by source line, from the line
tables Numba compiles with NUMBA_DEBUGINFO=1 (addr2line on the kept object files; see
its help for what debug info changes).

    python benchmarks/profile_kernels.py                      # 1920x1080 perspective
    python benchmarks/profile_kernels.py --projection orthographic --seconds 5
    python benchmarks/profile_kernels.py --expr "u*v" --top 40
    python benchmarks/profile_kernels.py --fly            # bench_terrain.py's fly-through
    python benchmarks/profile_kernels.py --fly --march    # ... by the ray march
    python benchmarks/profile_kernels.py --opacity 0.5    # translucent (kernels/layers.py)

Needs perf (Debian's linux-perf) and readelf (binutils); on a machine whose perf
cannot count cycles it samples the cpu-clock. See docs/algorithm.md ("Where
1920x1080 perspective's time goes") for what it measured.
"""
import argparse
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

os.environ.setdefault("FLOATCOL_DRAFT", "0")  # time the kernels, never drafts

import numba.core.codegen as _codegen  # noqa: E402

_OBJECTS = []                   # every object file Numba's engine was given


def _keeping(hook):
    def keep(cls, ll_module, *args):
        out = hook.__func__(cls, ll_module, *args)
        buf = args[0] if args else out          # (compiled: the new buffer; loaded: the cached)
        if buf:
            _OBJECTS.append(bytes(buf))
        return out
    return classmethod(keep)


# (before any library is made: the engine takes the hooks when the codegen starts)
_codegen.JITCodeLibrary._object_compiled_hook = _keeping(
    _codegen.JITCodeLibrary._object_compiled_hook)
_codegen.JITCodeLibrary._object_getbuffer_hook = _keeping(
    _codegen.JITCodeLibrary._object_getbuffer_hook)

import floatcol as fc  # noqa: E402


def _engine():
    from numba.core.registry import cpu_target
    return cpu_target.target_context.codegen()._engine


def write_perf_map(path, folder):
    """perf's map file of every function symbol in the object files kept: 'START SIZE
    NAME' lines (hex). The object files go to ``folder``. Returns [(start, size,
    object file, the symbol's offset in it)]."""
    engine = _engine()
    lines = []
    funcs = []
    for k, buf in enumerate(_OBJECTS):
        obj = os.path.join(folder, f"k{k}.o")
        with open(obj, "wb") as fh:
            fh.write(buf)
        out = subprocess.run(["readelf", "-sW", obj], capture_output=True, text=True).stdout
        for ln in out.splitlines():
            p = ln.split()
            if len(p) < 8 or p[3] != "FUNC" or p[6] == "UND":
                continue
            try:
                addr = engine.get_function_address(p[7])
            except Exception:
                addr = 0
            if addr:
                lines.append(f"{addr:x} {int(p[2]):x} {p[7]}\n")
                funcs.append((addr, int(p[2]), obj, int(p[1], 16)))
    with open(path, "w") as fh:
        fh.writelines(lines)
    return funcs


def source_lines(data, funcs, top):
    """The kernels' samples by source line (NUMBA_DEBUGINFO=1 compiles the line
    tables in): perf's sample addresses inside the mapped functions, each object's
    offsets looked up by addr2line (-i: the innermost inlined line)."""
    import bisect
    from collections import Counter
    ips = subprocess.run(["perf", "script", "-i", data, "-F", "ip"], capture_output=True,
                         text=True).stdout.split()
    starts = sorted(funcs)
    keys = [f[0] for f in starts]
    by_obj = {}
    total = 0
    for x in ips:
        ip = int(x, 16)
        total += 1
        i = bisect.bisect_right(keys, ip) - 1
        if i >= 0 and ip < starts[i][0] + starts[i][1]:
            a, _, obj, off = starts[i]
            by_obj.setdefault(obj, []).append(ip - a + off)
    count = Counter()
    for obj, offs in by_obj.items():
        out = subprocess.run(["addr2line", "-e", obj] + [hex(o) for o in offs],
                             capture_output=True, text=True).stdout.split()
        for loc in out:
            count[loc.replace(os.path.dirname(os.path.dirname(fc.__file__)) + "/", "")] += 1
    print("\n| share of the samples | source line (innermost inlined) |\n|---|---|")
    for loc, n in count.most_common(top):
        print(f"| {100.0 * n / max(total, 1):.2f} % | {loc} |")


def short(name):
    """A Numba symbol's Python name: _ZN8floatcol7kernels6column12_column_passB3v41...
    -> column._column_pass (its length-prefixed parts); others as they are."""
    if not name.startswith("_ZN"):
        return name[:60]
    rest = name[3:]
    parts = []
    while rest[:1].isdigit():
        digits = re.match(r"\d+", rest).group()
        n = int(digits)
        parts.append(rest[len(digits):len(digits) + n])
        rest = rest[len(digits) + n:]
    if any("numba_parfor_gufunc" in p for p in parts):
        return "a prange loop's body (a parallel kernel: finishing, staircase, ...)"
    out = ".".join(parts).replace("_3c", "<").replace("_3e", ">")
    for prefix in ("floatcol.kernels.", "floatcol."):
        if out.startswith(prefix):
            return out[len(prefix):]
    return out or name[:60]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--expr", default="3*sin(u*cos(v))")
    ap.add_argument("--size", default="1920x1080")
    ap.add_argument("--projection", default="perspective")
    ap.add_argument("--seconds", type=float, default=10.0)
    ap.add_argument("--top", type=int, default=25)
    ap.add_argument("--fly", action="store_true",
                    help="bench_terrain.py's fly-through instead: a 4097^2 fractal DEM at "
                         "1280x720, fc.fly's level-of-detail engine, point sampled")
    ap.add_argument("--area", action="store_true", help="with --fly: antialias='area'")
    ap.add_argument("--march", action="store_true",
                    help="with --fly: sampling='march' (the ray march, point sampled)")
    ap.add_argument("--beta", type=float, default=2.4,
                    help="with --fly: the fractal DEM's spectral exponent (2.4 the benchmark's "
                         "needles; 3.4 a smoother, more landscape-like DEM)")
    ap.add_argument("--amp", type=float, default=40.0,
                    help="with --fly: the DEM's standard deviation (height units)")
    ap.add_argument("--mesh", type=int, default=0, metavar="N",
                    help="the expression on an N x N grid over [-5, 5]^2 instead, drawn as "
                         "a height field (matplotlib's call form, X, Y, Z)")
    ap.add_argument("--opacity", type=float, default=1.0,
                    help="the surface translucent (Gordon 6.5-6.6: kernels/layers.py)")
    ap.add_argument("--lines", action="store_true",
                    help="also by source line: set NUMBA_DEBUGINFO=1 and NUMBA_CACHE_DIR to "
                         "a folder of its own (the kernels compile again with line tables). "
                         "Debug info changes the code: the fly-through's kernel kept its "
                         "speed (145 against 140 ms), the column pass did not (its SIMD "
                         "batch evaluator calls vmath's functions instead of inlining them: "
                         "106 against 50 ms at 1080p)")
    args = ap.parse_args()
    for tool in ("perf", "readelf"):
        if shutil.which(tool) is None:
            sys.exit(f"profile_kernels needs {tool}")
    if args.fly:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        from bench_terrain import fractal
        n = 4097
        surface = fc.HeightField(fractal(n, args.beta, seed=3) * args.amp, u=(0, 4 * (n - 1)),
                                 v=(0, 4 * (n - 1)))
        kw = fc.fly(surface, (2000.0, 1000.0), heading=30, pitch=-10, fov=60,
                    size=(1280, 720), above=300)
        kw.update(antialias="area" if args.area else False)
        if args.march:
            kw["sampling"] = "march"
        w, h = kw["size"]
        args.projection = (f"beta {args.beta:g}, std {args.amp:g}, fly-through, "
                           + ("area" if args.area else "point") + " sampled"
                           + (", sampling='march'" if args.march else ""))
    else:
        surface = args.expr
        w, h = (int(x) for x in args.size.split("x"))
        kw = dict(size=(w, h), projection=args.projection, u=(-5, 5), v=(-5, 5))
        if args.mesh:
            import numpy as np
            g = np.linspace(-5, 5, args.mesh)
            surface = fc.HeightField(fc.as_surface(args.expr).evaluate(*np.meshgrid(g, g)),
                                     u=(-5, 5), v=(-5, 5))
            del kw["u"], kw["v"]
            args.expr = f"{args.expr} on a {args.mesh}^2 grid (a height field)"
        if args.opacity < 1.0:
            kw["opacity"] = args.opacity
            args.projection += f", opacity {args.opacity:g}"
    for _ in range(5):
        fc.render(surface, **kw)
    folder = tempfile.mkdtemp()
    funcs = write_perf_map(f"/tmp/perf-{os.getpid()}.map", folder)
    n_sym = len(funcs)
    data = os.path.join(folder, "perf.data")
    rec = subprocess.Popen(["perf", "record", "-F", "999", "-p", str(os.getpid()), "-o", data],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(1.0)                              # (perf attaches)
    t0 = time.perf_counter()
    n = 0
    while time.perf_counter() - t0 < args.seconds:
        fc.render(surface, **kw)
        n += 1
    ms = (time.perf_counter() - t0) / n * 1e3
    rec.send_signal(signal.SIGINT)
    rec.wait()
    rep = subprocess.run(["perf", "report", "-i", data, "--no-children", "--sort", "dso,sym",
                          "-g", "none", "--percent-limit", "0.3", "--stdio"],
                         capture_output=True, text=True).stdout
    print(f"{'DEM' if args.fly else args.expr}, {w}x{h} {args.projection}: {n} renders, "
          f"{ms:.1f} ms each while "
          f"profiled; {n_sym} kernel symbols mapped\n")
    if os.environ.get("PROFILE_RAW"):
        print(rep)
    print("| share of the CPU samples (both threads) | function |")
    print("|---|---|")
    shown = 0
    for ln in rep.splitlines():
        m = re.match(r"\s+([\d.]+)%\s+(.*?)\s+\[[.k]\]\s+(\S+)", ln)
        if m and shown < args.top:
            dso, sym = m.group(2), m.group(3)
            if "libgomp" in dso:
                what = "libgomp (OpenMP: a thread waiting for work)"
            elif "[JIT]" in dso:
                what = short(sym)
            else:
                what = f"{short(sym)} ({os.path.basename(dso)})"
            print(f"| {m.group(1)} % | {what} |")
            shown += 1
    if args.lines:
        source_lines(data, funcs, args.top)


if __name__ == "__main__":
    main()
