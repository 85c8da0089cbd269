"""Test curves with exact derivatives (the cam geometry stage is built elsewhere)."""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.curve import FunctionCurve
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.motion.standard import dwell


def ellipse(a=30.0, b=20.0, quarter_breaks=True):
    def f(t, order):
        c, s = np.cos(t), np.sin(t)
        rows = [(a * c, b * s), (-a * s, b * c), (-a * c, -b * s), (a * s, -b * c)][order]
        return np.stack(rows, axis=-1)

    br = (math.pi / 2, math.pi, 1.5 * math.pi) if quarter_breaks else ()
    return FunctionCurve(f, 0.0, 2 * math.pi, closed=True, breaks_=br)


def demo_program() -> MotionProgram:
    """The demo spec's motion: modified sine rise 20 mm, dwell, cycloidal return, dwell."""
    return MotionProgram((
        Segment(make_law("modified-sine"), 0, 120, 20.0),
        Segment(dwell(), 120, 180, 0.0, base=20.0),
        Segment(make_law("cycloidal"), 180, 300, -20.0, base=20.0),
        Segment(dwell(), 300, 360, 0.0, base=0.0),
    ), rpm=120)


def polar_cam(program: MotionProgram | None = None, base_mm: float = 40.0):
    """Closed curve r(θ) = R + s(θ), exact derivatives from ``program.lift(θ, k)``; breaks at the joins."""
    program = program or demo_program()

    def f(t, order):
        r = [base_mm + program.lift(t, 0)] + [program.lift(t, k) if k <= order else None for k in (1, 2, 3)]
        u = np.stack([np.cos(t), np.sin(t)], axis=-1)
        w = np.stack([-np.sin(t), np.cos(t)], axis=-1)
        a, b = [  # P^(k) = a·u + b·w
            lambda: (r[0], 0 * r[0]),
            lambda: (r[1], r[0]),
            lambda: (r[2] - r[0], 2 * r[1]),
            lambda: (r[3] - 3 * r[1], 3 * r[2] - r[0]),
        ][order]()
        return a[:, None] * u + b[:, None] * w

    joins = tuple(math.radians(s.end_deg) for s in program.segments[:-1])
    return FunctionCurve(f, 0.0, 2 * math.pi, closed=True, breaks_=joins)


def wavy(amplitude=3.0, length=60.0):
    """Open curve y = A sin(2πx/L) over two periods (curvature changes sign), breaks where κ′ jumps.

    The second half is a mirrored cubic blend, so dκ/ds jumps at x = L.
    """
    k = 2 * math.pi / length

    def f(t, order):
        x = t
        y = [amplitude * np.sin(k * x), amplitude * k * np.cos(k * x),
             -amplitude * k**2 * np.sin(k * x), -amplitude * k**3 * np.cos(k * x)][order]
        # beyond x = L add a cubic term: y += c (x − L)^3  (C² join, κ′ jumps)
        c = 1e-4
        d = np.maximum(x - length, 0.0)
        y = y + [c * d**3, 3 * c * d**2, 6 * c * d, 6 * c * (x > length)][order]
        xx = [x, np.ones_like(x), np.zeros_like(x), np.zeros_like(x)][order]
        return np.stack([xx, y], axis=-1)

    return FunctionCurve(f, 0.0, 2 * length, closed=False, breaks_=(length,))


def developed_groove(program: MotionProgram | None = None, radius_mm: float = 30.0):
    """Cylindrical-cam groove centre developed at ``radius_mm``: x = s(θ) along the axis, y = R·θ."""
    program = program or demo_program()

    def f(t, order):
        x = program.lift(t, order)
        y = [radius_mm * t, radius_mm + 0 * t, 0 * t, 0 * t][order]
        return np.stack([x, y], axis=-1)

    joins = tuple(math.radians(s.end_deg) for s in program.segments[:-1])
    return FunctionCurve(f, 0.0, 2 * math.pi, closed=False, breaks_=joins)
