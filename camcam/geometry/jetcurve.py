"""Curves of the cam angle built from jets: the motion program as a jet, and
planar / space curves whose ``evaluate(t, order)`` reads the jet's derivative.

Every cam curve here is parameterised by the program cam angle θ (radians,
0…2π), closed, with ``breaks`` at the motion segment boundaries.  A curve can
also be evaluated on one analytic piece (``piece=i``) so that analyses see the
one-sided values at a segment boundary where an acceleration jumps.
"""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass
from typing import Callable

import numpy as np

from camcam.geometry.jet import MAX_ORDER, Jet
from camcam.motion.program import MotionProgram

__all__ = ["LiftJet", "JetCurve", "SpaceCurve", "program_breaks", "program_inner_breaks"]


def program_breaks(program: MotionProgram) -> np.ndarray:
    """Segment boundaries in radians, 0 and 2π included."""
    edges = [0.0] + [math.radians(s.end_deg) for s in program.segments[:-1]] + [2 * math.pi]
    return np.array(edges)


def program_inner_breaks(program: MotionProgram) -> tuple[np.ndarray, ...]:
    """Per segment, the angles (rad) inside it where its law changes piece: a derivative of the lift may jump
    there (the parabolic law's acceleration at mid-rise), so a quantity of the cam built on it may too.

    Examples
    --------
    >>> from camcam.motion.catalog import make_law
    >>> from camcam.motion.program import MotionProgram, Segment
    >>> p = MotionProgram((Segment(make_law("parabolic"), 0, 90, 10.0), Segment(make_law("cycloidal"), 90, 360,
    ...                    -10.0, base=10.0)), rpm=60)
    >>> [np.degrees(a).round(9).tolist() for a in program_inner_breaks(p)]
    [[45.0], []]
    """
    out = []
    for s in program.segments:
        law = s.law.as_piecewise()
        inner = np.asarray(law.breaks[1:-1], float) if law is not None else np.empty(0)
        out.append(np.radians(s.start_deg + inner * (s.end_deg - s.start_deg)))
    return tuple(out)


@dataclass(frozen=True)
class LiftJet:
    """The follower displacement as a jet: ``scale·(s(θ) − shift)``.

    ``scale`` = 1 keeps mm; ``math.pi/180`` turns an oscillating program's
    degrees into radians.  ``piece`` evaluates segment ``piece``'s law at
    (θ − start)/span without wrapping or clipping (one-sided at its ends).
    """

    program: MotionProgram
    scale: float = 1.0
    shift: float = 0.0

    def __call__(self, theta, K: int, piece: int | None = None) -> Jet:
        if K > MAX_ORDER:
            raise ValueError(f"the motion program gives lift derivatives up to order {MAX_ORDER}, asked {K}")
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        if piece is None:
            rows = list(self.program.lifts(theta, K))
        else:
            seg = self.program.segments[piece]
            T = (np.degrees(theta) - seg.start_deg) / (seg.end_deg - seg.start_deg)
            rows = seg.lifts(T, range(K + 1))
        rows[0] = rows[0] - self.shift
        return Jet(np.array(rows) * self.scale)


JetFunc = Callable[[np.ndarray, int, "int | None"], tuple[Jet, ...]]


@dataclass(frozen=True)
class JetCurve:
    """A closed :class:`~camcam.geometry.curve.PlanarCurve` of the cam angle from a jet function.

    ``func(theta, K, piece)`` returns the (x, y) jets of order ≥ K.  ``inner`` (rad, ascending) are the angles
    inside the pieces where a law changes piece (:func:`program_inner_breaks`): where a curve's direction is
    built on the acceleration (a tilting roller's flank), it may turn by a corner there, and an offset of it
    jump; :func:`camcam.toolpath.surrogate.chebyshev_curve` splits its copy at them.
    """

    func: JetFunc
    breaks: np.ndarray
    _: KW_ONLY
    t_start: float = 0.0
    t_end: float = 2 * math.pi
    closed: bool = True
    inner: tuple | np.ndarray = ()

    def jets(self, t, K: int, piece: int | None = None) -> tuple[Jet, ...]:
        return self.func(np.atleast_1d(np.asarray(t, dtype=float)), K, piece)

    def evaluate(self, t, order: int = 0, piece: int | None = None) -> np.ndarray:
        if not 0 <= order <= 3:
            raise ValueError(f"order must be 0..3, got {order!r}")
        return np.stack([j.d[order] for j in self.jets(t, order, piece)], axis=-1)

    def polyline(self, per_piece: int = 200) -> np.ndarray:
        """A dense view: points at ``per_piece`` parameters per analytic piece, ends once."""
        ts = np.concatenate([np.linspace(a, b, per_piece, endpoint=False) for a, b in zip(self.breaks, self.breaks[1:])])
        return self.evaluate(ts)


@dataclass(frozen=True)
class SpaceCurve(JetCurve):
    """A closed 3-D curve of the cam angle: the same jets, three of them; ``evaluate`` → (n, 3)."""
