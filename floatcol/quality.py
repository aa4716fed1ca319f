"""Quality: how hard the renderer works for a picture (sampling, corrections,
antialiasing), as one object. ``resolve`` checks it and gives the values the passes
and the kernels take."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .kernels import layout as L
from .kernels.shade import INTERP_INTENSITY
from .material import INTERPOLATIONS, fraction

METHODS = ("column", "horizon")
DEFAULT_LINES = 160             # horizon lines, as in the paper's figures
#: artifact corrections (section 5): what fixes a ridge, and what fixes a shading
#: problem (intensity jump, bump); the default is the best picture per cost measured
#: by benchmarks/bench_fidelity.py
CORRECTIONS = {"none": (L.FIX_NONE, L.FIX_NONE),
               "spline": (L.FIX_SPLINE, L.FIX_NONE),
               "supersample": (L.FIX_SUPER, L.FIX_SUPER),
               "adaptive": (L.FIX_ADAPTIVE, L.FIX_ADAPTIVE),
               "spline+supersample": (L.FIX_SPLINE, L.FIX_SUPER),
               "spline+adaptive": (L.FIX_SPLINE, L.FIX_ADAPTIVE)}
DEFAULT_CORRECTIONS = "spline+adaptive"
DETECTORS = {"ridge": L.DETECT_RIDGE, "intensity": L.DETECT_JUMP, "bump": L.DETECT_BUMP,
             "wall": L.DETECT_WALL}
DEFAULT_JUMP = 1.0 / 16.0       # the paper's threshold: 1/16 of the maximal intensity
DEFAULT_RATE = 16               # the paper's supersampling rate
SAMPLINGS = ("uniform", "adaptive", "lod", "march")
#: where the column pass runs: the CPU's cores, or an NVIDIA GPU (kernels/cuda.py)
DEVICES = ("cpu", "cuda")


@dataclass
class Quality:
    """method "column" (shaded) or "horizon" (``lines`` monochrome lines); the
    sampling planes (``step`` in world units or ``pixel_step`` pixels apart,
    ``sampling`` "uniform" or "adaptive", perspective ``placement``); the corrections
    of section 5 (``corrections``, ``detect``, ``jump_threshold``,
    ``supersample_rate``, ``spline_tolerance``); ``antialias`` (section 6.4); the
    ``device`` the column pass runs on ("cpu", "cuda")."""
    method: str = "column"
    lines: int = DEFAULT_LINES
    step: float | None = None
    pixel_step: float = 1.0
    sampling: str = "uniform"
    placement: str = "exact"
    corrections: str = DEFAULT_CORRECTIONS
    detect: Any = None
    jump_threshold: float = DEFAULT_JUMP
    supersample_rate: int = DEFAULT_RATE
    spline_tolerance: float | None = None
    antialias: Any = None
    device: str = "cpu"

    def check_method(self):
        if not isinstance(self.method, str) or self.method not in METHODS:
            raise ValueError(f"method must be one of {', '.join(METHODS)}, got {self.method!r}")

    def n_lines(self):
        return whole("lines", self.lines)

    def fixes(self, interpolation):
        """The six VP_FIX_RIDGE .. VP_SPLINE_TOL values (checked)."""
        return corrections(self.corrections, self.detect, interpolation, self.jump_threshold,
                           self.supersample_rate, self.spline_tolerance)

    def antialiasing(self, shading):
        """(coverage blending along columns, sub-columns per pixel)."""
        return antialias(self.antialias, self.method, shading)

    @property
    def area(self):
        """Exact area sampling along the columns (antialias="area", Cohen-Or 1997)."""
        return isinstance(self.antialias, str) and self.antialias == "area"

    def check_device(self):
        """ValueError for a device that is not one, or one that cannot run here
        ("cuda": the column pass, area sampling's or the translucent layers', on an
        NVIDIA GPU, kernels/cuda.py)."""
        if not isinstance(self.device, str) or self.device not in DEVICES:
            raise ValueError(f"device must be 'cpu' or 'cuda', got {self.device!r}")
        if self.device == "cuda":
            from .kernels.cuda import check_device
            check_device()

    def check_sampling(self):
        if self.sampling not in SAMPLINGS:
            raise ValueError("sampling must be 'uniform', 'adaptive', 'lod' or 'march', got "
                             f"{self.sampling!r}")
        if self.sampling in ("lod", "march") and not isinstance(
                self.antialias, (bool, np.bool_, str, type(None))):
            raise ValueError(f"sampling={self.sampling!r} antialiases along the columns: use "
                             "antialias=True, 'area' or False (not sub-columns)")


def corrections(corrections, detect, interpolation, jump, rate, tol):
    """Check the correction options; the six VP_FIX_RIDGE .. VP_SPLINE_TOL values."""
    if not isinstance(corrections, str) or corrections not in CORRECTIONS:
        raise ValueError(f"corrections must be one of {', '.join(map(repr, CORRECTIONS))}, "
                         f"got {corrections!r}")
    fix_r, fix_s = CORRECTIONS[corrections]
    if corrections == "none":
        detect = ()                   # the plain floating column of section 4
    if detect is None:
        detect = ("ridge", "intensity", "wall") + (("bump",) if INTERPOLATIONS[interpolation]
                                                    == INTERP_INTENSITY else ())
    elif isinstance(detect, str):
        detect = (detect,)
    mask = 0
    try:
        names = list(detect)
    except TypeError:
        raise ValueError(f"detect must be a list of {', '.join(DETECTORS)}, got {detect!r}") from None
    for name in names:
        if name not in DETECTORS:
            raise ValueError(f"detect: unknown problem {name!r}; use any of "
                             f"{', '.join(DETECTORS)}")
        mask |= DETECTORS[name]
    jump = fraction("jump_threshold", jump)
    if isinstance(rate, bool) or not isinstance(rate, (int, np.integer)) or not 2 <= rate <= 256:
        raise ValueError(f"supersample_rate must be a whole number from 2 to 256, got {rate!r}")
    tol = 0.0 if tol is None else fraction("spline_tolerance", tol)
    return float(fix_r), float(fix_s), float(mask), jump, float(rate), tol


def antialias(antialias, method, shading):
    """(coverage blending along columns, sub-columns per pixel)."""
    if antialias is None:
        antialias = method == "column" and shading == "default"
    if isinstance(antialias, (bool, np.bool_)):
        return bool(antialias) and method == "column", 1
    if isinstance(antialias, str) and antialias == "area":
        if method != "column":
            raise ValueError("antialias='area' applies to method='column' only")
        return True, 1
    if isinstance(antialias, (int, np.integer)) and 2 <= antialias <= 4:
        if method != "column":
            raise ValueError("antialias with sub-columns applies to method='column' only")
        return True, int(antialias)
    raise ValueError("antialias must be True, False, 2, 3, 4 sub-columns or 'area', got "
                     f"{antialias!r}")


def whole(name, x):
    if isinstance(x, bool) or not isinstance(x, (int, np.integer)) or x < 1:
        raise ValueError(f"{name} must be a positive whole number, got {x!r}")
    return int(x)
