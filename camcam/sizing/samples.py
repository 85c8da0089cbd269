"""One motion program, evaluated once on the cam-angle grid the whole sweep shares.

Each segment is sampled on its own closed interval, so a segment boundary
appears twice, once with each side's one-sided derivatives (an acceleration
jump at a join is seen from both sides, as the exact analysis sees it).  The
lift's extremes are root-found, not read off the grid: the translating
roller's outer radius is a closed form in the largest lift.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from camcam.motion.program import MotionProgram

__all__ = ["ProgramSamples", "sample_program"]


@dataclass(frozen=True, kw_only=True)
class ProgramSamples:
    """s, s′, s″ (per radian of cam angle) at the grid angles; radians of swing for an oscillating program.

    ``inner`` marks the samples whose two neighbours lie in the same segment
    (where a second difference estimates s‴-smooth curvature of a figure).
    """

    theta: np.ndarray
    s: np.ndarray
    s1: np.ndarray
    s2: np.ndarray
    inner: np.ndarray
    lift_max: float
    lift_min: float
    step_rad: float


def _refine(seg, T0: float, T1: float, sign: float) -> float:
    """max of sign·s on segment ``seg`` between T0 and T1 (bounded Brent, 1e-12 in T)."""
    f = lambda T: -sign * float(seg.derivative(np.array([T]), 0)[0] + seg.base)  # noqa: E731
    r = minimize_scalar(f, bounds=(T0, T1), method="bounded", options={"xatol": 1e-12})
    return max(-r.fun, -f(T0), -f(T1))


def sample_program(program: MotionProgram, samples_per_rev: int) -> ProgramSamples:
    """Sample ``program`` with about ``samples_per_rev`` points per revolution (at least 3 a segment).

    Examples
    --------
    >>> from camcam.motion.catalog import make_law
    >>> from camcam.motion.program import MotionProgram, Segment
    >>> p = MotionProgram((Segment(make_law("cycloidal"), 0, 180, 10.0),
    ...                    Segment(make_law("cycloidal"), 180, 360, -10.0, base=10.0)), rpm=60)
    >>> ps = sample_program(p, 360)
    >>> ps.theta.size, round(ps.lift_max, 12), round(ps.step_rad, 6)
    (362, 10.0, 0.017453)
    """
    scale = math.pi / 180.0 if program.unit == "deg" else 1.0
    thetas, rows, inner = [], [], []
    best_hi, best_lo = -math.inf, math.inf
    for seg in program.segments:
        n = max(3, int(math.ceil((seg.end_deg - seg.start_deg) / 360.0 * samples_per_rev)) + 1)
        T = np.linspace(0.0, 1.0, n)
        s = seg.derivative(T, 0) + seg.base
        rows.append(np.stack([s, seg.derivative(T, 1), seg.derivative(T, 2)]))
        thetas.append(np.radians(seg.start_deg + T * (seg.end_deg - seg.start_deg)))
        m = np.ones(n, bool)
        m[0] = m[-1] = False
        inner.append(m)
        for sign in (1.0, -1.0):
            i = int(np.argmax(sign * s))
            v = _refine(seg, T[max(i - 1, 0)], T[min(i + 1, n - 1)], sign)
            if sign > 0:
                best_hi = max(best_hi, v)
            else:
                best_lo = min(best_lo, -v)
    data = np.concatenate(rows, axis=1) * scale
    step = 2 * math.pi / samples_per_rev
    return ProgramSamples(theta=np.concatenate(thetas), s=data[0], s1=data[1], s2=data[2], inner=np.concatenate(inner),
                          lift_max=float(best_hi * scale), lift_min=float(best_lo * scale), step_rad=step)
