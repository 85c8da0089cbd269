"""Cubic B-splines interpolating the exact cam curves and surfaces within a stated deviation.

A CAD solid (the STEP file, :mod:`camcam.export.step`) needs the cam's profile, flanks and
groove walls as B-splines.  Each analytic piece of an exact curve or surface (between two
of its ``breaks``, where a second derivative may jump) gets its own clamped cubic B-spline,
parameterised by the cam angle θ itself and interpolating the exact points at evenly spaced
nodes with the exact one-sided end derivatives along θ, so that neighbouring pieces meet in
the same points and tangents.  Because the spline's parameter is the exact one, |B(θ) − P(θ)|
bounds the distance of each spline point from the exact curve or surface; it is measured at
:data:`CHECK_PER_SPAN` parameters in every span and the nodes are doubled until it is below
the target (:func:`refined`).  The curves are interpolated by OpenCascade
(:func:`camcam.export.step_solids.fit_curve`, where OCP is imported anyway); a groove wall,
an exact surface of (θ, ρ) with ρ the roller cross-section's radius, here (tensor product,
scipy's ``make_interp_spline``: :func:`fit_surface`).

Examples
--------
>>> check_params(np.array([0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]))[[0, 1, -1]]
array([0.    , 0.0625, 1.    ])
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError

__all__ = ["SurfacePiece", "SurfaceFit", "fit_surface", "refined", "analytic_spans", "end_parameters", "check_params",
           "CHECK_PER_SPAN", "next_nodes"]

#: Parameters per knot span at which a fit's deviation from the exact curve is measured.
CHECK_PER_SPAN = 16
#: Nodes per piece to start from, and the most a piece may need.
START_NODES, MAX_NODES = 8, 4096
#: With a known order of convergence, the deviation a fit's next node count aims at, as a share of the target
#: (:func:`next_nodes`): a margin for the error constant's change between the two counts.
AIM = 0.8
#: Spans shorter than this (radians) are folded into the span before them: OpenCascade cannot interpolate
#: through nodes closer than its 1e-9 mm point tolerance, and a break this close to the next one (two equal
#: break angles one rounding apart) bounds no analytic piece of its own worth the name.
MIN_SPAN_RAD = 1e-9


def check_params(knots: np.ndarray) -> np.ndarray:
    """The parameters a fit is measured at: :data:`CHECK_PER_SPAN` per span of the distinct ``knots``, and the end."""
    u = np.unique(knots)
    return np.concatenate([np.linspace(x, y, CHECK_PER_SPAN, endpoint=False) for x, y in zip(u, u[1:])] + [u[-1:]])


def analytic_spans(breaks, program=None) -> list[tuple[float, float, int | None]]:
    """The spans (a, b, piece) between ``breaks`` (radians, ends included) on which a cam curve is analytic, and
    the index of the motion segment each lies in (``None`` without a ``program``): with the program, each
    segment is split further at its law's own breaks (a parabolic law's acceleration jumps at its middle, a
    modified sine's at 1/8 and 7/8: the profile's second derivative jumps with it)."""
    br = np.asarray(breaks, float)
    spans = []
    for i, (a, b) in enumerate(zip(br, br[1:])):
        inner = () if program is None else getattr(program.segments[i].law, "breaks", ())
        edges = [float(a)] + [a + float(T) * (b - a) for T in inner if 0.0 < T < 1.0] + [float(b)]
        spans += [(x, y, None if program is None else i) for x, y in zip(edges, edges[1:])]
    return _folded(spans)


def _folded(spans: list[tuple[float, float, int | None]]) -> list[tuple[float, float, int | None]]:
    """``spans`` with each shorter than :data:`MIN_SPAN_RAD` joined to the one before it (the first to the one
    after it): the pieces still cover the turn end to end.  Its few 1e-9 rad are evaluated on the neighbour's
    motion segment, whose analytic law runs on past its end by as little.

    Examples
    --------
    >>> _folded([(0.1, 0.1 + 1e-17, None), (0.1 + 1e-17, 3.0, None), (3.0, 6.0, None)])
    [(0.1, 3.0, None), (3.0, 6.0, None)]
    """
    out = []
    for a, b, piece in spans:
        if out and b - a < MIN_SPAN_RAD:
            out[-1] = (out[-1][0], b, out[-1][2])
        elif out and out[-1][1] - out[-1][0] < MIN_SPAN_RAD:
            out[-1] = (out[-1][0], b, piece)
        else:
            out.append((a, b, piece))
    return out


def end_parameters(a: float, b: float) -> np.ndarray:
    """Where a span's end derivatives are taken: a hair inside it, so that they are its own at a law's inner break
    (where the law gives the next piece's); the shift, 1e-10 of the span, moves them by about as little."""
    e = 1e-10 * (b - a)
    return np.array([a + e, b - e])


def next_nodes(n: int, deviation_mm: float, tolerance_mm: float, order: int | None) -> int:
    """The node count to try after ``n`` nodes deviated ``deviation_mm`` (≥ ``tolerance_mm``): twice ``n``, or
    with the interpolant's ``order`` of convergence (the deviation ∝ hᵒʳᵈᵉʳ, h the node spacing) the count
    that brings it to :data:`AIM` × the tolerance, at least 1.25 × ``n`` (a deviation that falls more slowly
    still grows the count fast) and at most 8 × ``n`` (twice ``n`` for a deviation that is not finite); never
    above :data:`MAX_NODES`.

    Examples
    --------
    >>> next_nodes(8, 1e-4, 1e-5, None)
    16
    >>> next_nodes(8, 1e-3, 5e-5, 4)  # 8 · (1e-3 / 4e-5)^¼ = 17.8
    18
    >>> next_nodes(40, 5.1e-5, 5e-5, 4)  # just over: 1.25 × n
    50
    >>> next_nodes(8, float("inf"), 5e-5, 4)
    16
    """
    if order is None or not math.isfinite(deviation_mm):  # no order, or no figure to scale by: doubled
        grown = 2 * n
    else:
        grown = min(8 * n, max(math.ceil(1.25 * n), math.ceil(n * (deviation_mm / (AIM * tolerance_mm)) ** (1 / order))))
    return min(grown, MAX_NODES)


def refined(spans, make, deviation, join, tolerance_mm: float, what: str, order: int | None = None) -> tuple[list, float]:
    """``make(piece, a, b, n)``'s spline of each span (a, b, piece) of ``spans`` (:func:`analytic_spans`) with
    few nodes n (from :data:`START_NODES`, grown by :func:`next_nodes`: doubled, or to the count ``order``
    predicts) whose ``deviation(piece, spline)`` is under ``tolerance_mm``, each span's end made the next
    one's start by ``join(spline, next)`` (the last's the first's), and the largest deviation.

    Raises
    ------
    GeometryError
        A span needs more than :data:`MAX_NODES` nodes (the curve is not smooth on it): the run writes no STEP
        and says so (:func:`camcam.export.step.step_files`).
    """
    pieces, worst = [], 0.0
    for k, (a, b, piece) in enumerate(spans):
        n = START_NODES
        while (dev := deviation(piece, s := make(piece, a, b, n))) >= tolerance_mm:
            if n >= MAX_NODES:
                raise GeometryError(f"span {k} of the {what} deviates {dev:.3g} mm from its B-spline at {n} nodes")
            n = next_nodes(n, dev, tolerance_mm, order)
        pieces.append(s)
        worst = max(worst, dev)
    # one end for two pieces: the values at a break agree to rounding (the curve or surface is continuous)
    for s, nxt in zip(pieces, pieces[1:] + pieces[:1]):
        join(s, nxt)
    return pieces, worst


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


def _surface_piece(point, tangent, a: float, b: float, piece, rho: np.ndarray, n: int) -> SurfacePiece:
    from scipy.interpolate import make_interp_spline

    t = np.linspace(a, b, n + 1)
    grid = point(t, rho)  # (n+1, len(rho), 3)
    ends = tangent(end_parameters(a, b), rho, piece)  # (2, len(rho), 3)
    along_u = make_interp_spline(t, grid, k=3, bc_type=([(1, ends[0])], [(1, ends[1])]))
    across = make_interp_spline(rho, np.moveaxis(np.asarray(along_u.c), 1, 0), k=3)
    return SurfacePiece(np.asarray(along_u.t), np.asarray(across.t), np.moveaxis(np.asarray(across.c), 0, 1))


def fit_surface(point, tangent, spans, rho: np.ndarray, tolerance_mm: float) -> SurfaceFit:
    """Per-piece bicubic B-spline surfaces of an exact surface S(θ, ρ), closed in θ.

    Parameters
    ----------
    point, tangent : callable
        ``point(theta, rho)`` the exact points and ``tangent(theta, rho, piece)`` ∂S/∂θ (on motion segment
        ``piece``), each (len(θ), len(ρ), 3); both analytic on each of ``spans``.
    spans : list
        (a, b, piece) spans in θ (radians) covering one turn (:func:`analytic_spans`).
    rho : ndarray
        The nodes across the band (increasing; at least four), mm.
    tolerance_mm : float
        The deviation to stay under, measured at :data:`CHECK_PER_SPAN` parameters per span both ways.

    Raises
    ------
    GeometryError
        A piece needs more than :data:`MAX_NODES` nodes in θ.
    """
    rho = np.asarray(rho, float)

    def make(piece, a, b, n):
        return _surface_piece(point, tangent, a, b, piece, rho, n)

    def deviation(i, s):
        u, v = check_params(s.knots_u), check_params(s.knots_v)
        return float(np.max(np.linalg.norm(s.evaluate(u, v) - point(u, v), axis=-1)))

    def join(s, nxt):
        s.poles[-1] = nxt.poles[0]

    # a clamped cubic interpolant's error falls as h⁴ (de Boor, A Practical Guide to Splines, ch. V): the
    # count that meets the tolerance is predicted from the last one, not doubled past it
    pieces, worst = refined(spans, make, deviation, join, tolerance_mm, "surface", order=4)
    return SurfaceFit(tuple(pieces), worst)
