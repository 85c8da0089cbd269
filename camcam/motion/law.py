"""The motion-law interface and its exact piecewise implementation.

A *motion law* is a dimensionless displacement S(T) over T ∈ [0, 1] with its
derivatives V = dS/dT, A = d²S/dT², J = d³S/dT³.  A *rise law* has S(0) = 0 and
S(1) = 1 and is used from rest to rest (dwell before and after); fitted lift
tables and B-spline laws implement the same interface.

Characteristic values are extremes over the whole law, computed exactly:
stationary points of each piece in closed form (see :mod:`camcam.motion.piece`)
plus the values at the piece ends.  A jump of a derivative at a piece boundary
(or, for a rest-to-rest law, against rest at T = 0 or 1) makes the next
derivative infinite there; it is reported as ``±inf``, never as a large number.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from dataclasses import dataclass, field

import numpy as np

from camcam.motion.piece import TrigPoly

__all__ = ["Extreme", "Characteristics", "MotionLaw", "PiecewiseLaw", "JUMP_ATOL"]

#: Absolute size below which a derivative's change across a piece boundary is
#: rounding, not a jump.  Dimensionless values are O(1)…O(100); the piece
#: formulas are exact to ~1e-13, so 1e-9 separates noise from real jumps by 4
#: orders of magnitude either way.
JUMP_ATOL = 1e-9


@dataclass(frozen=True)
class Extreme:
    """An extreme value of one derivative and the dimensionless time where it occurs."""

    value: float
    T: float


@dataclass(frozen=True, kw_only=True)
class Characteristics:
    """Extremes of V, A, J over T ∈ [0, 1].

    ``Vm``, ``Am``, ``Jm`` are the largest absolute values; ``Jmax``/``Jmin``
    (and the others) keep their sign.  Infinite values mean a jump of the
    derivative below.
    """

    Vmax: Extreme
    Vmin: Extreme
    Amax: Extreme
    Amin: Extreme
    Jmax: Extreme
    Jmin: Extreme

    @property
    def Vm(self) -> float:
        return max(abs(self.Vmax.value), abs(self.Vmin.value))

    @property
    def Am(self) -> float:
        return max(abs(self.Amax.value), abs(self.Amin.value))

    @property
    def Jm(self) -> float:
        return max(abs(self.Jmax.value), abs(self.Jmin.value))

    def as_dict(self) -> dict[str, float]:
        """The values `camcam laws --json` prints."""
        return {
            "Vm": self.Vm,
            "Am": self.Am,
            "Amax": self.Amax.value,
            "Amin": self.Amin.value,
            "Jm": self.Jm,
            "Jmax": self.Jmax.value,
            "Jmin": self.Jmin.value,
        }


class MotionLaw(ABC):
    """Dimensionless motion law S(T), T ∈ [0, 1].

    Subclasses implement :meth:`evaluate` and :meth:`extreme`.  ``name`` is the
    spec name; ``rest_to_rest`` says whether the law is meant to start and end
    at rest, so that a non-zero V or A at its ends counts as a jump.
    """

    name: str
    rest_to_rest: bool

    @abstractmethod
    def evaluate(self, T, order: int = 0) -> np.ndarray:
        """Derivative ``order`` (0 = S, 1 = V, 2 = A, 3 = J) at T (array-like, in [0, 1])."""

    @abstractmethod
    def extreme(self, order: int, rest_ends: bool | None = None) -> tuple[Extreme, Extreme]:
        """(minimum, maximum) of derivative ``order`` over [0, 1], exact.

        ``rest_ends`` (default: ``rest_to_rest``) counts a non-zero V or A at
        T = 0 or 1 as a jump from or to rest.  A motion program passes False:
        it judges its joins itself.
        """

    def evaluate_orders(self, T, orders) -> list[np.ndarray]:
        """:meth:`evaluate` of each of ``orders`` at T, the same values (a law may share work between them)."""
        return [self.evaluate(T, k) for k in orders]

    def as_piecewise(self) -> "PiecewiseLaw | None":
        """The law as :class:`TrigPoly` pieces (itself or the pieces it evaluates with), or None when it is
        made otherwise: a program of piecewise laws evaluates them from one table
        (:mod:`camcam.motion.piece_table`)."""
        return None

    def svaj(self, T) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """S, V, A, J at T."""
        return tuple(self.evaluate(T, k) for k in range(4))  # type: ignore[return-value]

    def characteristics(self) -> Characteristics:
        vmin, vmax = self.extreme(1)
        amin, amax = self.extreme(2)
        jmin, jmax = self.extreme(3)
        return Characteristics(Vmax=vmax, Vmin=vmin, Amax=amax, Amin=amin, Jmax=jmax, Jmin=jmin)

    def end_values(self) -> tuple[np.ndarray, np.ndarray]:
        """(S, V, A, J) at T = 0 and at T = 1, for continuity checks between segments."""
        return (
            np.array([float(self.evaluate(0.0, k)) for k in range(4)]),
            np.array([float(self.evaluate(1.0, k)) for k in range(4)]),
        )


def _coefficient_table(pieces) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Padded polynomial coefficients (n, degree+1) and sinusoid a, b, ω (n,) of TrigPoly pieces."""
    deg = max(len(p.poly) for p in pieces)
    coef = np.zeros((len(pieces), deg))
    for i, p in enumerate(pieces):
        coef[i, : len(p.poly)] = p.poly
    a = np.array([p.a for p in pieces])
    b = np.array([p.b for p in pieces])
    w = np.array([p.omega if p.has_trig else 0.0 for p in pieces])
    return coef, a, b, w


def check_T(T) -> np.ndarray:
    """``T`` as an array, refused (ValueError naming the value) outside [0, 1] or NaN."""
    T = np.asarray(T, dtype=float)
    if T.size and (np.nanmin(T) < -1e-12 or np.nanmax(T) > 1 + 1e-12 or np.isnan(T).any()):
        bad = T[(T < -1e-12) | (T > 1 + 1e-12) | np.isnan(T)].flat[0]
        raise ValueError(f"T must lie in [0, 1], got {bad!r}")
    return T


@dataclass(frozen=True, eq=False)
class PiecewiseLaw(MotionLaw):
    """A law made of :class:`TrigPoly` pieces of S on ``breaks``.

    Parameters
    ----------
    name : str
        Spec name.
    breaks : tuple of float
        Increasing piece boundaries from 0 to 1.
    pieces : tuple of TrigPoly
        S on each interval, in the local variable u = T − breaks[i].
    rest_to_rest : bool
        See :class:`MotionLaw`.

    Examples
    --------
    >>> law = PiecewiseLaw("ramp", (0.0, 1.0), (TrigPoly((0.0, 0.0, 3.0, -2.0)),))
    >>> float(law.evaluate(0.5)), float(law.evaluate(0.5, 1))
    (0.5, 1.5)
    """

    name: str
    breaks: tuple[float, ...]
    pieces: tuple[TrigPoly, ...]
    rest_to_rest: bool = True
    _derivs: tuple = field(init=False, repr=False)
    _tables: tuple = field(init=False, repr=False)

    def __post_init__(self) -> None:
        b = np.asarray(self.breaks, dtype=float)
        if len(b) != len(self.pieces) + 1 or b[0] != 0.0 or b[-1] != 1.0 or np.any(np.diff(b) <= 0):
            raise ValueError(f"breaks must rise from 0 to 1 with one more entry than pieces, got {self.breaks!r}")
        derivs = [tuple(self.pieces)]
        for _ in range(4):  # each order from the previous one (the same steps as p.derivative(k))
            derivs.append(tuple(p.derivative() for p in derivs[-1]))
        derivs = tuple(derivs)
        object.__setattr__(self, "_derivs", derivs)
        object.__setattr__(self, "_tables", tuple(_coefficient_table(fs) for fs in derivs))

    @property
    def tables(self) -> tuple:
        """Per derivative order 0…4 the pieces' padded polynomial coefficients (pieces, degree + 1) and
        sinusoid a, b, ω (pieces,): what :meth:`evaluate` computes with."""
        return self._tables

    def as_piecewise(self) -> "PiecewiseLaw":
        return self

    def _index(self, T: np.ndarray) -> np.ndarray:
        idx = np.searchsorted(self.breaks, T, side="right") - 1
        return np.clip(idx, 0, len(self.pieces) - 1)

    def evaluate(self, T, order: int = 0) -> np.ndarray:
        if not 0 <= order <= 4:
            raise ValueError(f"order must be 0..4, got {order!r}")
        return self.evaluate_orders(T, (order,))[0]

    def evaluate_orders(self, T, orders) -> list[np.ndarray]:
        """:meth:`evaluate` of each of ``orders`` at T: the pieces located, and the sinusoid's sine and
        cosine taken, once for all of them (the same values, bit for bit, as one order at a time)."""
        if not all(0 <= k <= 4 for k in orders):
            raise ValueError(f"order must be 0..4, got {tuple(orders)!r}")
        T = check_T(T)
        idx = self._index(T)
        u = T - np.asarray(self.breaks)[idx]
        outs, trig = [], None  # trig: (ω table, sin ωu, cos ωu) of the last order that had a sinusoid
        for order in orders:
            coef, a, b, w = self._tables[order]
            c = coef[idx]  # all pieces at once: a table with hundreds of pieces costs one gather
            out = c[..., -1]
            for j in range(coef.shape[1] - 2, -1, -1):
                out = out * u + c[..., j]
            if w.any():
                if trig is None or not np.array_equal(trig[0], w):
                    wu = w[idx] * u
                    trig = (w, np.sin(wu), np.cos(wu))
                out = out + a[idx] * trig[1] + b[idx] * trig[2]
            outs.append(out)
        return outs

    def one_sided(self, order: int, rest_ends: bool) -> tuple[np.ndarray, np.ndarray]:
        """Values of derivative ``order`` just left and just right of every break.

        ``left[i]``/``right[i]`` belong to ``breaks[i]``; ``left[0]`` and
        ``right[-1]`` are the rest values (0 for V, A, J) with ``rest_ends``,
        else the law's own end values.
        """
        fs = self._derivs[order]
        n = len(self.pieces)
        left = np.empty(n + 1)
        right = np.empty(n + 1)
        for i in range(n):
            right[i] = fs[i](0.0)
            left[i + 1] = fs[i](self.breaks[i + 1] - self.breaks[i])
        if rest_ends and order >= 1:
            left[0] = 0.0
            right[n] = 0.0
        else:
            left[0] = right[0]
            right[n] = left[n]
        return left, right

    def extreme(self, order: int, rest_ends: bool | None = None) -> tuple[Extreme, Extreme]:
        rest_ends = self.rest_to_rest if rest_ends is None else rest_ends
        if not 0 <= order <= 3:
            raise ValueError(f"order must be 0..3, got {order!r}")
        cands: list[tuple[float, float]] = []
        fs = self._derivs[order]
        for i, f in enumerate(fs):
            t0, t1 = self.breaks[i], self.breaks[i + 1]
            for u in (0.0, t1 - t0, *self.pieces[i].derivative(order).stationary_points(t1 - t0)):
                cands.append((float(f(u)), t0 + u))
        # Jumps of lower derivatives make this one infinite at the break.
        for lower in range(order):
            left, right = self.one_sided(lower, rest_ends)
            for i, t in enumerate(self.breaks):
                jump = right[i] - left[i]
                if abs(jump) > JUMP_ATOL * max(1.0, abs(left[i]), abs(right[i])):
                    if lower == order - 1:
                        cands.append((math.copysign(math.inf, jump), t))
                    else:  # a jump two or more orders down: an impulse doublet
                        cands += [(math.inf, t), (-math.inf, t)]
        lo = min(cands, key=lambda c: (c[0], c[1]))
        hi = max(cands, key=lambda c: (c[0], -c[1]))
        return Extreme(lo[0], lo[1]), Extreme(hi[0], hi[1])
