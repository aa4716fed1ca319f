"""The first pictures of a fresh install: drafts while the kernels compile.

Numba compiles the kernels once, into its disk cache, in about a minute on a 2-core
machine (most of it the column kernel; kernels/_jit.py says why it is one kernel).
Rather than wait, a process whose kernels are neither compiled nor cached

- starts one background process, ``python -m floatcol.warmup``, that compiles them
  into the cache (a lock file next to the cache keeps it to one, across processes;
  it outlives a short script such as the CLI's), then every other kernel at a lower
  priority (every option's: _the_rest), and
- draws its pictures meanwhile with the draft pass (passes/draft.py: numpy alone,
  no compile; about a second at 1920x1080), ``Render.stats["engine"] == "draft"``.

Once the cache holds the kernels, every render loads them (a second or two, once a
process) and draws full-quality pictures, ``stats["engine"] == "kernels"``. A
scene the draft does not draw (passes/draft.py's ``supports``) compiles in the
process as before. ``FLOATCOL_DRAFT=0`` in the environment turns drafts off: every
render waits for its kernels (the test suite does, for reproducible pictures).
"""
from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import threading
import time

#: The environment variable that turns drafts off ("0")
ENV = "FLOATCOL_DRAFT"
#: The lock file in Numba's cache folder of the kernels: the warm-up's process id
LOCK_NAME = "floatcol-warmup.pid"

_child = None       # the warm-up process this process started (subprocess.Popen)
_state = threading.local()      # .whole: inside full_quality() (this thread)


@contextlib.contextmanager
def full_quality():
    """Renders inside (in this thread) are never drafts: a clip's frames (fc.animate,
    fc.fly_through) are all drawn alike, the first waiting for its kernels, not drafts
    until the warm-up is done and then the kernels' pictures."""
    before = getattr(_state, "whole", False)
    _state.whole = True
    try:
        yield
    finally:
        _state.whole = before


#: the kinds of shadows whose kernels differ (shadow_kind's)
SHADOW_KINDS = ("texture", "soft", "on-the-fly")


def shadow_kind(light):
    """The kind of shadows a light (light.py Light) casts, a SHADOW_KINDS entry, or None
    where it casts none."""
    if not light.shadows:
        return None
    if light.shadow_method == "on-the-fly":
        return "on-the-fly"
    return "soft" if light.radius > 0.0 else "texture"


def _shadow_dispatchers(shadows):
    """The kernels of shadows of the kind ``shadows`` (shadow_kind's, or None)."""
    if shadows is None:
        return ()
    from .kernels import shadow as k
    if shadows == "on-the-fly":
        return (k.sweep_cells, k.sweep_order, k.shadow_sweep)
    own = (k.horizon_sweeps, k.shadow_lookup)
    return own + (k.horizon_slopes,) if shadows == "soft" else own


def _dispatchers(kind="column", smooth=False, shadows=None):
    """The kernels a picture runs (what must be compiled or cached) whose geometry
    pass is ``kind`` (renderer.geometry_kind: "column", a default picture's; "area",
    an area-sampled one's, fc.terrain's default; "lod" or "march", a fly camera's;
    "layers", a translucent one's), with ``smooth``, smooth shading's too, and those of
    its ``shadows`` (shadow_kind's, or None)."""
    from .kernels.shade import centre_kernel, finish_kernel
    extra = _shadow_dispatchers(shadows)
    if smooth:
        from .kernels.normals import smooth_normals_kernel
        extra += (smooth_normals_kernel,)
    # (with the functions they take as values: _jit.kernel_calling)
    if kind == "area":
        from .kernels.area import area_kernel
        return (area_kernel, *area_kernel.called, finish_kernel) + extra
    if kind == "layers":                # a translucent picture's (passes/translucency.py)
        from .kernels.layers import composite_kernel, layers_kernel, picture_kernel
        return (layers_kernel, *layers_kernel.called, composite_kernel, picture_kernel) + extra
    if kind in ("lod", "march"):
        from .kernels.lod import lod_kernel
        from .kernels.march import march_kernel
        own = (march_kernel,) if kind == "march" else (lod_kernel, *lod_kernel.called)
        return own + (finish_kernel,) + extra
    from .kernels.column import column_kernel
    from .kernels.silhouette import silhouette_kernel
    return (column_kernel, *column_kernel.called, finish_kernel, silhouette_kernel,
            *silhouette_kernel.called, centre_kernel) + extra


def every_kernel():
    """{name: dispatcher} of every CPU kernel in floatcol.kernels (a parallel kernel's
    own dispatcher, not its launcher) and of every jitted function a kernel calls as a
    value (_jit.kernel_calling: compiled on its own), each under the module that
    defines it: what warm_all compiles."""
    import importlib
    import pkgutil

    from . import kernels
    from .kernels._jit import _Exclusive
    found = {}
    for m in pkgutil.iter_modules(kernels.__path__):
        if m.name == "cuda" or m.name.startswith("_"):
            continue
        mod = importlib.import_module("floatcol.kernels." + m.name)
        for name, obj in vars(mod).items():
            if isinstance(obj, _Exclusive):
                for fn in obj.called:
                    found[fn.py_func.__module__ + "." + fn.__name__] = fn
                obj = obj._dispatcher
            elif not (name.endswith("_kernel") and hasattr(obj, "py_func")):
                continue
            # (a kernel imported from another module is that module's)
            if obj.py_func.__module__ == mod.__name__:
                found[mod.__name__ + "." + name] = obj
    return found


def kernels_ready(kind="column", smooth=False, shadows=None):
    """Whether every kernel of a picture (_dispatchers' of its geometry pass ``kind``,
    ``smooth``-shaded or not, with ``shadows`` of that kind or none) is compiled in
    this process or in Numba's disk cache (its index file is there)."""
    for d in _dispatchers(kind, smooth, shadows):
        if d.signatures:
            continue
        try:
            if not os.path.exists(d._cache._cache_file._index_path):
                return False
        except AttributeError:          # pragma: no cover - another Numba's layout
            return True
    return True


def _lock_path():
    from .kernels.column import column_kernel
    try:
        return os.path.join(column_kernel._cache._cache_path, LOCK_NAME)
    except AttributeError:              # pragma: no cover - another Numba's layout
        return None


def _alive(pid):
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True
    return True


def _running_elsewhere(lock):
    """Whether another process's warm-up (the lock's pid) is running; a stale lock
    (its process gone) is removed."""
    try:
        with open(lock) as fh:
            pid = int(fh.read().strip() or 0)
        age = time.time() - os.path.getmtime(lock)
    except (OSError, ValueError):
        return False
    if pid > 0 and _alive(pid) or pid == 0 and age < 30.0:   # (its pid not yet written)
        return True
    try:
        os.unlink(lock)
    except OSError:
        pass
    return False


def _spawn(lock, first="column", shadows=None):
    """Start the warm-up process (compiling the kernels of the picture that starts it,
    whose geometry pass is ``first``, with its ``shadows``' kind, first), or find
    another process's running; False where none can be started."""
    global _child
    for _ in range(2):                  # a stale lock (its process gone) is removed once
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
            break
        except FileExistsError:
            if _running_elsewhere(lock):
                return True
        except OSError:                 # a read-only cache folder
            return False
    else:
        return False
    try:
        env = dict(os.environ, **{ENV: "0"})
        order = [] if first == "column" else ["--first", first]
        if shadows is not None:
            order += ["--shadows", shadows]
        _child = subprocess.Popen([sys.executable, "-m", "floatcol.warmup", lock] + order,
                                  env=env,
                                  stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                  stderr=subprocess.DEVNULL, start_new_session=True,
                                  close_fds=True)
        os.write(fd, str(_child.pid).encode())
    except OSError:
        try:
            os.unlink(lock)
        except OSError:
            pass
        return False
    finally:
        os.close(fd)
    return True


def drafting(kind="column", smooth=False, shadows=None):
    """Whether this render (its geometry pass ``kind``, ``smooth``-shaded or not, with
    ``shadows`` of a shadow_kind or none) should be a draft: drafts are on, its kernels
    are not ready, and a warm-up process is compiling them (started here if none is;
    it compiles the kernels of a default picture, of an area-sampled smooth-shaded
    one, fc.terrain's, of a fly camera's, and of each kind of shadows, this render's
    first). Once this process's own warm-up has ended without leaving the kernels (it
    failed), renders compile in the process instead."""
    if os.environ.get(ENV, "1") == "0" or getattr(_state, "whole", False) \
            or kernels_ready(kind, smooth, shadows):
        return False
    if _child is not None:
        return _child.poll() is None
    lock = _lock_path()
    if lock is None:
        return False
    return _spawn(lock, "lod" if kind == "march" else kind, shadows)


#: What the warm-up renders: the kernels of the default pictures, in both
#: projections, with the batch evaluator (at least BATCH_MIN_SAMPLES samples) and
#: without, and the intensity and depth arrays.
WARM_RENDERS = (
    dict(size=(800, 600)),
    dict(size=(64, 48)),
    dict(size=(64, 48), projection="perspective"),
)


#: the warm-up's pictures by the geometry pass whose kernels they compile: the default
#: pictures (WARM_RENDERS), fc.terrain's default picture (about 20 s on 2 cores) and
#: a fly camera's views, antialiased and point sampled (about 20 s)
WARM_ORDER = ("column", "area", "lod")
#: what ``--first`` may name: a WARM_ORDER entry, or a translucent picture's kernels
FIRSTS = WARM_ORDER + ("layers",)


def warm(first="column", shadows=None):
    """Compile (or load) the kernels of WARM_RENDERS into Numba's cache, those of an
    area-sampled, smooth-shaded height field (fc.terrain's default picture), those
    of a fly camera's views and those of each kind of shadows (SHADOW_KINDS),
    ``first``'s (a WARM_ORDER entry, or "layers": a translucent picture's, which the
    others' leave to _the_rest) first (and after a terrain's, the other terrain's
    before the default picture's), with ``shadows``' kind right after it (drawn by
    the same pass: about 5 s more)."""
    import numpy as np

    import floatcol as fc
    z = np.sin(np.linspace(0, 6, 17))[:, None] * np.cos(np.linspace(0, 5, 17))[None, :]
    hf = fc.HeightField(z, u=(0, 16), v=(0, 16))

    def column():
        for kw in WARM_RENDERS:
            fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), **kw).intensity

    def area():
        fc.render(hf, size=(64, 48), antialias="area", smooth_shading=True).intensity

    def lod():
        cam = fc.fly(hf, (8, 1), heading=0, size=(64, 36), above=2)
        fc.render(hf, **cam, antialias="area", smooth_shading=True).intensity
        fc.render(hf, **cam, antialias=False, smooth_shading=True).intensity

    def layers(**opts):
        for proj in ("orthographic", "perspective"):
            fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(64, 48), opacity=0.5,
                      projection=proj, **opts).intensity

    def shadowed(kind, shadow):
        """A small picture of the geometry pass ``kind`` with shadows of that kind."""
        opts = dict(lightsource=(30, 40),
                    shadows="on-the-fly" if shadow == "on-the-fly" else True)
        if shadow == "soft":
            opts["light_radius"] = 1.0
        if kind == "layers":
            layers(**opts)
        elif kind == "column":
            fc.render("3*sin(u*cos(v))", u=(-5, 5), v=(-5, 5), size=(64, 48), **opts).intensity
        elif kind == "area":
            fc.render(hf, size=(64, 48), antialias="area", smooth_shading=True,
                      **opts).intensity
        else:
            cam = fc.fly(hf, (8, 1), heading=0, size=(64, 36), above=2)
            fc.render(hf, **cam, antialias="area", smooth_shading=True, **opts).intensity
    steps = dict(column=column, area=area, lod=lod, layers=layers)
    rest = [k for k in WARM_ORDER if k != first]
    if first not in ("column", "layers"):
        rest.sort(key=lambda k: k == "column")    # (a terrain's pictures before)
    steps[first]()
    if shadows is not None:
        shadowed(first, shadows)
    for name in rest:
        steps[name]()
    for shadow in SHADOW_KINDS:
        if shadow != shadows:
            shadowed("column", shadow)


def warm_all():
    """Compile (or load) every CPU kernel into Numba's cache, not only the default
    picture's: small pictures with each engine and pass (antialiasing by sub-columns
    and by area, translucency, shadows of each kind, textures, colour fields,
    contours and wireframes, floating horizons, adaptive planes, height fields with
    objects and their shadows, a fly-through's level-of-detail engine and ray march,
    Guedes's variants, composites),
    in both projections. ``python -m floatcol.warmup --all`` runs it: what a machine
    image or a CI job can do once, so that no later picture waits for a compile
    (about 140 s on 2 cores with an empty cache, a second or two with a full one)."""
    warm()
    for step in warm_all_steps():
        step()


def warm_all_steps():
    """warm_all's pictures after the default one, as a list of functions of no
    arguments, each drawing a few pictures (a test suite's job may take them in
    another order, tests/kernel_claims.py)."""
    import numpy as np

    import floatcol as fc
    from .terrain import GUEDES_VARIANTS, guedes
    expr = "3*sin(u*cos(v))"

    def both(**opts):
        def step():
            for proj in ("orthographic", "perspective"):
                fc.render(expr, u=(-5, 5), v=(-5, 5), size=(64, 48), projection=proj,
                          **opts).intensity
        return step

    z = np.sin(np.linspace(0, 6, 33))[:, None] * np.cos(np.linspace(0, 5, 33))[None, :]
    hf = fc.HeightField(3 * z, u=(0, 32), v=(0, 32))
    objects = [fc.tree(16, 16, 3), fc.box(8, 8, 2, 2, 2), fc.pole(20, 20, 4), fc.marker(24, 8, 1)]

    def terrain(**opts):
        return lambda: fc.render(hf, size=(64, 48), **opts).intensity

    def ring():
        # a box with poles on its four sides: one's shadow falls on it (the shadow's
        # edge on an object), whatever the light
        ring = [fc.box(16, 16, 6, 6, 3)] + [fc.pole(16 + du, 16 + dv, 10, radius=0.8)
                                            for du, dv in ((-5, 0), (5, 0), (0, -5), (0, 5))]
        fc.render(hf, size=(64, 48), objects=ring, shadows=True, lightsource=(0, 30)).intensity

    def fly():
        cam = fc.fly(hf, (16, 1), heading=0, size=(64, 36), above=4)
        for area in (False, True):
            fc.render(hf, **cam, antialias="area" if area else True).intensity
        fc.render(hf, **dict(cam, sampling="march"), antialias=False).intensity
        fc.render(hf, **cam, smooth_shading=True).intensity      # (passes/normals.py)

    def variants():
        for variant in GUEDES_VARIANTS:
            guedes(hf, (16, 1), size=(32, 18), variant=variant)

    def curvilinear_mesh():
        # matplotlib's plot_surface(X, Y, Z) of a polar grid (mesh.py's kernel)
        from .mesh import curvilinear
        r, p = np.meshgrid(np.linspace(0, 1, 5), np.linspace(0, 2 * np.pi, 9))
        curvilinear(r * np.cos(p), r * np.sin(p), r * r)

    # (in about the order in which the test suite first meets them, tests/conftest.py)
    steps = [both(antialias=3), both(antialias="area"),
             lambda: fc.render_many([fc.Layer(expr, ((-5, 5), (-5, 5))),
                                     fc.Layer("u*v/5", ((-5, 5), (-5, 5)))], size=(64, 48))]
    steps += [both(**opts) for opts in (
        dict(wireframe=(5, 5)), dict(opacity=0.5),
        dict(texture=np.linspace(0, 1, 48).reshape(4, 4, 3)), dict(contours=[0.0]),
        dict(color="u + v"), dict(color="u + v", contours=[0.0]), dict(method="horizon"),
        dict(shadows=True), dict(shadows="on-the-fly"), dict(shadows=True, light_radius=1.0),
        dict(opacity=0.5, shadows=True), dict(sampling="adaptive"))]
    steps += [terrain(**opts) for opts in (
        dict(), dict(antialias="area"), dict(shadows=True), dict(objects=objects),
        dict(objects=objects, shadows=True), dict(objects=objects, shadows=True, light_radius=1.0),
        dict(objects=objects, shadows=True, opacity=0.5))]
    return steps + [ring, fly, variants, curvilinear_mesh]


#: the warm-up's niceness once the first pictures' kernels are cached (_the_rest)
REST_NICENESS = 10


def _the_rest():
    """The warm-up process's second part, once warm()'s kernels are cached: every other
    kernel (warm_all_steps': translucency, sub-columns, textures, contours, ...) at a
    lower priority (REST_NICENESS), so that a later picture with any option loads its
    kernels instead of compiling them in its process (a translucent one's took 13.6 s
    after warm() at 800x600, a textured one's 3.9 s), while the user's own processes
    keep the cores. A step that fails is left to the picture that needs it."""
    try:
        os.nice(REST_NICENESS)
    except (AttributeError, OSError):       # pragma: no cover - no nice() here
        pass
    for step in warm_all_steps():
        try:
            step()
        except Exception:                   # noqa: BLE001 - compiled where needed instead
            pass


def main(argv=None):
    """``python -m floatcol.warmup [--all] [--first area|lod|layers] [--shadows KIND]``: warm()
    (warm_all() with --all; that picture's kernels first with --first, its shadows'
    right after with --shadows), and for the warm-up process that drafting() starts,
    then the rest at a lower priority (_the_rest). The warm-up process that
    drafting() starts passes its lock file's path, which it removes when done
    (nothing else is ever removed: a path that is not a lock file named LOCK_NAME is
    an error)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    everything = "--all" in argv
    rest = [a for a in argv if a != "--all"]
    first = "column"
    shadows = None
    if "--first" in rest:
        k = rest.index("--first")
        first = rest[k + 1] if k + 1 < len(rest) else ""
        del rest[k:k + 2]
    if "--shadows" in rest:
        k = rest.index("--shadows")
        shadows = rest[k + 1] if k + 1 < len(rest) else ""
        del rest[k:k + 2]
    if len(rest) > 1 or rest and os.path.basename(rest[0]) != LOCK_NAME \
            or first not in FIRSTS or shadows not in SHADOW_KINDS + (None,):
        print(f"usage: python -m floatcol.warmup [--all] [--first area|lod|layers] "
              f"[--shadows texture|soft|on-the-fly] (got {' '.join(argv)})", file=sys.stderr)
        return 2
    os.environ[ENV] = "0"
    try:
        if everything:
            warm_all()
        else:
            warm(first, shadows)
            if rest:
                _the_rest()
    finally:
        if rest:
            try:
                os.unlink(rest[0])
            except OSError:
                pass
    return 0


if __name__ == "__main__":
    sys.exit(main())
