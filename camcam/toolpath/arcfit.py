"""The NC second fitting: arcs (G1-continuous arc spline) or lines, deviation guaranteed.

Arcs.  On each analytic piece of the curve (between its ``breaks``) a G1 arc
spline is marched from the curve's start point and exact tangent.  Its nodes
lie on the curve; each arc leaves a node along the spline's tangent and ends
at the next node.  A plain greedy march (longest arc each time) leaves a
tangent error that cuts the next arc short; so each candidate next node is
scored by how far the arc after it can reach (one-step lookahead).  The
march then settles on the optimal periodic G1 arc spline, whose error
e(s) = −κ′h³B₃(s/h)/6 equioscillates with |e| ≤ |κ′|h³/124.7, i.e. about
(192/124.7)^⅓ = 1.155·N_lb arcs.  Each piece ends with a biarc onto the
curve's exact end tangent, so pieces join tangent-continuously.

Lines.  The seed paper's chordal method (Hu & Guo, eq. 8): a chord of length
L on curvature radius ρ errs by δ ≈ L²/(8ρ), so the step starts from
L = √(8ρδ) and is lengthened or shortened until the chord is within tolerance.

Guarantee.  Every node, arc end and centre is put on the post's printed grid
(:class:`~camcam.toolpath.quantizer.Quantizer`), each piece is rebuilt as the
controller cuts it and measured two-sided against the exact curve by
:func:`measure_deviation` (which adds its own between-sample bound).  The
shares of the tolerance and the one retry loop are
:class:`~camcam.toolpath.budget.FitBudget`'s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import simpson

from camcam.errors import FitError, InputError
from camcam.geometry.curve import PlanarCurve, curvature, curvature_rate, speed
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.toolpath.deviation import Deviation, measure_deviation
from camcam.toolpath.elements import Arc, Line, arc_from_tangent
from camcam.toolpath.fitcore import (Piece, biarc, dev, end_tangent, greedy, pieces, signed_angle, sweep_ok,
                                      unit)
from camcam.toolpath.quantizer import Quantizer

__all__ = ["FitResult", "fit_contour", "lower_bound_blocks", "line_estimate_blocks"]


@dataclass(frozen=True)
class FitResult:
    """A fitted contour: elements on the decimal grid, in the curve's direction."""

    elements: tuple
    mode: str
    tolerance_mm: float
    decimals: int
    deviation: Deviation
    lower_bound: float  # N_lb for arcs (∫(|κ′|/192δ)^⅓ ds), for lines ∫√(|κ|/8δ) ds
    piece_blocks: tuple[int, ...]
    piece_lower_bounds: tuple[float, ...]

    @property
    def line_blocks(self) -> int:
        return sum(isinstance(e, Line) for e in self.elements)

    @property
    def arc_blocks(self) -> int:
        return sum(isinstance(e, Arc) for e in self.elements)

    @property
    def max_deviation_mm(self) -> float:
        return self.deviation.max_deviation_mm


def _integral(curve, a, b, f, n: int = 20001) -> float:
    """∫ f ds over [a, b] by Simpson's rule on ``n`` parameter points (vectorised)."""
    t = np.linspace(a, b, n)
    return float(simpson(f(t) * speed(curve, t), x=t))


def lower_bound_blocks(curve: PlanarCurve, tolerance_mm: float, a=None, b=None) -> float:
    """N_lb = ∫ (|dκ/ds| / (192 δ))^(1/3) ds: fewest arcs any arc spline can use (asymptotically)."""
    edges = pieces(curve, a, b)
    return sum(_integral(curve, lo, hi, lambda t: np.cbrt(np.abs(curvature_rate(curve, t)) / (192 * tolerance_mm)))
               for lo, hi in edges)


def line_estimate_blocks(curve: PlanarCurve, tolerance_mm: float, a=None, b=None) -> float:
    """∫ √(|κ| / (8 δ)) ds: chords needed by the chordal method (δ = L²/8ρ)."""
    return sum(_integral(curve, lo, hi, lambda t: np.sqrt(np.abs(curvature(curve, t)) / (8 * tolerance_mm)))
               for lo, hi in pieces(curve, a, b))


#: Candidate next nodes per step, spread over [0.25, 2.5] × the last step.
LOOKAHEAD_GRID = 14


def _fit_arcs_piece(piece, tol, max_sweep, sag):
    """March a G1 arc spline over one piece with a one-step lookahead.

    From the current node (on the curve, with the spline's tangent), every
    candidate end node whose single arc stays within ``tol`` is scored by how
    far the *following* arc can then reach; the best one is taken.  The
    tangent error a plain greedy march leaves behind is what makes it short
    (≈ 2.5 vs 5.0 in units of (δ/κ′)^⅓); the lookahead settles at the
    periodic optimum's equioscillating arcs (≈ 4.94).  The piece ends with a
    biarc onto the curve's exact end tangent.
    """
    a, b = piece.a, piece.b
    exact_end = unit(float(piece.phi(b)[0]))
    cache: dict = {}

    def arc_to(t0, tan, t1):
        key = (t0, tuple(tan), t1)
        if key not in cache:
            e = arc_from_tangent(piece.point(t0)[0], tan, piece.point(t1)[0], sag)
            ok = sweep_ok([e], max_sweep) and dev(piece, [e], t0, t1) <= tol
            cache[key] = (e, ok)
        return cache[key]

    def feasible(t0, tan, h):
        grid = t0 + h * np.linspace(0.25, 2.5, LOOKAHEAD_GRID)
        grid = np.unique(np.minimum(grid, b))
        return [t1 for t1 in grid if t1 > t0 and arc_to(t0, tan, t1)[1]]

    def finish(t0, tan):
        bi = biarc(piece.point(t0)[0], tan, piece.point(b)[0], exact_end, sag)
        if bi is not None and sweep_ok(bi, max_sweep) and dev(piece, bi, t0, b) <= tol:
            return bi
        return None

    elems = []
    t = a
    tan = unit(float(piece.phi(a)[0]))
    h = (b - a) / 2.5  # first try the whole piece (a dwell circle is one arc)
    while True:
        if b - t <= 2.5 * h:
            e, ok = arc_to(t, tan, b)
            if ok and abs(signed_angle(end_tangent(e), exact_end)) < 1e-9:
                elems.append(e)
                return elems
            bi = finish(t, tan)
            if bi is not None:
                elems.extend(bi)
                return elems
        # the end b is only reached through the exact-tangent checks above
        cands = [c for c in feasible(t, tan, h) if c < b - 1e-12 * (b - a)]
        if not cands:
            h *= 0.3
            if h < (b - a) * 1e-9:
                raise FitError(f"cannot fit an arc near t = {t:g} within {tol:g} mm")
            continue
        t1_max = max(cands)
        step = h * 2.25 / (LOOKAHEAD_GRID - 1)  # grid spacing

        def score(t1):
            e, _ = arc_to(t, tan, t1)
            et = tuple(end_tangent(e))
            if b - t1 <= 2.5 * (t1 - t) and finish(t1, et) is not None:
                return b + 1.0  # the piece can be closed from here
            nxt = feasible(t1, et, t1 - t)
            if not nxt:
                return t1
            lo, hi = max(nxt), min(max(nxt) + step * (t1 - t) / h, b)
            for _ in range(5):  # sharpen the reach between grid points
                mid = 0.5 * (lo + hi)
                if arc_to(t1, et, mid)[1]:
                    lo = mid
                else:
                    hi = mid
            return lo

        scored = [(score(t1), t1) for t1 in sorted(cands, reverse=True)[:7]]
        best_reach, best = max(scored)
        for frac in (-0.5, -0.25, 0.25, 0.5):  # refine around the best grid point
            t1 = best + frac * step
            if t < t1 < b - 1e-12 * (b - a) and t1 <= t1_max + step and arc_to(t, tan, t1)[1]:
                r = score(t1)
                if r > best_reach:
                    best_reach, best = r, t1
        e, _ = arc_to(t, tan, best)
        elems.append(e)
        tan = tuple(end_tangent(e))
        h = best - t
        t = best
        if len(cache) > 4096:
            cache.clear()


def _fit_lines_piece(piece, tol):
    a, b = piece.a, piece.b
    k = np.abs(curvature(piece.curve, piece.grid))
    v = speed(piece.curve, piece.grid)

    def ok(t0, t1):
        q0, q1 = piece.point(t0)[0], piece.point(t1)[0]
        if np.hypot(*(q1 - q0)) == 0:
            return False
        return dev(piece, [Line(tuple(q0), tuple(q1))], t0, t1) <= tol

    nodes = [a]
    while nodes[-1] < b:
        t0 = nodes[-1]
        j = int(np.searchsorted(piece.grid, t0))
        j = min(j, len(piece.grid) - 1)
        step_mm = math.sqrt(8.0 * tol / max(k[j], 1e-12))  # seed paper eq. (8): δ = L²/8ρ
        nodes.append(greedy(t0, b, ok, step_mm / max(v[j], 1e-12)))
    pts = piece.point(np.array(nodes))
    return [Line(tuple(p), tuple(q)) for p, q in zip(pts[:-1], pts[1:])]


def fit_contour(curve: PlanarCurve, tolerance_mm: float, *, mode: str = "arcs",
                quantizer: Quantizer = Quantizer(4), max_sweep_deg: float = 90.0,
                a: float | None = None, b: float | None = None, exact: PlanarCurve | None = None,
                printed: Callable[[tuple], tuple] | None = None, budget: FitBudget = DEFAULT_BUDGET) -> FitResult:
    """Fit lines/arcs to ``curve`` with a guaranteed two-sided deviation ≤ ``tolerance_mm`` as printed.

    Each analytic piece is fitted, put on the printed grid, rebuilt as the
    controller will cut it (``printed``) and measured two-sided against the
    exact curve; a piece that misses is fitted again at a tighter target
    (:meth:`FitBudget.targets`, the one retry loop).

    Parameters
    ----------
    curve : PlanarCurve
        The curve the march runs on: the exact curve, or a surrogate of it
        (with an ``error_mm`` attribute) when ``exact`` is given.
    tolerance_mm : float
        Two-sided deviation allowed on the program as printed.
    mode : {"arcs", "lines"}
    quantizer : Quantizer
        The post's printed rounding: nodes and centres are snapped to its grid.
    max_sweep_deg : float
        Largest arc sweep (≤ 180; also keeps arcs away from full circles).
    a, b : float, optional
        Parameter range (default the whole curve).
    exact : PlanarCurve, optional
        The curve the printed path is measured against (default ``curve``).
    printed : callable, optional
        Snapped elements → the path the controller cuts (default
        ``quantizer.printed_elements``; the rotary job passes its (X, A) model).
    budget : FitBudget
        How the tolerance is shared out.

    Returns
    -------
    FitResult
        Elements on the printed grid, in the curve's direction.

    Raises
    ------
    InputError
        When the tolerance is below the decimals' floor or the mode unknown.
    FitError
        When a piece still misses after the budget's last attempt.

    Examples
    --------
    >>> import numpy as np
    >>> from camcam.geometry.jet import Jet
    >>> from camcam.geometry.jetcurve import JetCurve
    >>> ellipse = JetCurve(lambda t, K, piece=None: (Jet.variable(t, K).cos() * 30.0, Jet.variable(t, K).sin() * 20.0),
    ...                    np.array([0.0, np.pi, 2 * np.pi]))
    >>> fit = fit_contour(ellipse, 0.01)
    >>> fit.arc_blocks > 0 and fit.max_deviation_mm <= 0.01
    True
    """
    if mode not in ("arcs", "lines"):
        raise InputError(f"mode: expected 'arcs' or 'lines', got {mode!r}")
    if not 0 < max_sweep_deg <= 180:
        raise InputError(f"max_sweep_deg: expected 0 < value ≤ 180, got {max_sweep_deg!r}")
    exact = curve if exact is None else exact
    printed = quantizer.printed_elements if printed is None else printed
    band = tolerance_mm - (getattr(curve, "error_mm", 0.0) if exact is not curve else 0.0)
    if not budget.holds(band, quantizer):
        raise InputError(f"tolerance {tolerance_mm:g} mm is too fine for {quantizer.decimals} decimals "
                         f"(rounding alone takes {budget.rounding_mm(quantizer):.2g} mm); use at least "
                         f"{budget.floor_mm(quantizer):.2g} mm or more decimals")
    targets = tuple(budget.targets(band, quantizer))
    sag = budget.sag_mm(targets[0], quantizer)  # arcs flatter than this print as lines
    max_sweep = math.radians(max_sweep_deg)
    margin = budget.margin_mm(tolerance_mm)
    all_elems, blocks, lbs = [], [], []
    worst = None
    for lo, hi in pieces(curve, a, b):
        piece = Piece(curve, lo, hi)
        for target in targets:
            raw = (_fit_arcs_piece(piece, target, max_sweep, sag) if mode == "arcs"
                   else _fit_lines_piece(piece, target))
            elems = quantizer.snap_elements(raw)
            dev = measure_deviation(exact, printed(elems), lo, hi, margin_mm=margin)
            if dev.max_deviation_mm <= tolerance_mm:
                break
        else:
            raise FitError(f"cannot fit the curve on t ∈ [{lo:g}, {hi:g}] within {tolerance_mm:g} mm: the printed "
                           f"path stays {dev.max_deviation_mm:.4g} mm off after {budget.attempts} attempts")
        all_elems.extend(elems)
        blocks.append(len(elems))
        lbs.append(lower_bound_blocks(exact, tolerance_mm, lo, hi) if mode == "arcs"
                   else line_estimate_blocks(exact, tolerance_mm, lo, hi))
        if worst is None or dev.max_deviation_mm > worst.max_deviation_mm:
            worst = dev
    return FitResult(tuple(all_elems), mode, tolerance_mm, quantizer.decimals, worst, float(sum(lbs)),
                     tuple(blocks), tuple(lbs))
