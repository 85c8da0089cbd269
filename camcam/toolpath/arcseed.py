"""A closed contour's arc spline without a march: a chain seeded from the optimal pattern's arc density.

:mod:`camcam.toolpath.arcspline` explains the optimum of a G1 arc spline in
a band of half width δ on a smooth curve: the error on each arc follows
e = −κ′h³B₃(s/h)/6, so an arc of the optimum is h = (124.7·δ/|κ′|)^⅓ long and
the optimum spends (|κ′|/124.7·δ)^⅓ arcs per unit length, 1.155 × the N_lb
integrand.  That density is the seed: :func:`seed_density` integrates it over
the turn (at least |κ|/(0.9·max sweep) per unit length, since a dwell's
circle, where κ′ = 0, still needs arcs for its sweep), and :func:`seeded_chain`
puts N joints at equal steps of the integral, on the curve and along its
tangent, and lets the chain optimiser
(:func:`~camcam.toolpath.arcchain.minimax_chain`, Maier's free breakpoints
and the LP steps of :func:`~camcam.toolpath.arcpolish.fewer_arcs`) move them
to the least largest error; the chain is printed on the grid and measured
both ways (:mod:`camcam.toolpath.arcprint`), as the optimised chain of a
march is.

It tries N = ⌈∫⌉, ⌈∫⌉ + 1, ⌈∫⌉ + 2 (at most the goal's count) and keeps the
first that stays within the band.  A seed whose chain is still over 1.25 × its
target at the 8th LP step is given up (:data:`GIVE_UP`; on the 20 seeds of
disc-oscillating-roller and disc-translating-flat it was judged on, every one
that fitted was within 1.18 × its target there, 7 of the 9 that did not were
over 1.2 ×, and such a seed costs half the time), and so is one still over
1.03 × at half the steps (of the 11 seeds of those two samples that fitted,
the slowest was at 1.00 × at half time; disc-translating-flat at 0.001 mm's
first seed hovered at 1.04–1.06 × for all 30 steps, 0.23 CPU s;
:func:`~camcam.toolpath.arcpolish.fewer_arcs` gives its chains :data:`~camcam.toolpath.arcpolish.HOPELESS`,
1.05 ×).
Measured with ``benchmarks/run_nc.py --arcs`` (2026-12-06, every closed
contour of the six disc samples with analytic motion at 0.1, 0.01, 0.002,
0.001 and 0.0005 mm, 30 cases): fewer arcs than the beam march (with its
optimised chain) on 17 (one fewer on 16, two on optimize/run-table1 at 0.01
mm), as many on the other 13, none more; a contour's fit took 0.07–0.80 s
where one of the three counts fits (the march 0.17–1.96 s).  On two
(optimize/run-table1 and disc-oscillating-flat at 0.001 mm) none of the three
fits and the march runs as before, 0.2–0.27 s later.  Fewer joints than ⌈∫⌉
fitted only where the sweep limit rounds the count (0.1 mm); and a seed with a
joint at the middle of a dwell, where the march starts, fitted far less often
(none of the four counts from ⌈∫⌉ − 1 on 20 of the 30 cases): the seed starts
at the section's start.  ``benchmarks/seeded_chain.py`` prints, case by case,
which counts fit and what each try costs.

The spline is returned from the section's start; :func:`~camcam.toolpath.arcspline.fit_arc_spline` begins
it at the joint nearest the middle of the longest dwell, where the march starts and the program's leads go
(on the disc samples the seeded chain spans each 60° dwell with one arc, so that joint is the dwell's end).

Where the curve is not smooth on the scale of δ (a noisy lift table, a cam
recovered from measured points) the density counts the wiggles of κ′ that
the band can swallow, and the march does far better (the noisy lift at the
five tolerances: 6, 14, 22, 33, 45 arcs marched, the first seeded count that
fits 7, 15, 27, 34 and none; the recovered disc 8, 17, 28, 44, 67 against 10,
23, 40, 52 and none): such a curve is told by its
N_lb, which the Chebyshev copy the fitter works on has 4–6 % above the exact
curve's there and within 0.1 % on the analytic cams, so
:func:`~camcam.toolpath.arcspline.fit_arc_spline` seeds only a curve whose two
figures agree within :data:`SMOOTH_RATIO`.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.curve import curvature, curvature_rate
from camcam.toolpath.arcchain import CurveTable, OnCurve, minimax_chain
from camcam.toolpath.arcpolish import ENOUGH
from camcam.toolpath.arcprint import printed_chain
from camcam.toolpath.beam import ArcSpline
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.toolpath.quantizer import Quantizer

__all__ = ["seed_density", "seeded_count", "seeded_chain", "SMOOTH_RATIO", "PATTERN_CONSTANT"]

#: The optimal G1 pattern's error bound |e| ≤ |κ′|h³/124.7: 6 over the largest |B₃| on [0, 1] (√3/36),
#: 72√3 = 124.708 to four figures.  The seed is a heuristic start, and the chain it gives depends on the joints' exact
#: places: the counts in the module notes were measured with 124.7 (with 72√3 the polar test cam at 0.00095 mm
#: comes out at 32 arcs instead of 31), so 124.7 it stays.
PATTERN_CONSTANT = 124.7
#: A curve is seeded when its Chebyshev copy's N_lb is within this factor of the exact curve's (module notes).
SMOOTH_RATIO = 1.01
#: (step, factor, factor at half the steps): a seed whose chain is still over factor × its target at that LP
#: step is given up, and one over the last factor × it at half the steps (module notes).
GIVE_UP = (8, 1.25, 1.03)


def seed_density(curve, a: float, b: float, tolerance_mm: float, max_sweep: float, n: int = 4096):
    """The optimal pattern's arcs along [a, b] within ``tolerance_mm``: parameters (n,), the running count (n + 1,)
    and the turns the tangent makes round the closed curve (+1 counter-clockwise, −1 clockwise).

    The count per unit length is max((|κ′| / 124.7·tol)^⅓, |κ| / (0.9·max_sweep)), integrated by the
    rectangle rule on ``n`` parameters from ``a`` (the last entry is the whole turn's).

    Examples
    --------
    A circle of radius 10 mm has κ′ = 0: only its sweep counts, 2π / (0.9 · 2π/3) = 3.33 arcs.

    >>> from camcam.geometry.curve import FunctionCurve
    >>> def circle(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return 10 * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], -1)
    >>> C = FunctionCurve(circle, 0.0, 2 * np.pi, closed=True)
    >>> t, count, turns = seed_density(C, 0.0, 2 * np.pi, 0.01, 2 * np.pi / 3)
    >>> round(float(count[-1]), 3), turns
    (3.333, 1)
    """
    t = np.linspace(a, b, n, endpoint=False)
    d1 = curve.evaluate(t, 1)
    sp = np.hypot(d1[:, 0], d1[:, 1])
    pattern = np.cbrt(np.abs(curvature_rate(curve, t)) / (PATTERN_CONSTANT * tolerance_mm))
    per_length = np.maximum(pattern, np.abs(curvature(curve, t)) / (0.9 * max_sweep))
    count = np.concatenate([[0.0], np.cumsum(per_length * sp) * ((b - a) / n)])
    heading = np.arctan2(d1[:, 1], d1[:, 0])
    turning = np.mod(np.diff(np.append(heading, heading[0])) + np.pi, 2 * np.pi) - np.pi
    return t, count, round(float(turning.sum()) / (2 * np.pi))


def seeded_chain(curve, a: float, b: float, tolerance_mm: float, quantizer: Quantizer, max_sweep: float, sag: float,
                 n_max: int, *, tries: int = 3, per_arc: int = 24,
                 budget: FitBudget = DEFAULT_BUDGET) -> tuple[ArcSpline, ...]:
    """A printed closed G1 spline of at most ``n_max`` arcs within ``tolerance_mm``, seeded from the arc density.

    N = ⌈∫⌉ … ⌈∫⌉ + ``tries`` − 1 joints (at most ``n_max``), in turn, are put at equal steps of
    :func:`seed_density` from ``a``, on the curve along its tangent; the chain is optimised
    (:func:`~camcam.toolpath.arcchain.minimax_chain`), printed and measured both ways on the curve's table,
    as :func:`~camcam.toolpath.arcpolish.fewer_arcs` does.  The chain's share of ``tolerance_mm`` (what printing may
    add, the G1 gap it may keep) is ``budget``'s (:class:`~camcam.toolpath.budget.FitBudget`).

    Returns
    -------
    tuple of ArcSpline
        The first spline that keeps within ``tolerance_mm``, its elements starting at the curve parameters in
        ``starts``; or nothing (none did, or the band is too narrow for the grid, or arcs may sweep
        more than 0.9 π).

    Examples
    --------
    An ellipse of semi-axes 40 and 25 mm within 0.01 mm, on a 4-decimal grid: N_lb = 14.65.

    >>> from camcam.geometry.curve import FunctionCurve
    >>> def ellipse(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return np.stack([[40 * c, 25 * s], [-40 * s, 25 * c], [-40 * c, -25 * s], [40 * s, -25 * c]][k], -1)
    >>> E = FunctionCurve(ellipse, 0.0, 2 * np.pi, closed=True)
    >>> (sp,) = seeded_chain(E, 0.0, 2 * np.pi, 0.0095, Quantizer(4), np.radians(120), 5e-5, 21)
    >>> len(sp.elements) <= 1.2 * 14.65 + 4, sp.elements[0].start == sp.elements[-1].end
    (True, True)
    """
    allowed = budget.chain_band_mm(tolerance_mm, quantizer)
    if not budget.chain_holds(tolerance_mm, quantizer) or max_sweep > 0.9 * math.pi:
        return ()
    density = seed_density(curve, a, b, allowed, max_sweep)
    first = max(3, math.ceil(float(density[1][-1])))
    tab = None
    for n in range(first, min(first + tries - 1, n_max) + 1):
        if tab is None:
            tab = CurveTable(curve, a, b, 16384)
        for spline in seeded_count(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, n, density, tab, per_arc=per_arc,
                                   budget=budget):
            return (spline,)
    return ()


def seeded_count(curve, a: float, b: float, tolerance_mm: float, quantizer: Quantizer, max_sweep: float, sag: float, n: int,
                 density, tab: CurveTable, *, per_arc: int = 24, budget: FitBudget = DEFAULT_BUDGET
                 ) -> tuple[ArcSpline, ...]:
    """One seed of :func:`seeded_chain`: ``n`` joints at equal steps of ``density`` (:func:`seed_density` at the
    band less printing's allowance, :meth:`FitBudget.chain_band_mm`) from ``a``, optimised on ``tab``, printed and
    measured; the spline, or nothing (the chain given up or over the band, or its printed form over ``tolerance_mm``)."""
    allowed = budget.chain_band_mm(tolerance_mm, quantizer)
    t, count, turns = density
    total = float(count[-1])
    joints_t = np.interp(np.arange(n) / n * total, count, np.concatenate([t, [b]]))
    seed = OnCurve(curve, a, b, t=joints_t, v=np.zeros(n), psi=np.zeros(n), w=turns)
    chain, err, gap = minimax_chain(seed, tab, max_sweep=max_sweep, per_arc=per_arc, enough=ENOUGH * allowed,
                                    early=(GIVE_UP[0], GIVE_UP[1] * allowed), hopeless=GIVE_UP[2] * allowed)
    if err > allowed or gap > budget.chain_gap_mm(tolerance_mm):
        return ()
    return printed_chain(chain, tab, quantizer, sag, max_sweep, tolerance_mm)
