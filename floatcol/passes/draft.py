"""The draft pass: the floating column in numpy alone, for the first pictures of a
fresh install while the kernels compile in the background (floatcol/warmup.py).

The kernels take about a minute to compile on a 2-core machine; numpy needs none.
The draft draws the same column algorithm (App. A.2) over the same sampling planes,
vectorised over a block of columns at a time instead of one column after another:

- every sample of every plane at once: orthographic, the column line's point (eq. 3)
  with the planes clipped to the column's stretch of the domain, so its ends are the
  domain's edge; perspective, Newton's iteration on Pi (eq. 9, ERRATA 2) from s = 0,
  all samples together, and where it settles outside the domain or not at all, the
  root on the part of the line inside the domain (the kernels' _root_inside);
- two successive valid samples of a column span the pixel centres between their
  screen rows; front to back, the first span over a pixel paints it (what the
  floating interval [ymin, ymax] decides, holes and several runs included);
- the painted point interpolates its two samples linearly in screen row (depth, u,
  v, w, normal, intensity) and is lit and coloured as finish_kernel does (shade.py's
  _light and _side_rgb, written here in numpy).

A perspective column whose curve folds back in t (kernels/fold.py's test), which one
point a plane cannot follow, is drawn ray by ray instead (_ray_columns).

What it leaves out, until the kernels are there: the corrections of section 5, the
antialiasing (an area-sampled picture is drawn at the pixel centres), smooth
shading (a height field's cells lit by their own partials), adaptive sampling. Against
the ray caster it scores about 40 dB where the kernels score 63 (tests/test_draft.py
measures it). A fly camera's view inside the scene is drawn on the level-of-detail
engine's planes (_planes). A texture or colour field colours it (draft_base), a
light casts its shadows (passes/draft_shadow.py), a translucent surface shows every
layer (passes/draft_layers.py), contours and wireframes are drawn on it in numpy
(passes/overlays.py draw_lines, from planes(); the lines alone with fill=False); a
line drawing's horizon lines are marked from its samples (passes/draft_horizon.py);
several opaque surfaces are drafted one by one and merged by depth (renderer.py).
A perspective eye over the domain looking down past the nadir is drawn by the column
pass's two passes from the eye's t, forward and back (split, halves); any other eye
over the domain (above the surface or under it) by one pass from the eye.
"""
from __future__ import annotations

import math

import numpy as np

from ..color import lower_or_upper
from ..kernels import layout as L
from ..kernels.sample import DOMAIN_EPS, NEWTON_ITERS, NEWTON_TOL_PX
from ..kernels.fold import FOLD_NEAR
from ..kernels.shade import INTERP_INTENSITY
from .colour import colour_table_rgb
from .geometry import check_bytes, too_large

#: Bytes a pixel of a draft holds at most at once: its G-buffer (9 float32) twice
#: (the tiled copy), the finishing pass's float64 planes, the picture
DRAFT_BYTES = 160
#: Samples (planes x columns) evaluated at once: the columns go in blocks of this size
BLOCK_SAMPLES = 1 << 20
#: A fly camera's planes at most (a pixel's footprint apart from the eye: a few thousand)
MAX_DRAFT_PLANES = 20_000


def supports(quality, view, surface):
    """Whether the draft can draw this layer's picture: a shaded picture or a line
    drawing (renderer.py checks the rest), and in perspective a viewpoint in front of
    the whole domain (one ascending pass per column), an eye over it looking down past
    the nadir (split: two passes from the eye's t), or for a shaded picture any other
    eye over it (a fly camera's inside the scene, above the surface or under it: every
    ray goes farther in t) on planes a pixel's footprint apart from the eye (_planes).
    An area-sampled one is drawn at the pixel centres, as every draft is (no
    antialiasing)."""
    if quality.method not in ("column", "horizon"):
        return False
    if view.orthographic:
        return True
    t_eye = -view.d3 * math.cos(view.alpha)       # the viewpoint's t (eqs. 4, 10)
    if view.t_range[0] > t_eye:
        return True
    if split(view):         # (looking down past the nadir: two passes from the eye's t)
        return True
    # the eye over the domain, every ray going farther in t: one pass from the eye on
    # planes a footprint apart (_planes), the eye above the surface or under it (the
    # lod engine's pyramid asks it above); a line drawing's lines are the column pass's
    # planes
    return quality.method != "horizon"


def _params(view):
    a, b = view.alpha, view.beta
    return math.cos(a), math.sin(a), math.cos(b), math.sin(b)


def _normal(view, wu, wv):
    """Eq. (11): the unit upper-side normal in screen coordinates."""
    ca, sa, cb, sb = _params(view)
    nx = -wu * cb + wv * sb
    ny = wu * sa * sb + ca + wv * sa * cb
    nz = -wu * ca * sb + sa - wv * ca * cb
    q = 1.0 / np.sqrt(nx * nx + ny * ny + nz * nz)
    return nx * q, ny * q, nz * q


def _in_domain(view, lines):
    """(lo, hi): the stretch of x where each line (u, v) = (u0 + du x, v0 + dv x) lies
    inside the domain (lo > hi where it misses it); ``lines`` (u0, du, v0, dv), numbers
    or arrays of one shape."""
    (ua, ub), (va, vb) = view.domain
    u0, du, v0, dv = lines
    lo, hi = -np.inf, np.inf
    for base, slope, a, b in ((u0, du, ua, ub), (v0, dv, va, vb)):
        flat = np.abs(slope) < 1e-15
        with np.errstate(divide="ignore", invalid="ignore"):
            l1, l2 = (a - base) / slope, (b - base) / slope
        lo = np.where(flat, np.where((base < a) | (base > b), np.inf, lo),
                      np.maximum(lo, np.minimum(l1, l2)))
        hi = np.where(flat, hi, np.minimum(hi, np.maximum(l1, l2)))
    return lo, hi


def _s_range(view):
    """(s_lo, s_hi): the heights on Π (from the view's centre) where the surface may
    be: f's range with a quarter of it to spare (the kernels' scan_range)."""
    flo, fhi = view.f_range
    spare = 0.25 * (fhi - flo) + 1e-9
    return flo - spare - view.center[2], fhi + spare - view.center[2]


def _column_t(view, x0):
    """(ta, tb) of each orthographic column: its line's stretch inside the domain
    (ta > tb where it misses)."""
    ca, sa, cb, sb = _params(view)
    cu, cv, _ = view.center
    # u = cu + x0 cb + t sb, v = cv - x0 sb + t cb (eq. 3)
    return _in_domain(view, (cu + x0 * cb, sb, cv - x0 * sb, cb))


def _inside(view, u, v):
    (ua, ub), (va, vb) = view.domain
    eu, ev = DOMAIN_EPS * (ub - ua), DOMAIN_EPS * (vb - va)
    ok = (u >= ua - eu) & (u <= ub + eu) & (v >= va - ev) & (v <= vb + ev)
    return ok, np.clip(u, ua + eu, ub - eu), np.clip(v, va + ev, vb - ev)


FIELDS = ("y", "z", "u", "v", "w", "nx", "ny", "nz", "lam", "t")
#: Bisections of a run's end (a hole, the domain's edge) between two planes
EDGE_BISECTIONS = 12


def _points(surface, view, x0, t):
    """Samples on column planes x = x0 and sampling planes t (arrays of one shape): a
    dict of FIELDS (y the screen row from the bottom, NaN where invalid) and ``ok``
    (a valid sample), and the evaluations of f."""
    ca, sa, cb, sb = _params(view)
    cu, cv, cw = view.center
    H = view.height
    if view.orthographic:
        u = cu + x0 * cb + t * sb                    # eq. (3)
        v = cv - x0 * sb + t * cb
        ok, u, v = _inside(view, u, v)
        w, wu, wv = _evaluate(surface, u, v, ok)
        evals = int(ok.sum())
        s = w - cw
        y1 = s * ca - t * sa                         # eq. (4)
        z = s * sa + t * ca
        ypix = y1 * view.scale + (H - 1) * 0.5
        vx, vy, vz = 0.0, 0.0, -1.0
    else:
        d1, d3 = view.d1, view.d3
        r0 = x0 * (t * ca + d3) / d1                 # eq. (9)
        k = x0 * sa / d1 + 0.0 * r0                  # dr/ds inside Pi
        s = np.zeros(r0.shape)
        done = np.zeros(r0.shape, dtype=bool)
        w = np.full(r0.shape, np.nan)
        wu = np.zeros(r0.shape)
        wv = np.zeros(r0.shape)
        evals = 0
        idx = np.arange(r0.size)
        for _ in range(NEWTON_ITERS):               # ERRATA 2: the exact point on Pi
            if idx.size == 0:
                break
            si = s.flat[idx]
            ri = r0.flat[idx] + k.flat[idx] * si
            ti = t.flat[idx]
            wi, wui, wvi = surface.evaluate(cu + ri * cb + ti * sb,    # eq. (2)
                                            cv - ri * sb + ti * cb, derivatives=True)
            evals += idx.size
            w.flat[idx], wu.flat[idx], wv.flat[idx] = wi, wui, wvi
            g = (wi - cw) - si
            ki = k.flat[idx]
            conv = (np.abs(ki * g) * view.scale <= NEWTON_TOL_PX) | (ki == 0.0)
            dg = ki * (wui * cb - wvi * sb) - 1.0
            bad = ~np.isfinite(g) | (dg == 0.0) | ~np.isfinite(dg)
            done.flat[idx[conv & ~bad]] = True
            step = ~conv & ~bad
            s.flat[idx[step]] = si[step] - g[step] / dg[step]
            idx = idx[step]
        # where Newton settled outside the domain or not at all, the root on the part
        # of the plane's line inside the domain (the kernels' _root_inside): near the
        # domain's edge, where the line leans far from the vertical, Newton from s = 0
        # finds the surface continued beyond the edge
        ok = done & np.isfinite(w)
        r = r0 + k * np.where(ok, w - cw, 0.0)
        inside, _, _ = _inside(view, cu + r * cb + t * sb, cv - r * sb + t * cb)
        again = ~(ok & inside) & (k != 0.0) & np.isfinite(r0)
        if again.any():
            evals += _root_inside(surface, view, r0, k, t, np.flatnonzero(again), w, wu, wv,
                                  done)
        ok = done & np.isfinite(w)
        s = np.where(ok, w - cw, 0.0)
        r = r0 + k * s
        u = cu + r * cb + t * sb
        v = cv - r * sb + t * cb
        inside, _, _ = _inside(view, u, v)
        ok &= inside
        y1 = s * ca - t * sa                         # eqs. (4), (10)
        z = s * sa + t * ca
        ok &= z + d3 > d1                            # in front of the screen plane: none
        depth = np.where(ok, z + d3, 1.0)
        ypix = y1 * d1 / depth * view.scale + (H - 1) * 0.5
        vx, vy, vz = -r, -y1, -depth                 # toward the viewpoint
    ok &= np.isfinite(w) & np.isfinite(wu) & np.isfinite(wv) & np.isfinite(ypix)
    wu = np.where(ok, wu, 0.0)
    wv = np.where(ok, wv, 0.0)
    nx, ny, nz = _normal(view, wu, wv)
    lx, ly, lz = view.light
    if lx == 0.0 and ly == 0.0 and lz == 0.0:      # eq. (12): the headlight
        lam = np.abs(vx * nx + vy * ny + vz * nz) / np.sqrt(vx * vx + vy * vy + vz * vz)
    else:
        lam = np.abs(lx * nx + ly * ny + lz * nz)
    return dict(y=np.where(ok, ypix, np.nan), z=z, u=u, v=v, w=w, nx=nx, ny=ny, nz=nz,
                lam=np.minimum(lam, 1.0), t=t + 0.0 * z, ok=ok), evals


def _root_inside(surface, view, r0, k, t, idx, w, wu, wv, done):
    """The kernels' _root_inside (kernels/sample.py) for the samples at flat indices
    ``idx`` of arrays of one shape: on the part of each one's line (r = r0 + k s on
    plane t) inside the domain and the scan range, where g = f - cw - s changes sign
    between the part's ends (an end at the scan range's bottom, top has g > 0, < 0),
    the root by Newton's iteration kept inside the bracket (bisecting where it would
    leave it). Writes w, wu, wv and done where one is found. Returns the evaluations."""
    ca, sa, cb, sb = _params(view)
    cu, cv, cw = view.center
    r0, k, t = r0.flat[idx], k.flat[idx], t.flat[idx]
    # the plane's line inside the domain: r in [ra, rb] (eq. 2)
    ra, rb = _in_domain(view, (cu + t * sb, cb, cv + t * cb, -sb))
    s_lo, s_hi = _s_range(view)
    with np.errstate(invalid="ignore"):
        s1, s2 = (ra - r0) / k, (rb - r0) / k
        a = np.maximum(np.minimum(s1, s2), s_lo)
        b = np.minimum(np.maximum(s1, s2), s_hi)
    keep = np.flatnonzero(a < b)
    idx, r0, k, t, a, b = idx[keep], r0[keep], k[keep], t[keep], a[keep], b[keep]
    evals = 0

    def g_at(s, sel):
        nonlocal evals
        r = r0[sel] + k[sel] * s
        wi, wui, wvi = surface.evaluate(cu + r * cb + t[sel] * sb, cv - r * sb + t[sel] * cb,
                                        derivatives=True)
        evals += sel.size
        return (wi - cw) - s, wi, wui, wvi

    ga = np.ones(a.shape)
    gb = -np.ones(b.shape)
    for end, g_end, beyond in ((a, ga, a > s_lo), (b, gb, b < s_hi)):
        sel = np.flatnonzero(beyond)
        g_end[sel] = g_at(end[sel], sel)[0]
    go = np.flatnonzero(np.isfinite(ga) & np.isfinite(gb) & ((ga >= 0.0) != (gb >= 0.0)))
    inner = (a > s_lo) & (b < s_hi)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = np.where(inner, a - ga * (b - a) / (gb - ga), 0.5 * (a + b))
    for _ in range(NEWTON_ITERS):
        if go.size == 0:
            break
        g, wi, wui, wvi = g_at(s[go], go)
        fin = np.isfinite(wi) & np.isfinite(g)
        conv = fin & (np.abs(k[go] * g) * view.scale <= NEWTON_TOL_PX)
        hit = go[conv]
        w.flat[idx[hit]], wu.flat[idx[hit]], wv.flat[idx[hit]] = wi[conv], wui[conv], wvi[conv]
        done.flat[idx[hit]] = True
        more = fin & ~conv
        go, g, wui, wvi = go[more], g[more], wui[more], wvi[more]
        same = (g >= 0.0) == (ga[go] >= 0.0)
        a[go] = np.where(same, s[go], a[go])
        ga[go] = np.where(same, g, ga[go])
        b[go] = np.where(same, b[go], s[go])
        dg = k[go] * (wui * cb - wvi * sb) - 1.0
        with np.errstate(divide="ignore", invalid="ignore"):
            s_n = s[go] - g / dg
        s[go] = np.where((s_n > a[go]) & (s_n < b[go]), s_n, 0.5 * (a[go] + b[go]))
    return evals


def _samples(surface, view, cols, t):
    """The samples of columns ``cols`` (m,) on planes ``t`` (n,): _points' dict of
    (n, m) arrays and ``pair`` (n - 1, m), whether the span from each sample to the
    next is surface; the evaluations of f. Orthographic planes are clipped to the
    column's stretch of the domain (its ends are the domain's edge); a run's end at
    a hole (or in perspective the domain's edge) is found by bisection between the
    planes (the kernels' EDGE_BISECTIONS), its sample put in the invalid one's place."""
    x0 = (cols - (view.width - 1) * 0.5) / view.scale
    tt = np.broadcast_to(t[:, None], (t.size, x0.size))
    if view.orthographic:
        ta, tb = _column_t(view, x0)
        tt = np.clip(tt, ta[None, :], tb[None, :])
        tt = np.where((ta <= tb)[None, :], tt, np.nan)
    xx = np.broadcast_to(x0[None, :], tt.shape)
    smp, evals = _points(surface, view, xx, tt)
    ok = smp["ok"]
    pair = ok[1:] & ok[:-1]
    # run ends: (ok, bad) ends a run at the bad sample's place, (bad, ok) starts one
    # at the bad sample's place, unless that sample also ends the run before it
    ends = ok[:-1] & ~ok[1:] & np.isfinite(tt[1:])
    starts = ~ok[:-1] & ok[1:] & np.isfinite(tt[:-1])
    starts[1:] &= ~ends[:-1]
    edge = np.zeros(ok.shape, dtype=bool)        # the samples of the run ends
    for mask, good, bad in ((ends, 0, 1), (starts, 1, 0)):
        k, c = np.nonzero(mask)
        if k.size == 0:
            continue
        t_ok, t_bad = tt[k + good, c].copy(), tt[k + bad, c].copy()
        for _ in range(EDGE_BISECTIONS):
            tm = 0.5 * (t_ok + t_bad)
            m, ev = _points(surface, view, x0[c], tm)
            evals += ev
            t_ok = np.where(m["ok"], tm, t_ok)
            t_bad = np.where(m["ok"], t_bad, tm)
        m, ev = _points(surface, view, x0[c], t_ok)
        evals += ev
        kb = k + bad
        for name in FIELDS:
            smp[name][kb, c] = m[name]
        ok[kb, c] = m["ok"]
        pair[k, c] = m["ok"]
        edge[kb, c] = m["ok"]
    smp["edge"] = edge
    return smp, pair, evals


def _fold_columns(view, smp, x0):
    """The columns (of x0 (m,)) that fold, the most folding samples first, by
    kernels/fold.py's test: a valid sample where 1 - k f_r < 0 (dG/ds > 0: its plane's
    line meets the surface more than once there), or a run's end between two planes
    (at a hole or the domain's edge) where 1 - k f_r < FOLD_NEAR (nearly a fold: a
    rim's last samples). With N the unit upper normal in screen coordinates (eq. 11),
    1 - k f_r = 1 + k N_x / (cos(a) N_y + sin(a) N_z)."""
    ca, sa, _, _ = _params(view)
    k = x0 * sa / view.d1
    with np.errstate(divide="ignore", invalid="ignore"):
        q = 1.0 + k[None, :] * smp["nx"] / (ca * smp["ny"] + sa * smp["nz"])
        fold = smp["ok"] & ((q < 0.0) | (smp["edge"] & (q < FOLD_NEAR)))
    count = fold.sum(axis=0)
    cols = np.flatnonzero(count)
    return cols[np.argsort(-count[cols], kind="stable")]


#: Bisections of a fold column's ray between the two planes where it meets the surface
RAY_BISECTIONS = 16
#: A draft's fold columns' rays evaluate f at most about this many times in all (about
#: 2 s on one core; beyond it a fold column keeps its point a plane, so that a fresh
#: install's first picture stays a few seconds). 3 sin(u cos v) from elevation 50 at
#: 1920x1080 takes 9.4 million for its 135 fold columns (the draft 2.1 -> 3.1 s)
RAY_EVALS = 16_000_000


def _rays(view, t):
    """The planes a fold column's rays test, the same for every column (_ray_columns):
    (rows (H,) bool: the rows whose rays go farther with t; i0, i1 (H,): each ray's
    first and last plane (of ``t``), from one before its heights enter the surface's
    range to one after they leave it; A, B: each row's ray s = A t + B on its column's
    plane Π, eqs. 4, 10 inverted)."""
    ca, sa, _, _ = _params(view)
    d1, d3, H = view.d1, view.d3, view.height
    y0 = (np.arange(H) - (H - 1) * 0.5) / view.scale
    den = d1 * ca - y0 * sa
    rows = den > 1e-12 * d1
    den = np.where(rows, den, 1.0)
    A = (d1 * sa + y0 * ca) / den
    B = y0 * d3 / den
    s_lo, s_hi = _s_range(view)
    with np.errstate(divide="ignore", invalid="ignore"):
        ta, tb = (s_lo - B) / A, (s_hi - B) / A
    t_first = np.where(A != 0.0, np.minimum(ta, tb), -np.inf)
    t_last = np.where(A != 0.0, np.maximum(ta, tb), np.inf)
    i0 = np.maximum(np.searchsorted(t, t_first) - 1, 0)
    i1 = np.minimum(np.searchsorted(t, t_last, side="right"), t.size - 1)
    return rows & (i1 > i0), i0, i1, A, B


#: A fold column's rays go over their planes this many at a time at first (doubling
#: each round up to BLOCK_SAMPLES samples in all), and those that have met the
#: surface stop
RAY_CHUNK = 16
#: Fold columns drawn together (their rays in one set of arrays)
RAY_COLUMNS = 64


def _ray_columns(surface, view, x0, t, rays):
    """Folding columns (x0 (m,)) drawn ray by ray: for each pixel row, the first of its
    planes (_rays, those over the domain) where its ray crosses the surface (g = f - cw
    - s changes sign between two planes), bisected; both sides; holes let the ray
    pass. Returns (hit (H, m) bool, FIELDS of the hits (H, m), evals). Where the
    column pass's one point a plane cannot follow the curve back (a fold; the kernels
    trace it, kernels/fold.py), each ray still finds its own point."""
    ca, sa, cb, sb = _params(view)
    cu, cv, cw = view.center
    d1, d3, H = view.d1, view.d3, view.height
    m = x0.size
    rows, i0, i1, A, B = (np.repeat(a, m) for a in rays)     # ray j * m + c
    xr = np.tile(x0, H)
    A, B = A[:, None].ravel(), B[:, None].ravel()

    def point(tt, jj):
        s = A[jj] * tt + B[jj]
        z = s * sa + tt * ca
        r = xr[jj] * (z + d3) / d1                # eq. (9)
        return s, z, r, cu + r * cb + tt * sb, cv - r * sb + tt * cb   # eq. (2)

    def g_at(tt, jj, derivatives=False):
        s, z, r, u, v = point(tt, jj)
        ok, _, _ = _inside(view, u, v)
        ok &= z + d3 > d1                         # beyond the screen plane
        w, wu, wv = _evaluate(surface, u, v, ok)
        g = np.where(ok, w - cw - s, np.nan)
        return (g, s, z, r, u, v, w, wu, wv) if derivatives else g

    # each ray's planes over the domain: its ground point (u, v) is linear in t
    rr = xr * (A * sa + ca) / d1                  # r = rr t + r0 (eq. 9)
    r0 = xr * (B * sa + d3) / d1
    lo, hi = _in_domain(view, (cu + r0 * cb, rr * cb + sb, cv - r0 * sb, cb - rr * sb))
    i0 = np.maximum(i0, np.searchsorted(t, lo) - 1)
    i1 = np.minimum(i1, np.searchsorted(t, hi, side="right"))
    evals = 0
    found = []                                    # (rays, ta, tb, g at ta) of the hits
    active = np.flatnonzero(rows & (i1 > i0) & (lo <= hi))
    start = i0[active]
    chunk = RAY_CHUNK
    while active.size:
        end = np.minimum(start + chunk, i1[active])
        cnt = end - start + 1
        first = np.cumsum(cnt) - cnt
        which = np.repeat(np.arange(active.size), cnt)
        ray = active[which]
        ti = t[start[which] + np.arange(which.size) - first[which]]
        g = g_at(ti, ray)
        evals += which.size
        going = end < i1[active]
        hit = _first_crossings(g_at, ray, which, ti, g)
        if hit is not None:
            k, ta, tb, ga, ev = hit
            evals += ev
            found.append((active[k], ta, tb, ga))
            going[k] = False
        active, start = active[going], end[going]
        chunk = max(min(2 * chunk, BLOCK_SAMPLES // max(active.size, 1)), RAY_CHUNK)
    hit = np.zeros(H * m, dtype=bool)
    fields = {name: np.zeros(H * m) for name in FIELDS}
    if found:
        jj, ta, tb, ga = (np.concatenate(x) for x in zip(*found))
        for _ in range(RAY_BISECTIONS):
            tm = 0.5 * (ta + tb)
            gm = g_at(tm, jj)
            same = np.isfinite(gm) & ((gm >= 0.0) == (ga >= 0.0))
            ta, ga = np.where(same, tm, ta), np.where(same, gm, ga)
            tb = np.where(same, tb, tm)
        evals += (RAY_BISECTIONS + 1) * jj.size
        tm = 0.5 * (ta + tb)
        _, s, z, r, u, v, w, wu, wv = g_at(tm, jj, derivatives=True)
        fin = np.isfinite(w) & np.isfinite(wu) & np.isfinite(wv)
        jj, tm, s, z, r, u, v, w, wu, wv = (a[fin] for a in (jj, tm, s, z, r, u, v, w, wu, wv))
        nx, ny, nz = _normal(view, wu, wv)
        y1 = s * ca - tm * sa
        lx, ly, lz = view.light
        if lx == 0.0 and ly == 0.0 and lz == 0.0:    # eq. (12): the headlight
            vx, vy, vz = -r, -y1, -(z + d3)
            lam = np.abs(vx * nx + vy * ny + vz * nz) / np.sqrt(vx * vx + vy * vy + vz * vz)
        else:
            lam = np.abs(lx * nx + ly * ny + lz * nz)
        hit[jj] = True
        for name, a in zip(FIELDS, (jj // m + 0.0, z, u, v, w, nx, ny, nz,
                                    np.minimum(lam, 1.0), tm)):
            fields[name][jj] = a
    return (hit.reshape(H, m), {name: a.reshape(H, m) for name, a in fields.items()},
            evals)


def _first_crossings(g_at, row, which, ti, g):
    """Each ray's first crossing of the surface among its planes ``ti`` (rays
    ``which``, ``row`` their indices for g_at, one after another, g at each): (the
    rays that cross, the crossing's bracket ta, tb, g at ta, evaluations), or None.
    Between a plane where the ray is over a hole or beyond the domain and one where it
    is not, the edge is bisected (EDGE_BISECTIONS, as a run's end), and the ray
    crosses between the edge and that plane where the sign there differs (it meets a
    steep rim)."""
    fin = np.isfinite(g)
    same = which[1:] == which[:-1]
    with np.errstate(invalid="ignore"):
        cross = same & fin[1:] & fin[:-1] & ((g[1:] >= 0.0) != (g[:-1] >= 0.0))
    at = np.flatnonzero(cross)
    ta, tb, ga = ti[at], ti[at + 1], g[at]
    edge = np.flatnonzero(same & (fin[1:] != fin[:-1]))
    if edge.size:
        good = np.where(fin[edge], edge, edge + 1)
        t_ok, t_bad, g_ok = ti[good], ti[np.where(fin[edge], edge + 1, edge)], g[good]
        jr = row[edge]
        for _ in range(EDGE_BISECTIONS):
            tm = 0.5 * (t_ok + t_bad)
            ok = np.isfinite(g_at(tm, jr))
            t_ok, t_bad = np.where(ok, tm, t_ok), np.where(ok, t_bad, tm)
        g_e = g_at(t_ok, jr)
        ok = np.isfinite(g_e) & ((g_e >= 0.0) != (g_ok >= 0.0))
        after = fin[edge]                         # (the edge after the finite plane)
        at = np.concatenate([at, edge[ok]])
        ta = np.concatenate([ta, np.where(after, ti[good], t_ok)[ok]])
        tb = np.concatenate([tb, np.where(after, t_ok, ti[good])[ok]])
        ga = np.concatenate([ga, np.where(after, g_ok, g_e)[ok]])
    if at.size == 0:
        return None
    order = np.argsort(at, kind="stable")
    at, ta, tb, ga = at[order], ta[order], tb[order], ga[order]
    k, first = np.unique(which[at], return_index=True)   # each ray's first
    return k, ta[first], tb[first], ga[first], (EDGE_BISECTIONS + 1) * edge.size


def _evaluate(surface, u, v, ok):
    """(w, f_u, f_v) where ``ok``; NaN, 0, 0 elsewhere."""
    w = np.full(u.shape, np.nan)
    wu = np.zeros(u.shape)
    wv = np.zeros(u.shape)
    if ok.any():
        w[ok], wu[ok], wv[ok] = surface.evaluate(u[ok], v[ok], derivatives=True)
    return w, wu, wv


def _column_planes(view):
    """Whether the draft samples the column pass's planes, view.step apart (_planes):
    orthographic, the eye in front of the domain, or looking down past the nadir
    (split); else a fly camera's."""
    ca = math.cos(view.alpha)
    return view.orthographic or view.t_range[0] > -view.d3 * ca or not ca > 1e-9 \
        or split(view)


def split(view):
    """Whether a perspective picture's eye is not in front of the domain and some of its
    rays go nearer in t with their distance (looking down past the nadir: the rays of
    the top or the bottom row, d1 cos(a) - y0 sin(a) <= 0, eqs. 4 and 10 inverted, as
    passes/lod.py supports): the column pass's two passes from the eye's t, forward
    and back (kernels/column.py render_column_into), which the lod engine cannot
    draw."""
    if view.orthographic:
        return False
    ca, sa = math.cos(view.alpha), math.sin(view.alpha)
    if view.t_range[0] > -view.d3 * ca:
        return False
    half = (view.height + 1.0) * 0.5 / view.scale
    return min(view.d1 * ca - y0 * sa for y0 in (-half, half)) <= 0.0


def halves(view, t, index=False):
    """The planes ``t`` (_planes') in the passes that sample them, each front to back:
    the one pass, or for a split view (split) the column pass's two from the eye's t,
    forward and back, each starting at the eye's t (or the domain's end nearer it).
    With ``index``, (planes, each one's number k on the grid t0 + k step, -1 at a
    pass's ends, as kernels/column.py _pass_plane numbers them) pairs."""
    k = np.arange(t.size)
    k[0] = k[-1] = -1                    # (a pass's ends)
    if not split(view):
        return [(t, k)] if index else [t]
    t_eye = -view.d3 * math.cos(view.alpha)
    t_lo, t_hi = view.t_range
    out = []
    if t_hi > t_eye:
        start = max(t_lo, t_eye)
        on = t > start
        out.append((np.concatenate([[start], t[on]]), np.concatenate([[-1], k[on]])))
    if t_lo < t_eye:
        start = min(t_hi, t_eye)
        on = t < start
        out.append((np.concatenate([[start], t[on][::-1]]),
                    np.concatenate([[-1], k[on][::-1]])))
    return out if index else [h for h, _ in out]


def _split_block(surface, view, cols, t, hrec=None, hstride=0):
    """A split view's (split) block of columns ``cols``: each pass's first span over
    each pixel centre (_paint), a pixel taking the pass that reaches it first (each ray
    goes one way from the eye: the passes' pixels meet at the nadir's row alone); a
    line drawing's records of each pass into hrec (the block's). Returns (hit (H, m),
    the G-buffer entries of the hit pixels in row order, the evaluations of f)."""
    H = view.height
    hit = np.zeros((H, cols.size), dtype=bool)
    vals = np.zeros((H, cols.size, L.G_SIZE))
    evals = 0
    for th, kh in halves(view, t, index=True):
        smp, pair, ev = _samples(surface, view, cols, th)
        evals += ev
        if hstride > 0:
            from .draft_horizon import horizon_records
            horizon_records(smp, pair, th, hstride, hrec, kh)
        got, k, c, rows = _paint(smp["y"], pair, H)
        fresh = ~hit[got]
        pts = span_points(smp, k[fresh], c[fresh], rows[fresh], view)
        new = got & ~hit
        vals[new] = pts
        hit |= got
    return hit, vals[hit], evals


def _planes(view):
    """The sampling planes: view.step apart (the column pass's), or where the eye is
    among them (a fly camera's), from the eye a pixel's footprint apart at the
    surface's middle height (the level-of-detail engine's, kernels/lod.py
    plane_table, without its pyramid: the draft point-samples the heights)."""
    t0, t1 = view.t_range
    ca, sa = math.cos(view.alpha), math.sin(view.alpha)
    t_eye = -view.d3 * ca
    if _column_planes(view):
        n = max(int(math.floor((t1 - t0) / view.step + 1e-9)), 0) + 1
        t = t0 + np.arange(n) * view.step
        if t[-1] < t1 - 1e-6 * view.step:
            t = np.append(t, t1)
        return t
    s_ref = 0.5 * (view.f_range[0] + view.f_range[1]) - view.center[2]
    # a footprint: max(z + d3, d1) / (d1 scale) at z = s_ref sin(a) + t cos(a)
    # (lod.footprint_at_depth), so t + c grows by a factor a plane where z + d3 >= d1
    c = (s_ref * sa + view.d3) / ca
    grow = 1.0 + 1.0 / (view.d1 * view.scale) * ca
    # from the first plane where a point of the surface's heights may lie beyond the
    # screen plane (z + d3 > d1: before it nothing is drawn)
    s_top = max((h - view.center[2]) * sa for h in view.f_range)
    t = max(t0, t_eye, (view.d1 - view.d3 - s_top) / ca)
    start = max(view.d1 / ca - c, t)             # where z + d3 reaches d1
    # (a pixel apart before the screen plane, where nothing is drawn: at most
    # MAX_DRAFT_PLANES planes there too, as beyond it)
    n_near = min(int(math.ceil((start - t) * view.scale)), MAX_DRAFT_PLANES) if start > t else 0
    near = np.linspace(t, start, n_near, endpoint=False)
    n = int(math.ceil(math.log((t1 + c) / (start + c)) / math.log(grow))) + 1 \
        if t1 > start else 1
    n = min(n, MAX_DRAFT_PLANES)
    far = (start + c) * grow ** np.arange(n) - c
    return np.concatenate([near, far[far < t1], [t1]])


def crossings(y, pair, H):
    """Every pixel centre that a span of surface (``pair``) between two successive
    samples (screen rows ``y``, (n, m)) passes over: (seg, pix), the span (an index
    into the flattened (n - 1, m): k m + c for the span from plane k to k + 1 of column
    c) and the pixel (row j from the bottom, j m + c), in plane order."""
    n, m = y.shape
    ya, yb = y[:-1], y[1:]
    lo = np.where(pair, np.ceil(np.minimum(ya, yb)), 1.0)
    hi = np.where(pair, np.floor(np.maximum(ya, yb)), 0.0)
    lo = np.maximum(lo, 0.0)
    hi = np.minimum(hi, H - 1.0)
    cnt = np.maximum(hi - lo + 1.0, 0.0).astype(np.int64).ravel()
    seg = np.repeat(np.arange(cnt.size, dtype=np.int64), cnt)   # spans in plane order
    first = np.cumsum(cnt) - cnt
    j = lo.ravel().astype(np.int64)[seg] + (np.arange(seg.size, dtype=np.int64) - first[seg])
    return seg, j * m + seg % m


#: the G-buffer's channels (layout.py G_*) and the samples' fields (_points') they hold
G_FIELDS = ((L.G_DEPTH, "z"), (L.G_U, "u"), (L.G_V, "v"), (L.G_W, "w"), (L.G_NX, "nx"),
            (L.G_NY, "ny"), (L.G_NZ, "nz"), (L.G_I, "lam"), (L.G_T, "t"))


def _origins(view):
    """What the G-buffer's channels are kept from: u and v from the view's centre, w
    from its w_origin, as the kernels store them (layout.py G_U, G_W); 0 elsewhere."""
    return {L.G_U: view.center[0], L.G_V: view.center[1], L.G_W: view.w_origin}


def span_points(smp, k, c, rows, view):
    """(n, G_SIZE) float64: the G-buffer entries at pixel rows ``rows`` (from the
    bottom) on the spans from sample k - 1 to sample k of columns c (_samples' smp),
    each field linear in the row between the two."""
    y = smp["y"]
    y0, y1 = y[k - 1, c], y[k, c]
    dy = y1 - y0
    lam = np.clip(np.where(dy != 0.0, (rows - y0) / np.where(dy != 0.0, dy, 1.0), 0.0),
                  0.0, 1.0)
    origin = _origins(view)
    out = np.zeros((k.size, L.G_SIZE))
    for ch, name in G_FIELDS:
        a = smp[name]
        out[:, ch] = (a[k - 1, c] - origin.get(ch, 0.0)) + lam * (a[k, c] - a[k - 1, c])
    return out


def _paint(y, pair, H):
    """Front to back, the first span of surface (``pair``) between two successive
    samples (screen rows ``y``, (n, m)) over each pixel centre paints it: (hit (H, m)
    bool, plane index k of the span's far sample, its column, the pixel's row), rows
    from the bottom."""
    n, m = y.shape
    seg, pix = crossings(y, pair, H)
    best = np.full(H * m, np.iinfo(np.int64).max)
    np.minimum.at(best, pix, seg)                 # the nearest span over each pixel
    hit = best != np.iinfo(np.int64).max
    sel = best[hit]
    k = sel // m + 1
    c = sel % m
    return hit.reshape(H, m), k, c, np.flatnonzero(hit) // m


def draft_geometry(surface, view, hrec=None, hstride=0):
    """(g (H, W, G_SIZE) float32 rows from the bottom, seen (H, W) bool, evals (W,)):
    the draft's G-buffer (layout.py's G_* channels) of one layer; with ``hstride`` >
    0, a line drawing's, whose horizon records go to ``hrec`` (W, lines, H_SIZE) as
    the column pass writes them (passes/draft_horizon.py; no column traced ray by
    ray: the kernels trace no folds in a line drawing either)."""
    W, H = view.width, view.height
    t = _planes(view)
    g = np.zeros((H, W, L.G_SIZE), dtype=np.float32)
    seen = np.zeros((H, W), dtype=bool)
    evals = np.zeros(W, dtype=np.int64)
    block = max(1, BLOCK_SAMPLES // max(t.size, 1))
    origin = _origins(view)
    twice = split(view)
    index = halves(view, t, index=True)[0][1]      # (the planes' numbers: a line's)
    traces = not view.orthographic and _column_planes(view) and hstride == 0 and not twice
    rays = None
    budget = RAY_EVALS
    for c0 in range(0, W, block):
        cols = np.arange(c0, min(W, c0 + block), dtype=np.float64)
        if twice:           # (looking down past the nadir: no fold traced ray by ray)
            hit, vals, ev = _split_block(surface, view, cols, t, None if hrec is None else
                                         hrec[c0:c0 + cols.size], hstride)
            evals[c0:c0 + cols.size] = ev // max(cols.size, 1)
            g[:, c0:c0 + cols.size][hit] = vals
            seen[:, c0:c0 + cols.size] = hit
            continue
        smp, pair, ev = _samples(surface, view, cols, t)
        evals[c0:c0 + cols.size] = ev // max(cols.size, 1)
        if hstride > 0:
            from .draft_horizon import horizon_records
            horizon_records(smp, pair, t, hstride, hrec[c0:c0 + cols.size], index)
        hit, k, c, rows = _paint(smp["y"], pair, H)
        gb = g[:, c0:c0 + cols.size]
        gb[hit] = span_points(smp, k, c, rows, view)
        # a column whose curve folds back: ray by ray instead (_ray_columns), where
        # the picture is the column pass's (the lod engine's traces no folds)
        x0 = (cols - (W - 1) * 0.5) / view.scale
        folds = _fold_columns(view, smp, x0) if traces else ()
        for g0 in range(0, len(folds), RAY_COLUMNS):
            if budget <= 0:
                break
            if rays is None:
                rays = _rays(view, t)
            cf = folds[g0:g0 + RAY_COLUMNS]
            hit_f, f, ev = _ray_columns(surface, view, x0[cf], t, rays)
            budget -= ev
            evals[c0 + cf] += ev // cf.size
            rows = rays[0][:, None]                # (the rows the rays drew)
            hit[:, cf] = np.where(rows, hit_f, hit[:, cf])
            for ch, name in G_FIELDS:
                gb[:, cf, ch] = np.where(rows & hit_f, f[name] - origin.get(ch, 0.0),
                                         gb[:, cf, ch])
        seen[:, c0:c0 + cols.size] = hit
    n = g[..., L.G_NX:L.G_NZ + 1]
    norm = np.sqrt((n.astype(np.float64) ** 2).sum(-1, keepdims=True))
    g[..., L.G_NX:L.G_NZ + 1] = np.where(norm > 0, n / np.where(norm > 0, norm, 1.0), 0.0)
    return g, seen, evals


def _toward_viewer(view, H, W, depth):
    return viewer_at(view, np.arange(W), np.arange(H)[:, None], depth)


def viewer_at(view, cols, rows, depth):
    """The unit vector toward the viewpoint at pixel columns ``cols`` and rows ``rows``
    (from the bottom) and depth ``depth`` (arrays that broadcast)."""
    if view.orthographic:
        return 0.0, 0.0, -1.0
    x0 = (cols - (view.width - 1) * 0.5) / view.scale
    y0 = (rows - (view.height - 1) * 0.5) / view.scale
    e = depth + view.d3
    m = e / view.d1
    vx, vy, vz = -x0 * m, -y0 * m, -e
    q = 1.0 / np.sqrt(vx * vx + vy * vy + vz * vz)
    return vx * q, vy * q, vz * q


def draft_finish(view, g, side, material, terms, lut, w_lo, w_hi, lower_rgb, bg8, base=None,
                 lit=None):
    """(rgba (H, W, 4) uint8, intensity (H, W) float32), rows from the bottom, of the
    draft's G-buffer g and seen sides ``side`` (_sides): finish_kernel's colours of a
    fully covered pixel (shade.py's _light, _side_rgb, pixel_rgba), in numpy. ``base``
    (H, W, 3): the surface's colours (a texture's or colour field's: draft_base)
    instead of its sides'; ``lit`` (H, W): the part of the light that reaches each
    point (draft_shadow's; None: all of it)."""
    H, W = side.shape
    seen = side != 0
    rgb, inten = shade(view, g, side, np.arange(W), np.arange(H)[:, None], material, terms,
                       lut, w_lo, w_hi, lower_rgb, base, lit)
    rgba = np.empty((H, W, 4), dtype=np.uint8)
    rgba[...] = bg8
    rgba[seen, :3] = (rgb[seen] * 255.0 + 0.5).astype(np.uint8)
    rgba[seen, 3] = 255
    return rgba, np.where(seen, inten, np.nan).astype(np.float32)


def shade(view, g, side, cols, rows, material, terms, lut, w_lo, w_hi, lower_rgb, base=None,
          lit=None):
    """(rgb (..., 3) in [0, 1], intensity (...)) of the points g (..., G_SIZE) seen from
    ``side`` (+1 upper, else lower) at pixel columns ``cols`` and rows ``rows`` (from the
    bottom; arrays that broadcast with g's shape): finish_kernel's light and colour
    (shade.py's _light, _side_rgb), ``base`` the surface's colours instead of its
    sides', ``lit`` the part of the light that reaches each point."""
    ambient, specular, shininess = terms
    depth = g[..., L.G_DEPTH].astype(np.float64)
    nx, ny, nz = (g[..., ch].astype(np.float64) for ch in (L.G_NX, L.G_NY, L.G_NZ))
    vx, vy, vz = viewer_at(view, cols, rows, depth)
    lx, ly, lz = view.light
    if lx == 0.0 and ly == 0.0 and lz == 0.0:
        lx, ly, lz = vx, vy, vz
    nl = lx * nx + ly * ny + lz * nz
    lam = g[..., L.G_I].astype(np.float64) if material.interp == INTERP_INTENSITY \
        else np.abs(nl)
    lit = 1.0 if lit is None else lit
    inten = ambient + (1.0 - ambient) * np.minimum(lam, 1.0) * lit
    sp = np.zeros(depth.shape)
    if specular > 0.0:
        nv = nx * vx + ny * vy + nz * vz
        flip = nv < 0.0                       # the seen side's normal
        nv_s = np.where(flip, -nv, nv)
        nl_s = np.where(flip, -nl, nl)
        rv = 2.0 * nl_s * nv_s - (lx * vx + ly * vy + lz * vz)   # R.V
        ok = (nl_s > 0.0) & (rv > 0.0)
        sp = np.where(ok, specular * np.power(np.where(ok, rv, 0.0), shininess), 0.0) * lit
    w = g[..., L.G_W].astype(np.float64) + view.w_origin       # (layout.py G_W)
    if base is None:
        upper = colour_table_rgb(w, lut, w_lo, w_hi)
        rgb = np.where((side > 0)[..., None], upper, lower_or_upper(lower_rgb, upper))
    else:
        rgb = base
    return np.minimum(rgb * inten[..., None] + sp[..., None], 1.0), inten


def draft_base(material, source, view, g, side, box, own):
    """((H, W, 3) colours, c_limits or None): a texture's or colour field's colours
    (passes/colour.py ``source``) at the draft's seen points, rows from the bottom,
    both sides, in numpy: a texture image bilinear on the mip level of each pixel's
    footprint (its texel coordinates' steps to the next pixel; texture_kernel's
    filters left for the kernels), premultiplied over the surface's own colours
    ``own`` (H, W, 3); a colour field through the material's colour map over the
    values seen."""
    from .colour import _bilinear, _called, field_rgb, field_table, field_values
    seen = side != 0
    u = (g[..., L.G_U].astype(np.float64) + view.center[0]) / box[0]   # (layout.py G_U)
    v = (g[..., L.G_V].astype(np.float64) + view.center[1]) / box[1]
    out = own.copy()
    if not seen.any():
        return out, None
    if source.field is not None:
        vals = field_values(source.field, u, v, seen, source.extent)
        table = field_table(material, vals, material.colors()[1])
        out[seen] = field_rgb(vals, table)
        return np.clip(out, 0.0, 1.0), table[3]
    if callable(source.texture):
        tex = _called(source.texture, u[seen], v[seen])
    else:
        levels = source.texture
        u0, u1, v0, v1 = source.extent
        h, w = (int(x) for x in levels.shapes[0])
        x = (u - u0) / (u1 - u0) * (w - 1)        # node-centred, as texture_base
        y = (v - v0) / (v1 - v0) * (h - 1)
        # the footprint: the largest step of the texel coordinates to a seen neighbour
        step = np.zeros(x.shape)
        for a in (x, y):
            for axis in (0, 1):
                d = np.abs(np.diff(a, axis=axis))
                ok = np.isfinite(d)
                d = np.where(ok, d, 0.0)
                pad = [(0, 0), (0, 0)]
                pad[axis] = (1, 0)
                step = np.maximum(step, np.pad(d, pad))
                pad[axis] = (0, 1)
                step = np.maximum(step, np.pad(d, pad))
        k = np.clip(np.floor(np.log2(np.maximum(step, 1.0))), 0,
                    len(levels.shapes) - 1).astype(np.int64)
        tex = np.zeros((int(seen.sum()), 4))
        ks, xs, ys = k[seen], x[seen], y[seen]
        for lv in np.unique(ks):
            hk, wk = (int(n) for n in levels.shapes[lv])
            o = int(levels.offsets[lv])
            level = levels.flat[o:o + hk * wk * 4].reshape(hk, wk, 4)
            at = ks == lv
            tex[at] = _bilinear(level, xs[at] * (wk - 1) / max(w - 1, 1),
                                ys[at] * (hk - 1) / max(h - 1, 1))
    out[seen] = tex[:, :3] + (1.0 - tex[:, 3:4]) * own[seen]   # premultiplied over it
    return np.clip(out, 0.0, 1.0), None


def _sides(view, g, seen):
    """(H, W) int8 rows from the bottom: +1 where the upper side is seen, -1 the
    lower, 0 nothing (the side the normal turns toward the viewer)."""
    H, W = seen.shape
    vx, vy, vz = _toward_viewer(view, H, W, g[..., L.G_DEPTH].astype(np.float64))
    nv = g[..., L.G_NX] * vx + g[..., L.G_NY] * vy + g[..., L.G_NZ] * vz
    return np.where(seen, np.where(nv > 0.0, 1, -1), 0).astype(np.int8)


def column_ranges(g, side, w_origin=0.0):
    """(W, 2) the lowest and highest w seen with the upper side in each column (as
    column_kernel's ``wrange``; +inf, -inf where none); g's w from ``w_origin``
    (layout.py G_W)."""
    up = side > 0
    w = g[..., L.G_W].astype(np.float64) + w_origin
    return np.stack([np.where(up, w, np.inf).min(axis=0),
                     np.where(up, w, -np.inf).max(axis=0)], axis=1)


def planes(gbuf, side, view, box):
    """(u, v, w, side) of each pixel, top row first, as colour.picture_planes gives them
    from the kernels' G-buffer (the surface's units, NaN where nothing is seen), from
    the draft's tiled G-buffer ``gbuf`` and sides ``side`` (top row first)."""
    H, W = side.shape
    g = gbuf.transpose(1, 0, 2, 3).reshape(H, -1, L.G_SIZE)[::-1, :W].astype(np.float64)
    seen = side != 0
    out = []
    for ch, origin, stretch in ((L.G_U, view.center[0], box[0]),
                                (L.G_V, view.center[1], box[1]),
                                (L.G_W, view.w_origin, box[2])):
        out.append(np.where(seen, (g[..., ch] + origin) / stretch, np.nan))
    return (*out, side.astype(np.float64))


def tiled(g):
    """(H, W, C) -> the G-buffer's tiles (n_tiles, H, TILE, C) (layout.py)."""
    H, W, C = g.shape
    n_tiles = -(-W // L.TILE)
    padded = np.zeros((H, n_tiles * L.TILE, C), dtype=g.dtype)
    padded[:, :W] = g
    return np.ascontiguousarray(padded.reshape(H, n_tiles, L.TILE, C).transpose(1, 0, 2, 3))


def draft_pass(surface, view, material, terms, box, bg8, source=None, shadows=None):
    """The draft picture of one layer, top row first: (rgba, side, intensity, depth,
    tiled G-buffer, evaluations per column, w_limits, c_limits, shadow or None);
    ``source`` its texture or colour field (passes/colour.py prepare's), or None;
    ``shadows`` (the light's passes/shadow.py Texture, not swept; the layer's index in it)
    or None (passes/draft_shadow.py)."""
    W, H = view.width, view.height
    check_bytes(W, H, W * H * DRAFT_BYTES)
    try:
        g, seen, evals = draft_geometry(surface, view)
    except MemoryError:
        raise ValueError(too_large(W, H, W * H * DRAFT_BYTES)) from None
    side = _sides(view, g, seen)
    _, lower_rgb = material.colors()
    lut, w_lo, w_hi, w_limits = material.color_table(column_ranges(g, side, view.w_origin),
                                                     box[2])
    base = c_limits = None
    if source is not None:
        upper = colour_table_rgb(g[..., L.G_W].astype(np.float64) + view.w_origin, lut, w_lo,
                           w_hi)
        own = np.where((side > 0)[..., None], upper, lower_or_upper(lower_rgb, upper))
        base, c_limits = draft_base(material, source, view, g, side, box, own)
    shadow = lit = None
    if shadows is not None:
        from .draft_shadow import draft_shadow
        shadow, lit = draft_shadow(shadows[0], shadows[1], view, g, side)
    rgba, intensity = draft_finish(view, g, side, material, terms, lut, w_lo, w_hi,
                                   lower_rgb, bg8, base, lit)
    depth = np.where(seen, g[..., L.G_DEPTH], np.inf).astype(np.float32)
    return (rgba[::-1], side[::-1], intensity[::-1], depth[::-1], tiled(g), evals,
            w_limits, c_limits, None if shadow is None else shadow[::-1])
