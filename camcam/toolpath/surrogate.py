"""A fast stand-in for an exact cam curve while the fitter marches: Chebyshev series per analytic piece.

The fitter evaluates its curve thousands of times at single parameters; a cam
curve built from Taylor jets costs ~0.5 ms a call.  Between two breaks the
curve is analytic (or, inside a piecewise law such as the modified sine, smooth up to
a jump of a high derivative), so a Chebyshev interpolant of x(t) and y(t) of
degree 32 is tried, and an interval where it is not within ``accuracy_mm`` of
the exact curve at points between the nodes is halved (measured, and the
worst kept as ``error_mm``).  Only the fitting runs on it: the printed program is
measured against the exact curve afterwards.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import Chebyshev

__all__ = ["ChebyshevCurve", "chebyshev_curve"]


@dataclass(frozen=True)
class ChebyshevCurve:
    """Piecewise Chebyshev copy of a curve: same parameter, breaks and ends."""

    breaks: np.ndarray
    knots: np.ndarray  # sub-interval ends (the breaks among them)
    series: tuple  # per sub-interval: ((x, x′, x″, x‴), (y, …)) Chebyshev objects
    error_mm: float
    closed: bool

    @property
    def t_start(self) -> float:
        return float(self.breaks[0])

    @property
    def t_end(self) -> float:
        return float(self.breaks[-1])

    def evaluate(self, t, order: int = 0) -> np.ndarray:
        if not 0 <= order <= 3:
            raise ValueError(f"order must be 0..3, got {order!r}")
        t = np.atleast_1d(np.asarray(t, float))
        idx = np.clip(np.searchsorted(self.knots, t, side="right") - 1, 0, len(self.series) - 1)
        out = np.empty((t.size, 2))
        for k in np.unique(idx):
            m = idx == k
            sx, sy = self.series[k]
            out[m, 0] = sx[order](t[m])
            out[m, 1] = sy[order](t[m])
        return out


DEGREE = 32


def _piece(curve, lo: float, hi: float, accuracy_mm: float, depth: int, out: list) -> float:
    """Append (lo, hi, series) sub-intervals covering [lo, hi]; return their worst error."""
    n = DEGREE
    k = np.arange(n + 1)
    nodes = 0.5 * (lo + hi) + 0.5 * (hi - lo) * np.cos(np.pi * (k + 0.5) / (n + 1))
    vals = curve.evaluate(nodes, 0)
    sx = Chebyshev.fit(nodes, vals[:, 0], n, domain=[lo, hi])
    sy = Chebyshev.fit(nodes, vals[:, 1], n, domain=[lo, hi])
    check = np.linspace(lo, hi, 4 * n + 3)
    exact = curve.evaluate(check, 0)
    err = float(np.hypot(sx(check) - exact[:, 0], sy(check) - exact[:, 1]).max())
    if err <= accuracy_mm or depth >= 12:
        derivs = lambda s: (s, s.deriv(1), s.deriv(2), s.deriv(3))  # noqa: E731
        out.append((lo, hi, (derivs(sx), derivs(sy))))
        return err
    mid = 0.5 * (lo + hi)
    return max(_piece(curve, lo, mid, accuracy_mm, depth + 1, out), _piece(curve, mid, hi, accuracy_mm, depth + 1, out))


def chebyshev_curve(curve, accuracy_mm: float = 1e-7) -> ChebyshevCurve:
    """The Chebyshev copy of ``curve`` (any planar curve with ``breaks``).

    Examples
    --------
    >>> from camcam.geometry.curve import FunctionCurve
    >>> def circ(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return 3.0 * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], axis=-1)
    >>> C = chebyshev_curve(FunctionCurve(circ, 0.0, 2 * np.pi, closed=True))
    >>> C.error_mm < 1e-7, bool(abs(C.evaluate([1.0], 2)[0, 0] + 3 * np.cos(1.0)) < 1e-6)
    (True, True)
    """
    br = np.asarray(curve.breaks, float)
    parts: list = []
    worst = 0.0
    for lo, hi in zip(br, br[1:]):
        worst = max(worst, _piece(curve, float(lo), float(hi), accuracy_mm, 0, parts))
    knots = np.array([p[0] for p in parts] + [parts[-1][1]])
    return ChebyshevCurve(br, knots, tuple(p[2] for p in parts), worst, bool(curve.closed))
