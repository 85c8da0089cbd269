"""A cam rebuilt at another base radius, and the smallest base radius that meets a limit.

Advice such as ``cam.base_radius >= 47.2 mm`` is measured, not extrapolated:
:func:`base_radius_meeting` searches upwards from the cam's own radius, rebuilding
the cam at each trial radius (:func:`cam_at`: a face groove's inner cam, a
cylinder's radius; a barrel cam's oscillating roller has its pivot moved out by
as much, so the arm stays in the groove), and returns a radius at which the
rebuilt cam meets the limit.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Callable

from camcam.errors import GeometryError

__all__ = ["cam_at", "moves_pivot", "is_barrel", "base_radius_meeting", "base_radius_advice"]


def moves_pivot(cam) -> bool:
    """A barrel cam's oscillating roller: its pivot moves out with the cylinder radius (the arm stays in the groove)."""
    return is_barrel(cam) and getattr(cam.follower, "pivot_distance", None) is not None


def is_barrel(cam) -> bool:
    return hasattr(cam, "groove_depth") and not hasattr(cam, "flanks")


def cam_at(cam, base_radius_mm: float):
    """``cam`` with another base radius (a face groove's inner cam, a cylinder's radius; a barrel cam's oscillating
    roller's pivot moved out by as much)."""
    if hasattr(cam, "flanks"):
        return replace(cam, cam=replace(cam.cam, base_radius=base_radius_mm))
    if moves_pivot(cam):
        pivot = cam.follower.pivot_distance + base_radius_mm - cam.base_radius
        return replace(cam, base_radius=base_radius_mm, follower=replace(cam.follower, pivot_distance=pivot))
    return replace(cam, base_radius=base_radius_mm)


def base_radius_meeting(cam, margin: Callable[[object], float], cap_mm: float = 10_000.0) -> float | None:
    """The smallest base radius (mm, rounded up to 0.1 mm) at which ``margin(cam)`` ≥ 0 for ``cam`` rebuilt
    with it, searched upwards from its own; None when none up to ``cap_mm`` does.  The value returned is
    measured, not extrapolated: the cam at exactly that radius meets the limit.  A barrel cam's
    oscillating roller has its pivot moved out by as much as the radius grows (:func:`cam_at`)."""

    def m(r: float) -> float | None:
        try:
            return float(margin(cam_at(cam, r)))
        except (GeometryError, ValueError):
            return None

    lo, m_lo = cam.base_radius, m(cam.base_radius)
    hi, m_hi = lo, m_lo
    while m_hi is None or m_hi < 0:
        lo, m_lo = hi, m_hi
        hi = hi * 1.25
        if hi > cap_mm:
            return None
        m_hi = m(hi)
    side = 0
    for _ in range(30):  # false position (Illinois) where both ends are measured, else halving
        if hi - lo <= 0.05:
            break
        if m_lo is not None and m_lo < 0 < m_hi:
            mid = hi - m_hi * (hi - lo) / (m_hi - m_lo)
            mid = min(max(mid, lo + 0.01 * (hi - lo)), hi - 0.01 * (hi - lo))
        else:
            mid = 0.5 * (lo + hi)
        m_mid = m(mid)
        if m_mid is not None and m_mid >= 0:
            hi, m_hi = mid, m_mid
            if side == 1 and m_lo is not None:
                m_lo /= 2  # Illinois: the end kept twice is halved
            side = 1
        else:
            lo, m_lo = mid, m_mid
            if side == -1:
                m_hi /= 2
            side = -1
    r = math.ceil(hi * 10.0 - 1e-9) / 10.0
    m_r = m(r)
    return r if m_r is not None and m_r >= 0 else hi


def base_radius_advice(cam, radius_mm: float) -> str:
    """``cam.base_radius >= R mm``, with the moved pivot a barrel's oscillating roller needs at that radius."""
    pivot = ""
    if moves_pivot(cam):
        pivot = f" with follower.pivot_distance = {cam.follower.pivot_distance + radius_mm - cam.base_radius:g} mm"
    return f"cam.base_radius >= {radius_mm:g} mm{pivot}"
