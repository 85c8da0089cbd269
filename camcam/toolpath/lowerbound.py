"""How many blocks a contour needs at least: N_lb for arcs, the chordal estimate for lines.

Both are integrals along the curve of a power of a signed curvature quantity,
∫ (|g| / c)^p ds: for arcs g = κ′ = dκ/ds, c = 192 δ, p = ⅓ (a single arc
with free ends equioscillates like a Chebyshev cubic, |e| ≤ |κ′|h³/192); for
lines g = κ, c = 8 δ, p = ½ (the seed paper's chord, δ = L²/8ρ).

Quadrature.  Within an analytic piece of the curve g is smooth, but |g|^p is
not where g changes sign: there it has a cusp (|t − t₀|^p), which caps any
equally spaced rule (Simpson on 20 001 points agreed with adaptive quadrature
to about 1e-4 only).  So each piece is cut at the roots of g
(:func:`camcam.geometry.extrema.roots_in`, to :data:`ROOT_XTOL`), and each part is mapped from
s ∈ [0, 1] by the quintic smoothstep t = a + (b − a)(10s³ − 15s⁴ + 6s⁵),
whose dt/ds = 30s²(1 − s)²(b − a) vanishes to second order at both ends:
near a simple root |g|^p·dt/ds then behaves like s^(3p + 2), which for p = ⅓ is
s³, a polynomial, and for p = ½ is s^3.5, smooth enough.  The mapped integrand
is summed by composite Gauss–Legendre (panels no wider than :data:`PANEL_MAX_RAD`, of
:data:`NODES` nodes each): about 2 900 evaluations for a whole disc cam instead of
20 001 per piece.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.curve import PlanarCurve, curvature, curvature_rate, speed
from camcam.geometry.extrema import roots_in
from camcam.toolpath.fitcore import pieces

__all__ = ["lower_bound_blocks", "line_estimate_blocks", "lower_bound_pieces", "line_estimate_pieces",
           "power_integral", "power_integrals", "NODES", "PANEL_MAX_RAD", "ROOT_XTOL"]

#: Where g changes sign the integrand is ~|t − t₀|^p: a root ε off leaves an error of order ε^(1+p)
#: times the integrand's scale, below 1e-13 of N_lb at ε = 1e-10 rad.
ROOT_XTOL = 1e-10

#: Gauss–Legendre nodes per panel, and the widest panel (rad of the curve parameter, after the map):
#: within a piece a lift table's spline still has a knot every degree or so, where κ′ has a kink.
NODES = 4
PANEL_MAX_RAD = math.radians(0.25)

_X, _W = np.polynomial.legendre.leggauss(NODES)


def _rule(panels: int) -> tuple[np.ndarray, np.ndarray]:
    """Nodes t(s) ∈ [0, 1] of the mapped composite rule and their weights (w·dt/ds)."""
    s = ((np.arange(panels)[:, None] + 0.5 * (_X[None, :] + 1.0)) / panels).ravel()
    w = np.tile(_W / (2.0 * panels), panels)
    return s**3 * (10.0 - 15.0 * s + 6.0 * s**2), w * 30.0 * s**2 * (1.0 - s) ** 2


def power_integral(curve: PlanarCurve, g, scale: float, power: float, a=None, b=None) -> float:
    """∫ (|g(t)| / scale)^power ds over [a, b] (default: the whole curve), cut at the roots of g.

    Parameters
    ----------
    curve : PlanarCurve
        The curve; s is its arc length.
    g : callable
        ``g(curve, t)`` for t of shape (n,), shape (n,): analytic between the curve's breaks.
    scale, power : float
        The integrand is ``(|g| / scale) ** power`` times the curve's speed.
    a, b : float, optional
        Parameter range; the curve's own by default.

    Returns
    -------
    float

    Examples
    --------
    A circle of radius 10 has κ = 1/10 everywhere, so ∫ √(κ / 8δ) ds = 2π·10·√(0.1/0.08):

    >>> import math
    >>> from camcam.geometry.curve import FunctionCurve, curvature
    >>> def f(t, order):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return 10 * np.stack([(c, s), (-s, c), (-c, -s), (s, -c)][order], axis=-1)
    >>> circle = FunctionCurve(f, 0.0, 2 * math.pi, closed=True)
    >>> round(power_integral(circle, curvature, 8 * 0.01, 0.5) / (20 * math.pi * math.sqrt(1.25)), 12)
    1.0
    """
    return float(np.sum(power_integrals(curve, g, scale, power, pieces(curve, a, b))))


def power_integrals(curve: PlanarCurve, g, scale: float, power: float, edges) -> np.ndarray:
    """:func:`power_integral` over each (a, b) of ``edges`` (each within one analytic piece), at once:
    one root search and one evaluation of ``g`` for all of them; shape (len(edges),)."""
    edges = [(float(lo), float(hi)) for lo, hi in edges]
    live = [k for k, (lo, hi) in enumerate(edges) if hi > lo]
    out = np.zeros(len(edges))
    if not live:
        return out
    ts, ws, owner = [], [], []
    for k, inner in zip(live, roots_in(lambda t: g(curve, t), [edges[k] for k in live], ROOT_XTOL)):
        cuts = [edges[k][0], *inner, edges[k][1]]
        for u, v in zip(cuts, cuts[1:]):
            if not v > u:
                continue
            # the map stretches the middle of a part by 30/16 = 1.875
            x, w = _rule(max(4, math.ceil(1.875 * (v - u) / PANEL_MAX_RAD)))
            ts.append(u + (v - u) * x)
            ws.append((v - u) * w)
            owner.append(np.full(len(x), k))
    t = np.concatenate(ts)
    f = np.concatenate(ws) * (np.abs(g(curve, t)) / scale) ** power * speed(curve, t)
    np.add.at(out, np.concatenate(owner), f)
    return out


def lower_bound_blocks(curve: PlanarCurve, tolerance_mm: float, a=None, b=None) -> float:
    """N_lb = ∫ (|dκ/ds| / (192 δ))^(1/3) ds: fewest arcs any arc spline can use (asymptotically)."""
    return power_integral(curve, curvature_rate, 192.0 * tolerance_mm, 1.0 / 3.0, a, b)


def lower_bound_pieces(curve: PlanarCurve, tolerance_mm: float, edges) -> tuple[float, ...]:
    """N_lb of each (a, b) of ``edges`` (:func:`lower_bound_blocks`), in one batch."""
    return tuple(float(x) for x in power_integrals(curve, curvature_rate, 192.0 * tolerance_mm, 1.0 / 3.0, edges))


def line_estimate_pieces(curve: PlanarCurve, tolerance_mm: float, edges) -> tuple[float, ...]:
    """The chordal estimate of each (a, b) of ``edges`` (:func:`line_estimate_blocks`), in one batch."""
    return tuple(float(x) for x in power_integrals(curve, curvature, 8.0 * tolerance_mm, 0.5, edges))


def line_estimate_blocks(curve: PlanarCurve, tolerance_mm: float, a=None, b=None) -> float:
    """∫ √(|κ| / (8 δ)) ds: chords needed by the chordal method (δ = L²/8ρ)."""
    return power_integral(curve, curvature, 8.0 * tolerance_mm, 0.5, a, b)
