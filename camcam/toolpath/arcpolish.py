"""Fewer arcs: a closed contour's march spline re-fitted with the goal's count of arcs by optimisation.

:func:`fewer_arcs` takes the beam march's spline of a closed contour
(:mod:`camcam.toolpath.beam`) that has more arcs than the goal, and asks the
chain optimiser (:mod:`camcam.toolpath.arcchain`) for the same contour with
fewer: one of the march's joints is dropped and the rest optimised as a
chain, and so on until the count is the goal's; the chain is then printed on
the grid (:mod:`camcam.toolpath.arcprint`) and measured.  It replaces most of the further march starts the goal used to
need (each a whole march, 0.3–0.5 s at 0.001 mm) with a few LP solves.

Which joint to drop.  Dropping a joint and optimising again is local
optimisation: the result depends on which joint goes (one drop can leave the
chain at 0.72 of the band and its neighbour at 2).  Measured on the 12
contour × tolerance cases of ``benchmarks/run_nc.py --arcs`` whose first march
missed the goal, every joint dropped in turn (2026-12-06): the drops that fit
sit at either end of a sliver (a closure's leftover arc, which prints badly
anyway), at a dwell split into two long arcs, at the shortest arcs (where κ′
jumps) or between arcs with error to spare.  :func:`_removal_order` puts those
first: on the 12 cases (17 drops) its first joint fits 15 times, and the two
others (disc-oscillating-flat at 0.0005 mm) fit at the second and third try.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.toolpath.arcchain import (CurveTable, OnCurve, chain_errors, chain_samples, joints_of, minimax_chain,
                                      on_curve, sample_spacing)
from camcam.toolpath.arcprint import printed_chain
from camcam.toolpath.beam import ArcSpline
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.toolpath.quantizer import Quantizer

__all__ = ["fewer_arcs", "ENOUGH", "HOPELESS"]

# What the chain may spend of the band (printing's allowance, the least share left, the G1 gap) is the budget's
# (FitBudget.chain_print_steps, chain_min_share, chain_gap_share).  These two are search heuristics, not shares:
# the chain is accepted only within the budget's band, then printed and measured, whatever they are.
#: The optimiser may stop once a chain is within this × its band (3 % to spare for printing, which moves its
#: error by up to 0.35 grid steps): a stopping rule of the search; a chain is accepted only within the band.
ENOUGH = 0.97
#: A drop's optimisation is given up once its chain is hopeless, still over this × the band (a stopping rule,
#: see :data:`camcam.toolpath.arcseed.GIVE_UP` for how such factors were judged); it only saves time.
HOPELESS = 1.05


def _removal_order(oc: OnCurve, tab: CurveTable, per_arc: int) -> list[int]:
    """Joints to try dropping, most promising first (the module's notes say how this was measured).

    Either end of a sliver (an arc shorter than a quarter of the median
    chord); a joint between two arcs each longer than 2.5 × the median chord
    (a dwell split in two); then the shortest-adjacent-arc order and the
    most-slack order (the least sampled error of the two arcs) taken in turn.
    """
    n = len(oc.t)
    _, c, _, _, _ = oc.joints.arcs()
    res = chain_errors(oc.joints, tab, *chain_samples(oc, tab, sample_spacing(oc, tab, per_arc)))
    ce = np.zeros(n)
    np.maximum.at(ce, res[1], np.abs(res[0]))
    prev = np.roll(c, 1)
    med = float(np.median(c))
    # a sliver (a closure's leftover) prints badly (its rounded ends turn its end tangent by up to 1.4 steps over
    # its chord, which the next arc carries over its length), so its joints go first
    short = np.argsort(np.minimum(c, prev), kind="stable").tolist()
    sliver = [j for j in short if min(c[j], prev[j]) < 0.25 * med]
    split = [j for j in range(n) if c[j] > 2.5 * med and prev[j] > 2.5 * med]
    slack = np.argsort(ce + np.roll(ce, 1), kind="stable").tolist()
    order: list[int] = []
    for j in sliver + split + [x for pair in zip(short, slack) for x in pair]:
        if j not in order:
            order.append(j)
    return order


def fewer_arcs(curve, a: float, b: float, tolerance_mm: float, quantizer: Quantizer, max_sweep: float, sag: float,
               spline: ArcSpline, n_arcs: int, *, tries: int = 12, per_arc: int = 24,
               budget: FitBudget = DEFAULT_BUDGET) -> tuple[ArcSpline, ...]:
    """A printed closed G1 spline of ``n_arcs`` arcs within ``tolerance_mm``, from a march's ``spline`` with more.

    While the chain has more than ``n_arcs`` arcs, a joint is dropped: the first of :func:`_removal_order`
    (of the march's joints, then of the last chain's), of at most ``tries``, whose chain optimised
    (:func:`~camcam.toolpath.arcchain.minimax_chain`) keeps within the band less ``budget``'s allowance for
    printing (:meth:`FitBudget.chain_band_mm <camcam.toolpath.budget.FitBudget.chain_band_mm>`).  (Optimising
    the march's own chain first, for its slack, found the same counts on the 12
    cases in 1.4–2 × the time.)  The chain is printed (:func:`~camcam.toolpath.arcprint.printed_spline`) and
    measured both ways on the curve's table (:func:`~camcam.toolpath.arcprint.measured_deviation`).

    Returns
    -------
    tuple of ArcSpline
        The one spline found, its elements starting at the curve parameters in ``starts``; or nothing, when
        no drop keeps within the band, printing leaves it, or the band is too narrow for the grid.
    """
    m = len(spline.elements)
    allowed = budget.chain_band_mm(tolerance_mm, quantizer)
    if m <= n_arcs or not budget.chain_holds(tolerance_mm, quantizer) or max_sweep > 0.9 * math.pi:
        return ()
    tab = CurveTable(curve, a, b, 16384)
    jn = joints_of(spline.elements)
    oc = on_curve(curve, a, b, jn, tab.t[tab.nearest(jn.J)])
    while len(oc.t) > n_arcs:
        # the last drop may stop once within the target (3 % to spare for printing); an earlier one is optimised
        # to the end, which leaves the most room for the drops after it
        enough = ENOUGH * allowed if len(oc.t) == n_arcs + 1 else 0.0
        for j in _removal_order(oc, tab, per_arc)[:tries]:
            keep = np.arange(len(oc.t)) != j
            trial = OnCurve(curve, a, b, t=oc.t[keep], v=oc.v[keep], psi=oc.psi[keep], w=oc.w)
            trial, err, gap = minimax_chain(trial, tab, max_sweep=max_sweep, per_arc=per_arc,
                                            hopeless=HOPELESS * allowed, enough=enough)
            if err <= allowed and gap <= budget.chain_gap_mm(tolerance_mm):
                oc = trial
                break
        else:
            return ()
    return printed_chain(oc, tab, quantizer, sag, max_sweep, tolerance_mm)
