"""Cubic B-splines interpolating the exact cam curves and surfaces within a stated deviation.

A CAD solid (the STEP file, :mod:`camcam.export.step`) needs the cam's profile, flanks and
groove walls as B-splines.  Each analytic piece of an exact curve (between two of its
``breaks``, where a second derivative may jump) gets its own clamped cubic B-spline,
parameterised by the cam angle θ itself and interpolating the exact points at evenly spaced
nodes with the exact one-sided end derivatives, so that neighbouring pieces meet in the
same point and tangent.  Because the spline's parameter is the curve's, |B(θ) − P(θ)| bounds
the distance of each spline point from the exact curve; it is measured at
:data:`CHECK_PER_SPAN` parameters in every span and the nodes are doubled until it is below
the target.  A groove wall, an exact surface of (θ, ρ), is interpolated the same way
(tensor product; ρ the roller cross-section's radius).

Examples
--------
>>> import numpy as np
>>> from camcam.geometry.curve import FunctionCurve
>>> def circle(t, order):
...     c, s = 5 * np.cos(t), 5 * np.sin(t)
...     return np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][order], axis=-1)
>>> fit = fit_curve(FunctionCurve(circle, 0.0, 2 * np.pi, closed=True), 1e-4)
>>> len(fit.pieces), fit.deviation_mm < 1e-4
(1, True)
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["SplinePiece", "CurveFit", "fit_curve", "SurfacePiece", "SurfaceFit", "fit_surface", "CHECK_PER_SPAN"]

#: Parameters per knot span at which a fit's deviation from the exact curve is measured.
CHECK_PER_SPAN = 16
#: Nodes per piece to start from, and the most a piece may need.
START_NODES, MAX_NODES = 8, 4096


@dataclass(frozen=True)
class SplinePiece:
    """One clamped cubic B-spline: ``knots`` (with their repeats, scipy's ``t``), ``poles`` (m, d) mm."""

    knots: np.ndarray
    poles: np.ndarray
    degree: int = 3

    def evaluate(self, t) -> np.ndarray:
        from scipy.interpolate import BSpline

        return BSpline(self.knots, self.poles, self.degree)(np.asarray(t, float))


@dataclass(frozen=True)
class CurveFit:
    """A closed curve's pieces, in order, and the largest deviation measured (mm)."""

    pieces: tuple[SplinePiece, ...]
    deviation_mm: float


def _piece_spline(curve, a: float, b: float, n: int, piece: int) -> SplinePiece:
    from scipy.interpolate import make_interp_spline

    t = np.linspace(a, b, n + 1)
    p = curve.evaluate(t, 0, piece) if piece is not None else curve.evaluate(t, 0)
    d = curve.evaluate(np.array([a, b]), 1, piece) if piece is not None else curve.evaluate(np.array([a, b]), 1)
    s = make_interp_spline(t, p, k=3, bc_type=([(1, d[0])], [(1, d[1])]))
    return SplinePiece(np.asarray(s.t), np.asarray(s.c))


def _check_params(knots: np.ndarray) -> np.ndarray:
    u = np.unique(knots)
    return np.concatenate([np.linspace(x, y, CHECK_PER_SPAN, endpoint=False) for x, y in zip(u, u[1:])] + [u[-1:]])


def _evaluate(curve, t, piece):
    return curve.evaluate(t, 0, piece) if piece is not None else curve.evaluate(t, 0)


def _refined(breaks: np.ndarray, make, deviation, tolerance_mm: float, what: str) -> tuple[list, float]:
    """``make(i, a, b, n)``'s spline of each piece i between ``breaks`` with the fewest nodes n (doubling from
    :data:`START_NODES`) whose ``deviation(i, spline)`` is under ``tolerance_mm``, their ends joined, and the
    largest deviation."""
    pieces, worst = [], 0.0
    for i, (a, b) in enumerate(zip(breaks, breaks[1:])):
        n = START_NODES
        while (dev := deviation(i, s := make(i, a, b, n))) >= tolerance_mm:
            if n >= MAX_NODES:
                raise ValueError(f"piece {i} of the {what} deviates {dev:.3g} mm from its B-spline at {n} nodes")
            n *= 2
        pieces.append(s)
        worst = max(worst, dev)
    # one end for two pieces: the values at a break agree to rounding (the curve or surface is continuous)
    for s, nxt in zip(pieces, pieces[1:] + pieces[:1]):
        s.poles[-1] = nxt.poles[0]
    return pieces, worst


def fit_curve(curve, tolerance_mm: float) -> CurveFit:
    """Per-piece cubic B-splines of the closed exact ``curve`` (:class:`~camcam.geometry.curve.PlanarCurve`
    or a space curve) deviating from it by less than ``tolerance_mm`` at every measured parameter.

    Neighbouring pieces share their end point exactly: piece i ends in the point piece i + 1
    starts from, the last ends in the first's start.

    Raises
    ------
    ValueError
        A piece needs more than :data:`MAX_NODES` nodes (the curve is not smooth between its breaks).
    """
    br = np.asarray(curve.breaks, float)
    one_sided = hasattr(curve, "jets")  # a JetCurve evaluates one piece at its ends (one-sided values)
    def make(i, a, b, n):
        return _piece_spline(curve, a, b, n, i if one_sided else None)

    def deviation(i, s):
        u = _check_params(s.knots)
        return float(np.max(np.linalg.norm(s.evaluate(u) - _evaluate(curve, u, i if one_sided else None), axis=1)))

    pieces, worst = _refined(br, make, deviation, tolerance_mm, "curve")
    return CurveFit(tuple(pieces), worst)


@dataclass(frozen=True)
class SurfacePiece:
    """A cubic B-spline surface of (θ, ρ): ``knots_u`` (θ), ``knots_v`` (ρ), ``poles`` (m_u, m_v, 3) mm."""

    knots_u: np.ndarray
    knots_v: np.ndarray
    poles: np.ndarray
    degree: int = 3

    def evaluate(self, u, v) -> np.ndarray:
        """Points (len(u), len(v), 3) on the grid u × v."""
        from scipy.interpolate import BSpline

        along_u = BSpline(self.knots_u, self.poles, self.degree)(np.asarray(u, float))  # (nu, m_v, 3)
        return np.moveaxis(BSpline(self.knots_v, np.moveaxis(along_u, 1, 0), self.degree)(np.asarray(v, float)), 0, 1)


@dataclass(frozen=True)
class SurfaceFit:
    """A closed band's pieces in θ, in order, and the largest deviation measured (mm)."""

    pieces: tuple[SurfacePiece, ...]
    deviation_mm: float


def _surface_piece(point, tangent, a: float, b: float, rho: np.ndarray, n: int) -> SurfacePiece:
    from scipy.interpolate import make_interp_spline

    t = np.linspace(a, b, n + 1)
    grid = point(t, rho)  # (n+1, len(rho), 3)
    ends = tangent(np.array([a, b]), rho)  # (2, len(rho), 3)
    along_u = make_interp_spline(t, grid, k=3, bc_type=([(1, ends[0])], [(1, ends[1])]))
    across = make_interp_spline(rho, np.moveaxis(np.asarray(along_u.c), 1, 0), k=3)
    return SurfacePiece(np.asarray(along_u.t), np.asarray(across.t), np.moveaxis(np.asarray(across.c), 0, 1))


def fit_surface(point, tangent, breaks, rho: np.ndarray, tolerance_mm: float) -> SurfaceFit:
    """Per-piece bicubic B-spline surfaces of an exact surface S(θ, ρ), closed in θ.

    Parameters
    ----------
    point, tangent : callable
        ``point(theta, rho)`` the exact points and ``tangent(theta, rho)`` ∂S/∂θ, each (len(θ), len(ρ), 3);
        both analytic between ``breaks`` (θ, radians, ends included).
    rho : ndarray
        The nodes across the band (increasing; at least four), mm.
    tolerance_mm : float
        The deviation to stay under, measured at :data:`CHECK_PER_SPAN` parameters per span both ways.

    Raises
    ------
    ValueError
        A piece needs more than :data:`MAX_NODES` nodes in θ.
    """
    rho = np.asarray(rho, float)
    def make(i, a, b, n):
        return _surface_piece(point, tangent, a, b, rho, n)

    def deviation(i, s):
        u, v = _check_params(s.knots_u), _check_params(s.knots_v)
        return float(np.max(np.linalg.norm(s.evaluate(u, v) - point(u, v), axis=-1)))

    pieces, worst = _refined(np.asarray(breaks, float), make, deviation, tolerance_mm, "surface")
    return SurfaceFit(tuple(pieces), worst)
