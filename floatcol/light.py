"""Lights: the frame a light lives in is part of the light (PyVista's ``Light``).

- ``Light.headlight()``: at the viewpoint (orthographic: toward the viewer), the
  paper's eq. (12) and the reference model of ``shading="lambert"``.
- ``Light.key(direction)``: fixed to the screen, a direction (x, y, z) toward the
  light in screen coordinates; the default shading's light is
  ``Light.key(DEFAULT_LIGHT)``, from the upper left, toward the viewer.
- ``Light.directional(direction)`` or ``Light.sun(azdeg, altdeg)``: fixed to the
  surface, a direction (u, v, w) toward the light, as matplotlib's
  ``LightSource(azdeg, altdeg).direction``; it turns with the camera.

The kernels take one light, as a screen direction (``screen_direction``); zeros mean
the headlight (kernels/sample.py ``lambert``).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

#: the key light of the default shading: from the upper left, toward the viewer
DEFAULT_LIGHT = (-0.45, 0.55, -1.0)
KINDS = ("headlight", "key", "directional")
#: Gordon's two ways to cast shadows (passes/shadow.py)
SHADOW_METHODS = ("texture", "on-the-fly")


@dataclass(frozen=True)
class Light:
    """A light: ``kind`` one of "headlight", "key" (screen-fixed) and "directional"
    (world-fixed); ``direction`` toward the light in the kind's frame (None for the
    headlight)."""
    kind: str = "headlight"
    direction: tuple | None = None
    #: cast and attached shadows (Gordon section 6.2; passes/shadow.py)
    shadows: bool = False
    #: the light's angular radius in degrees (a disk: the sun's is 0.27): soft shadows,
    #: whose penumbra behind an edge at distance D is about 2 D tan(radius) wide; 0 a
    #: point at infinity (hard shadows, antialiased)
    radius: float = 0.0
    #: how cast shadows are found: "texture" (section 6.2.1, the default: one shadow
    #: texture for every surface) or "on-the-fly" (6.2.2: no texture, one surface)
    shadow_method: str = "texture"

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"a light's kind must be one of {', '.join(KINDS)}, got {self.kind!r}")
        object.__setattr__(self, "shadows", bool(self.shadows))
        object.__setattr__(self, "radius", _radius(self.radius))
        if self.shadow_method not in SHADOW_METHODS:
            raise ValueError("shadows must be True, False, " +
                             ", ".join(repr(m) for m in SHADOW_METHODS) +
                             f", got {self.shadow_method!r}")
        if self.radius > 0.0 and not self.shadows:
            raise ValueError("light_radius gives soft shadows: use it with shadows=True")
        if self.kind == "headlight":
            if self.direction is not None:
                raise ValueError("a headlight lights from the viewpoint: it takes no direction")
            if self.shadows:
                raise ValueError("a headlight lights from the viewpoint, where nothing seen "
                                 "is in shadow: give a lightsource for shadows")
            return
        object.__setattr__(self, "direction", _direction(self.direction, self.kind))

    @classmethod
    def headlight(cls):
        return cls("headlight")

    @classmethod
    def key(cls, direction=DEFAULT_LIGHT, shadows=False, radius=0.0):
        return cls("key", direction, shadows, radius)

    @classmethod
    def directional(cls, direction, shadows=False, radius=0.0):
        return cls("directional", direction, shadows, radius)

    @classmethod
    def sun(cls, azdeg=315.0, altdeg=45.0, shadows=False, radius=0.0):
        """A world-fixed light as matplotlib's ``LightSource(azdeg, altdeg)``: azimuth
        clockwise from north (+v), altitude above the (u, v) plane, in degrees."""
        from .view import _number
        az = math.radians(90.0 - _number("azdeg", azdeg))
        alt = math.radians(_number("altdeg", altdeg))
        return cls("directional", (math.cos(az) * math.cos(alt), math.sin(az) * math.cos(alt),
                                   math.sin(alt)), shadows, radius)

    def world_direction(self, elev, azim):
        """The direction toward the light in world (u, v, w) for render()'s angles
        (a key light's turns with the camera), or None for the headlight."""
        if self.kind == "headlight":
            return None
        if self.kind == "directional":
            return self.direction
        return screen_to_world_direction(self.direction, elev, azim)

    def screen_direction(self, elev, azim):
        """The kernels' light for render()'s angles (degrees): a unit screen direction,
        or None for the headlight."""
        if self.kind == "headlight":
            return None
        if self.kind == "key":
            return self.direction
        return world_to_screen_direction(self.direction, elev, azim)


def _direction(d, kind):
    frame = "(x, y, z) in screen" if kind == "key" else "(u, v, w) in world"
    try:
        if isinstance(d, (str, bytes)):
            raise TypeError
        x, y, z = (float(c) for c in d)
    except (TypeError, ValueError):
        raise ValueError(f"light must be a direction {frame} coordinates, got {d!r}") from None
    if not all(math.isfinite(c) for c in (x, y, z)):
        raise ValueError(f"light must be finite, got {d!r}")
    if x == y == z == 0.0:
        raise ValueError(f"light must be a non-zero direction {frame[:9]}, got {d!r}")
    return tame_direction((x, y, z))


def tame_direction(d):
    """A direction whose squares neither overflow nor underflow: d itself, or where its
    largest component is beyond 1e+-150, d over that component ((1e300, 1e300, 1)
    overflowed in its length, three 1e-300s underflowed to a zero length)."""
    m = max(abs(c) for c in d)
    if m == 0.0 or 1e-150 < m < 1e150:
        return tuple(d)
    return tuple(c / m for c in d)


#: the largest angular radius of a light, degrees
MAX_RADIUS = 30.0


def _radius(given):
    try:
        if isinstance(given, (bool, str, bytes)):
            raise TypeError
        r = float(given)
    except (TypeError, ValueError):
        raise ValueError(f"light_radius must be an angle in degrees (the sun's is 0.27), "
                         f"got {given!r}") from None
    if not 0.0 <= r <= MAX_RADIUS:
        raise ValueError(f"light_radius must be in [0, {MAX_RADIUS:g}] degrees, got {r}")
    return r


def world_to_screen_direction(d, elev, azim):
    """A direction in world (u, v, w) -> screen (x, y, z) for render()'s angles."""
    a, b = -math.radians(elev), math.radians(azim)
    ca, sa, cb, sb = math.cos(a), math.sin(a), math.cos(b), math.sin(b)
    du, dv, s = d
    r = du * cb - dv * sb
    t = du * sb + dv * cb
    return (r, s * ca - t * sa, s * sa + t * ca)


def screen_to_world_direction(d, elev, azim):
    """The inverse of world_to_screen_direction."""
    a, b = -math.radians(elev), math.radians(azim)
    ca, sa, cb, sb = math.cos(a), math.sin(a), math.cos(b), math.sin(b)
    x, y, z = d
    s = y * ca + z * sa
    t = -y * sa + z * ca
    return (x * cb + t * sb, -x * sb + t * cb, s)


_LAMBERT = ("shading='lambert' lights from the viewpoint; leave light=None or use "
            "shading='default'")


def as_light(light, shading, lightsource=None, shadows=False, light_radius=0.0):
    """render()'s ``light`` keyword as a Light: None is the shading's own (the key
    light for "default", the headlight for "lambert"), a Light as is, and a triple a
    key light's screen direction (render's convention since 0.1). ``lightsource``
    (azdeg, altdeg) or a matplotlib LightSource: a sun instead; ``shadows``: the light
    casts shadows, soft ones from a disk of ``light_radius`` degrees."""
    if lightsource is not None:
        if light is not None:
            raise ValueError("give either lightsource or light, not both")
        light = _sun(lightsource)
    if isinstance(shadows, str) and shadows not in SHADOW_METHODS:
        raise ValueError("shadows must be True, False, " +
                         ", ".join(repr(m) for m in SHADOW_METHODS) + f", got {shadows!r}")
    if shadows:
        if shading == "lambert":
            raise ValueError("shading='lambert' lights from the viewpoint, where nothing seen "
                             "is in shadow; use shading='default' for shadows")
        if light is None:
            light = Light("key", DEFAULT_LIGHT)
        elif not isinstance(light, Light):
            light = Light("key", light)
        method = shadows if isinstance(shadows, str) else light.shadow_method
        light = Light(light.kind, light.direction, True, light_radius or light.radius, method)
    elif light_radius:
        _radius(light_radius)
        raise ValueError("light_radius gives soft shadows: use it with shadows=True")
    if isinstance(light, Light):
        if shading == "lambert" and light.kind != "headlight":
            raise ValueError(_LAMBERT)
        return light
    if shading == "lambert":
        if light is not None:
            raise ValueError(_LAMBERT)
        return Light.headlight()
    if light is None:
        return Light("key", DEFAULT_LIGHT)
    return Light("key", light)


def _sun(lightsource):
    """A sun from render's ``lightsource``: (azdeg, altdeg) or a LightSource."""
    if hasattr(lightsource, "azdeg") and hasattr(lightsource, "altdeg"):
        return Light.sun(lightsource.azdeg, lightsource.altdeg)
    try:
        az, alt = lightsource
    except (TypeError, ValueError):
        raise ValueError("lightsource must be (azdeg, altdeg) in degrees or a "
                         f"matplotlib.colors.LightSource, got {lightsource!r}") from None
    return Light.sun(az, alt)
