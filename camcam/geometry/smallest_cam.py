"""One cam's smallest base radius (and best offset) for a pressure-angle limit (the sweep over
many designs, `camcam size`, is :mod:`camcam.sizing`).

Defaults: the kind's ``default_max_pressure_angle_deg`` (30° for a translating
follower, 35° for an oscillating one).  The
search runs on a dense sample of the lift (fast, vectorised); the answer is
then polished against the exact analysis (:func:`camcam.geometry.analysis.analyse`,
root-found extremes) so that the returned cam meets the limit exactly to
1e-6 mm of base radius.  Flat-faced followers have no pressure angle to limit:
their size is the smallest base radius without a cusp.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from camcam.errors import GeometryError
from camcam.geometry.analysis import max_pressure_angle, smallest_base_radius_without_undercut, undercut_margin
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import TranslatingRoller

__all__ = ["Sizing", "size_cam"]

#: Samples of the lift per revolution for the search stage (the result is polished exactly).
SEARCH_SAMPLES = 7200


@dataclass(frozen=True, kw_only=True)
class Sizing:
    """The sized cam and its figures."""

    cam: DiscCam
    base_radius_mm: float
    offset_mm: float | None
    max_pressure_angle_deg: float
    limit_deg: float | None


def _max_pa(cam: DiscCam) -> float:
    return max_pressure_angle(cam).value


def _search_translating(cam: DiscCam, limit: float) -> tuple[float, float]:
    t = np.linspace(0.0, 2 * math.pi, SEARCH_SAMPLES, endpoint=False)
    s, s1 = cam.program.lift(t), cam.program.lift(t, 1)
    rr, sg = cam.roller_radius, cam.sigma

    def worst(rb: float, e: float) -> float:
        rp = rb + rr
        return float(np.max(np.abs(np.arctan2(s1 - sg * e, math.sqrt(max(rp * rp - e * e, 0.0)) + s))))

    def best(rb: float) -> tuple[float, float]:
        rp = rb + rr
        r = minimize_scalar(lambda e: worst(rb, e), bounds=(-0.9 * rp, 0.9 * rp), method="bounded", options={"xatol": 1e-6})
        return float(r.fun), float(r.x)

    lo, hi = 1e-3, max(1.0, rr)
    while best(hi)[0] > limit:
        lo, hi = hi, hi * 2
        if hi > 1e5:
            raise GeometryError(f"no base radius up to 100 m keeps the pressure angle under {math.degrees(limit):g}°")
    rb = brentq(lambda r: best(r)[0] - limit, lo, hi, xtol=1e-6) if best(lo)[0] > limit else lo
    return rb, best(rb)[1]


def size_cam(cam: DiscCam, limit_deg: float | None = None, optimise_offset: bool = True) -> Sizing:
    """Smallest base radius (and, for a translating roller, the best offset) of ``cam``'s kind.

    Examples
    --------
    >>> from camcam.motion.catalog import make_law
    >>> from camcam.motion.program import MotionProgram, Segment
    >>> p = MotionProgram((Segment(make_law("cycloidal"), 0, 180, 20.0),
    ...                    Segment(make_law("cycloidal"), 180, 360, -20.0, base=20.0)), rpm=60)
    >>> z = size_cam(DiscCam(TranslatingRoller(roller_radius=10.0), p, base_radius=30.0), optimise_offset=False)
    >>> round(z.max_pressure_angle_deg, 6)
    30.0
    """
    if not cam.is_roller:
        rb = smallest_base_radius_without_undercut(replace(cam, base_radius=1e-3))
        sized = replace(cam, base_radius=rb)
        return Sizing(cam=sized, base_radius_mm=rb, offset_mm=None, max_pressure_angle_deg=0.0, limit_deg=None)
    limit_deg = cam.follower.default_max_pressure_angle_deg if limit_deg is None else float(limit_deg)
    if not 0 < limit_deg < 90:
        raise GeometryError(f"pressure-angle limit must be between 0 and 90°, got {limit_deg:g}")
    limit = math.radians(limit_deg)
    offset = None
    if "offset" in cam.follower.spec_keys and optimise_offset:  # a roller on a stem: the offset is free
        rb, offset = _search_translating(cam, limit)
        base = replace(cam, follower=replace(cam.follower, offset=offset), base_radius=rb)
    else:
        base = cam

    def excess(rb: float) -> float:
        try:
            return _max_pa(replace(base, base_radius=rb)) - limit_deg
        except GeometryError:
            return 90.0

    lo = hi = base.base_radius
    while excess(hi) > 0:
        lo, hi = hi, hi * 1.5
        if hi > 1e5:
            raise GeometryError(f"no base radius up to 100 m keeps the pressure angle under {limit_deg:g}°")
    while excess(lo) <= 0 and lo > 1e-2:
        hi, lo = lo, lo / 1.5
    rb = brentq(excess, lo, hi, xtol=1e-7) if excess(lo) > 0 else lo
    if undercut_margin(replace(base, base_radius=rb))[0] <= 0:
        rb = smallest_base_radius_without_undercut(replace(base, base_radius=rb))
    sized = replace(base, base_radius=rb)
    return Sizing(cam=sized, base_radius_mm=rb, offset_mm=offset, max_pressure_angle_deg=_max_pa(sized),
                  limit_deg=limit_deg)
