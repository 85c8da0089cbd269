"""The textbook rise laws, built exactly.

Polynomial laws are written down as S(T).  Laws defined by the shape of their
acceleration (modified trapezoid, modified sine, modified constant velocity,
parabolic) are integrated twice exactly, piece by piece, and scaled so that
S(1) = 1; no constant is copied from a table.  References for the shapes:
H. A. Rothbart, *Cam Design Handbook* (2004), ch. 3; R. L. Norton, *Cam Design
and Manufacturing Handbook* (2009), ch. 3; S. Makino, *カム機構* (MCV 50 curve).
"""

from __future__ import annotations

import math

import numpy as np

from camcam.motion.law import PiecewiseLaw
from camcam.motion.piece import TrigPoly

__all__ = [
    "dwell",
    "cycloidal",
    "harmonic",
    "polynomial_345",
    "polynomial_4567",
    "modified_trapezoid",
    "modified_sine",
    "modified_constant_velocity",
    "parabolic",
    "yu_lee",
    "from_acceleration",
]

PI = math.pi


def from_acceleration(name: str, breaks, accel: list[TrigPoly]) -> PiecewiseLaw:
    """Integrate a piecewise acceleration shape from rest and scale it to S(1) = 1.

    Parameters
    ----------
    name : str
        Spec name of the law.
    breaks : sequence of float
        Piece boundaries, 0 … 1.
    accel : list of TrigPoly
        Acceleration on each piece in the local variable u = T − breaks[i]
        (any amplitude: the result is scaled).

    Examples
    --------
    >>> law = from_acceleration("parabolic", (0, 0.5, 1), [TrigPoly((1.0,)), TrigPoly((-1.0,))])
    >>> float(law.evaluate(1.0)), float(law.evaluate(0.25, 2))
    (1.0, 4.0)
    """
    breaks = tuple(float(b) for b in breaks)
    pieces = []
    v0 = s0 = 0.0
    for i, a in enumerate(accel):
        length = breaks[i + 1] - breaks[i]
        v = a.integral(v0)
        s = v.integral(s0)
        pieces.append(s)
        v0, s0 = float(v(length)), float(s(length))
    if abs(v0) > 1e-12 * max(1.0, abs(s0)):
        raise ValueError(f"{name}: acceleration shape does not end at rest (V(1) = {v0!r})")
    scale = 1.0 / s0
    return PiecewiseLaw(name, breaks, tuple(p.scaled(scale) for p in pieces))


def dwell() -> PiecewiseLaw:
    """No motion: S ≡ 0 (used with rise 0)."""
    return PiecewiseLaw("dwell", (0.0, 1.0), (TrigPoly((0.0,)),))


def cycloidal() -> PiecewiseLaw:
    """S = T − sin(2πT)/(2π)."""
    return PiecewiseLaw("cycloidal", (0.0, 1.0), (TrigPoly((0.0, 1.0), a=-1 / (2 * PI), omega=2 * PI),))


def harmonic() -> PiecewiseLaw:
    """Simple harmonic: S = (1 − cos πT)/2.  A ≠ 0 at both ends: infinite jerk from rest."""
    return PiecewiseLaw("harmonic", (0.0, 1.0), (TrigPoly((0.5,), b=-0.5, omega=PI),))


def polynomial_345() -> PiecewiseLaw:
    """S = 10T³ − 15T⁴ + 6T⁵."""
    return PiecewiseLaw("polynomial-345", (0.0, 1.0), (TrigPoly((0, 0, 0, 10, -15, 6)),))


def polynomial_4567() -> PiecewiseLaw:
    """S = 35T⁴ − 84T⁵ + 70T⁶ − 20T⁷."""
    return PiecewiseLaw("polynomial-4567", (0.0, 1.0), (TrigPoly((0, 0, 0, 0, 35, -84, 70, -20)),))


def modified_trapezoid() -> PiecewiseLaw:
    """Modified trapezoid (1/8 proportions): sine ramps of A between constant plateaus."""
    w = 4 * PI  # a quarter sine wave over 1/8
    return from_acceleration(
        "modified-trapezoid",
        (0, 1 / 8, 3 / 8, 5 / 8, 7 / 8, 1),
        [
            TrigPoly(a=1.0, omega=w),
            TrigPoly((1.0,)),
            TrigPoly(b=1.0, omega=w),  # cos from +1 to −1 over 1/4
            TrigPoly((-1.0,)),
            TrigPoly(b=-1.0, omega=w),  # −cos from −1 to 0 over 1/8
        ],
    )


def modified_sine() -> PiecewiseLaw:
    """Modified sine: quarter waves of period 1/2 at the ends, a 3/2-period half wave between."""
    return from_acceleration(
        "modified-sine",
        (0, 1 / 8, 7 / 8, 1),
        [
            TrigPoly(a=1.0, omega=4 * PI),
            TrigPoly(b=1.0, omega=4 * PI / 3),  # cos from +1 to −1 over 3/4
            TrigPoly(b=-1.0, omega=4 * PI),
        ],
    )


def modified_constant_velocity() -> PiecewiseLaw:
    """Modified constant velocity (MCV 50): modified-sine acceleration over the first
    quarter, constant velocity over the middle half, modified-sine deceleration."""
    return from_acceleration(
        "modified-constant-velocity",
        (0, 1 / 16, 1 / 4, 3 / 4, 15 / 16, 1),
        [
            TrigPoly(a=1.0, omega=8 * PI),  # 0 → 1 over 1/16
            TrigPoly(b=1.0, omega=8 * PI / 3),  # 1 → 0 over 3/16
            TrigPoly((0.0,)),
            TrigPoly(a=-1.0, omega=8 * PI / 3),  # 0 → −1 over 3/16
            TrigPoly(b=-1.0, omega=8 * PI),  # −1 → 0 over 1/16
        ],
    )


def parabolic() -> PiecewiseLaw:
    """Constant acceleration then constant deceleration: A = ±4, jumps at T = 0, ½, 1."""
    return from_acceleration("parabolic", (0, 0.5, 1), [TrigPoly((1.0,)), TrigPoly((-1.0,))])


def yu_lee(beta7: float = 0.65, beta9: float = -0.665, beta11: float = 1.33) -> PiecewiseLaw:
    """Yu and Lee's parameterised polynomial family (seed 000, eq. 9).

    y = y7 + y9 + y11 with the seed's betas as defaults (β7 = 0.65, β9 = −0.665,
    β11 = 1.33).  Every member has S(0) = 0, S(1) = 1 and V, A = 0 at both ends.
    """
    y7 = np.array([0, 0, 0, 20, -65, 96, -70, 20], dtype=float)
    y7[:8] -= beta7 * np.array([0, 0, 0, 10, -50, 90, -70, 20])
    y9 = -beta9 * np.array([0, 0, 0, 0, 35, -210, 490, -560, 315, -70])
    y11 = -beta11 * np.array([0, 0, 0, 0, 0, 126, -882, 2520, -3780, 3150, -1386, 252])
    coef = np.zeros(12)
    coef[:8] += y7
    coef[:10] += y9
    coef += y11
    return PiecewiseLaw("yu-lee", (0.0, 1.0), (TrigPoly(tuple(coef)),))
