"""Near-minimal G1 arc spline in a two-sided tolerance band, marched on the printed numbers.

Problem.  Given a smooth planar curve P (the tool-centre path) and a
tolerance δ, find a tangent-continuous (G1) spline of circular arcs, as few
as possible, whose printed form (every end and centre rounded to the post's
decimals) stays within δ of P on both sides.

Literature and the choice made here.

* Drysdale, Rote & Sturm ("Approximation of an open polygonal curve with a
  minimum number of circular arcs and biarcs", Comput. Geom. 2008) find the
  minimum by a shortest path in the graph of all feasible arcs, but only with
  breakpoints at the input vertices (and, for G1, biarcs with tangents given at
  the vertices), O(n² log n) in the vertices.
* Held & Eibl ("Biarc approximation of polygons within asymmetric tolerance
  bands", CAD 2005) and Meek & Walton (arc splines of smooth curves, 1992–95)
  march biarcs through the band; a biarc spends two arcs per pair of
  interpolated tangents, which is not the error pattern of the optimum.
* Maier ("Smooth minimum arc paths", 2014) computes a SMAP, the true minimum
  G1 arc spline in a tolerance polygon, by propagating the region reachable
  with k arcs; breakpoints are free and the papers report that freeing them
  "has a considerably positive effect on the number of segments" against
  Drysdale–Rote–Sturm.

For a *smooth* curve the optimum can be written down.  Along the curve the
normal error e(s) of a G1 arc spline is C¹ and, on each arc (constant
curvature), e‴ = −κ′.  A single arc with no continuity constraint could
equioscillate like a Chebyshev cubic, |e| ≤ |κ′|h³/192: that is the lower
bound N_lb = ∫(|κ′|/192δ)^⅓ ds.  With e and e′ continuous and period h the
error is forced to e = −κ′h³B₃(s/h)/6 (B₃ the Bernoulli polynomial), which
swings from +δ to −δ inside each arc and is zero at the joints:
|e| ≤ |κ′|h³/124.7, i.e. (192/124.7)^⅓ = 1.155·N_lb arcs.  Its joints lie *on*
the curve, so the free breakpoints of Maier's reachable regions buy nothing
in the interior of a smooth curve: only the tangent at each joint is free.
That reduces the search to one dimension per joint (the joint's parameter;
the tangent is inherited from the previous arc), and the question becomes
which joint sequence reaches the end with the fewest arcs.  A plain greedy
march (longest arc each time) leaves tangent errors that cut the next arc
short (≈ 1.7·N_lb measured here before this module); this module searches
the joint sequences breadth-first with a beam: every state after k arcs is
expanded to many candidate next joints at once (numpy: every candidate arc
against the curve as one array), the states reaching farthest are kept, and
a closing biarc or arc (below) gives the spline.

What the search keeps.  Joints on the curve alone cannot undo a tangent
error on a stretch of constant curvature (a dwell's circle): an arc between
two points of a circle mirrors the error, so the march would crawl.  So each
state is also tried with joints offset across the band (``offsets``), which
is Maier's free breakpoint where it pays.  After k arcs the states are
thinned like a reachable region: per cell of (joint offset, tangent error)
only the farthest survives (:func:`camcam.toolpath.beam._frontier`; the tangent error is measured
in δ/h, the optimum's joints sit at ±10.4), then the ``beam`` whose next arc
reaches farthest (one-step lookahead).  The lookahead ranks the ``pool`` by
the reach of each state's on-curve ray alone; only the ``beam`` kept get
their off-curve rays (before 2026-12-04 all five rays of all 40 states were
expanded and those of 24 thrown away after ranking).  Measured on 750
marches (the five disc samples' first contours at 0.002, 0.001 and 0.0005
mm, 25 start shifts × 2 stretches each): 34.00 arcs on average against
34.04, 325 marches within the goal against 306, and one march 0.68 → 0.51
CPU s on disc-translating-roller at 0.001 mm (0.72 → 0.53 on
disc-oscillating-roller); every sample's output as before
(``tests/data/sample_checksums.json``).

Closing a closed contour.  The march starts at the middle of a stretch of
near-constant curvature (a dwell, :func:`~camcam.toolpath.arcclose.quiet_stretches`) with its first
joint's offset and tangent free, runs on past the start by a third of a
turn, and closes in one of two ways, whichever spends fewer arcs:

* a biarc with a free join (Held–Eibl's family, searched over its join
  parameter) onto the start or onto the j-th joint, the first j arcs then
  dropped (two arcs for the closure);
* one arc that *lands* on the circle of the j-th arc: from a state's joint and
  tangent exactly one arc touches a given circle with the same direction of
  travel (:func:`~camcam.toolpath.arcbatch.touch`, signed radii ρ = (R² − |p − c|²) / (2 (n·(p − c) + R))),
  so where the touch point lies on the j-th arc's circle ahead of its end,
  that arc is drawn back to it and arcs 1 … j−1 drop out
  (:func:`~camcam.toolpath.arcclose.landings`): one arc for the closure.  The touch point is
  rounded to the grid, and the closure is kept only if the kink it leaves is
  no more than rounding makes (≤ 0.71·step·(2/chord + 1/R)) and the two arcs
  stay within the band on the curve samples.

Counting arcs is a step function of a chaotic search: moving the start by a
few degrees inside the dwell changes the count by ±1–2 (measured on the disc
samples: e.g. 31–34 arcs on one curve at 0.001 mm).  So while a closed
contour's spline has more than ``goal`` = 1.18·N_lb + 4 blocks (N_lb of the
march's band, 0.95·δ: 1.18·(1/0.95)^⅓ = 1.2 on the tolerance's N_lb, the
issue's bound; N_lb of the exact curve, which the fitter passes in: the
Chebyshev copy's own, by a trapezoid rule, is up to 4 % higher on the noisy
lift and the recovered cam, a looser goal than the bound the counts are
judged by; the same counts on all 40 cases of ``run_nc.py --arcs``), the
march starts again from shifted points of the longest dwell and of the next
one (``start_shifts`` × half the stretch, at most ``tries`` marches) and
keeps the spline with the fewest blocks.  A contour within the goal at the
first start (the default sample at 0.1–0.001 mm) is marched once, as before.  A contour still over the goal after all of them is
marched from its first ``wide_tries`` = 2 starts once more with a wider search
(beam 24, pool 60, 7 children per ray instead of 16, 40, 5): that search is
no better on average (its counts differ by ±1 from the default's), but as a
last resort it can only lower the count, and it costs time only on contours
that miss the goal (optimize/run-table1 at 0.001 mm: 31 → 30 arcs, the goal
30.4, the NC step with two workers +3.5 s; disc-translating-flat at 0.0005 mm:
still 40, +7.4 s).

Tried and dropped (measured on the misses): a finer frontier (33 → 65 or 129
tangent cells, pool 80–200, beam 30–60) saves 1–2 arcs on some cases at 2–4×
the time and loses 1–2 on others; extra children that land tangentially on a
dwell's circle (offset across the band) from the states before it changed no
count on the 40 cases.

Also tried (2026-12-02, on the two misses of the time): replacing any 3
consecutive arcs of the final spline by a G1 biarc between the same joints
(11 join ratios) found no replacement on any march, so the beam leaves no
3-for-2 slack; six other budget variants left disc-translating-flat at
0.0005 mm at 40.

Also tried (2026-12-03), for time: a narrower first march (beam 8, pool 24,
about 60 % of a march's time) kept where it meets the goal: the default
sample's NC step 1.75 → 1.18 s at 0.01 mm, but over the 40 cases it had more
arcs than the full march from the same start on 22, fewer on 4 (10 instead
of 9 on the default sample at 0.1 mm), and reverse/recovered-disc at 0.0005
mm came out at 71 arcs against the target's 67.7 (that curve's goal, from the
Chebyshev copy's N_lb, is looser than the target).  The two wide marches
right after the first start instead of after all the others: 3 marches
instead of 11–14 on disc-translating-roller at 0.0005 mm and
optimize/run-table1 at 0.001 mm, but 2 more on disc-oscillating-roller at
0.001 mm and on disc-oscillating-flat at 0.001 and 0.0005 mm (95 marches
against 106 over the 40 cases, a wide one costing 1.5–2 ordinary ones): no
gain.  Eight wide starts on disc-translating-flat at 0.0005 mm: 40 or 41
arcs on all 20 marches.

Also tried (2026-12-05), to spare disc-oscillating-roller at 0.001 mm its 12
marches (counts 36 36 36 37 37 37 38 36 37 36 36 35 from the 12 starts, the
goal 35.9): (a) one march from all 8 start shifts of a dwell at once, each
root's states ranked by their progress from their own root (by rows, or by
the N_lb integrand ∫|κ′|^⅓ ds, the same): over the 6 disc curves at 0.01,
0.002, 0.001 and 0.0005 mm 708 arcs against 704 for the first start alone,
10 goals met against 12, so no better than one more start; (b) from every
joint of a 36-arc march, a beam of 8 levels closing onto the spline's later
joints (biarc, or a landing on a later arc's circle): no window of up to 8
arcs could be done with fewer (33 windows on each of 2 marches), so the
beam leaves no local slack and the count is set by the whole turn (the
march's reach passes once round after 34.8–36.6 levels, its arcs covering
0.9–0.98 of the optimum pattern's length in smooth stretches).

Measured (``benchmarks/run_nc.py --arcs``, the eight disc samples at 0.1–0.0005 mm,
band 0.95·δ): all 40 contour × tolerance cases within 1.2·N_lb + 4 (24
with the biarc closure and one start; 27 with the landing closure alone; 38
before the wider last resort; 39 before the near-miss starts below),
1.28–1.57·N_lb at 0.01–0.0005 mm where N_lb is honest (1.48–1.76 at 0.1 mm,
where the +4 matters).
The last miss, by one block, was disc-translating-flat at 0.0005 mm (40
against 39.8): its 12 starts and 2 wide marches found no spline with one
arc fewer, and a sweep of 50 starts (25 shifts × 2 stretches) found 39 at
2 of them.  So a contour within ``near_miss`` = 1 block of its goal after
all that is marched from up to ``more_tries`` = 50 further starts (the
start shifts left over, then the rest of the 0.08 grid on (−1, 1),
farthest-first: a rule, not picked by any march's count) until one meets
the goal: 39 arcs there, its fit 5.9 → 13.4 s; a contour farther over
its goal is not (the starts would cost time and not reach it), and no
other of the 40 cases marches them.  The default sample's curve: 9,
16, 25, 32 and 39 blocks at 0.1, 0.01, 0.002, 0.001, 0.0005 mm (9, 16, 26,
33, 40 before the landing closure; 15, 20, –, 40 and 48 with the earlier
one-step-lookahead march split at every break).  The remaining gap to
1.155·N_lb is the transitions into and out of dwells, where κ′ jumps (about
an arc each), and the beam's myopia in smooth stretches (arcs reach
0.85–0.97 of the optimum's length there).  The further starts cost time only
where the first misses the goal: up to ``tries`` marches (≈ 3 s each at
0.001 mm), 6–40 s of fit on the contours that need further starts, two at a
time with two workers.  (Until 2026-12-06 the second start was marched beside
the first in a spare child of lower priority and dropped when the first met
the goal: disc-groove at 0.001 mm 3.79 → 3.07 s then; with the optimised
chain below it is not needed, and its CPU cost 2–4 % of the wall time of the
runs whose first start meets the goal, medians of 8 alternated runs.)

The optimised chain (2026-12-06).  A closed contour whose first march misses
the goal is then re-fitted with the goal's count of arcs
(:func:`camcam.toolpath.arcpolish.fewer_arcs`): a joint of the march is
dropped and the rest fitted to the curve as a G1 chain in the largest error
by LP steps (:mod:`camcam.toolpath.arcchain`, joints and breakpoints free),
until the count is the goal's, and the chain is put on the grid
(:mod:`camcam.toolpath.arcprint`) and measured.  The further starts below are
marched only if that finds nothing.  All 12 contour × tolerance cases of
``benchmarks/run_nc.py --arcs`` whose first march misses the goal reach it
this way (disc-oscillating-roller at 0.001 mm: 35 arcs after one march and
0.25 CPU s of LP, where the starts needed 12 marches, ≈ 5 s).

The seeded chain (2026-12-06).  The optimal pattern above says how long each
arc of the optimum is, (124.7·δ/|κ′|)^⅓; so a closed contour of a smooth curve
is first fitted without any march: joints at equal steps of that arc density,
optimised as a chain (:mod:`camcam.toolpath.arcseed`).  Where one of three
counts from the density's integral fits within the goal, that spline is the
fit; the march (everything above) runs only where none does, or where the
curve is noisy (its Chebyshev copy's N_lb over 1 % above the exact curve's).
On the 30 contour × tolerance cases of ``benchmarks/run_nc.py --arcs`` with
analytic motion: one arc fewer than the march on 16, two fewer on one, as
many on 13 (the default sample's curve 8, 16, 25, 31, 38 blocks at 0.1 …
0.0005 mm, the march's 9, 16, 25, 32, 39), and the fit in 0.07–0.80 s instead
of 0.17–1.96 s.  The noisy lift and the recovered disc are marched as before.

Vectorised.  The curve (the Chebyshev copy) is tabulated once; a joint is a
table row, and every candidate arc of every state in a pass is built, put on
the grid and measured against its curve samples as one set of numpy arrays
(:func:`~camcam.toolpath.arcbatch.candidate_deviation`).

Breaks between the curve's analytic pieces are crossed (the curve is G1
there); only a tangent discontinuity (a corner) ends a section.

Printed numbers.  Each candidate is built from the printed start, to the
printed end (the curve point rounded), and its centre is rounded too
(I/J posts); the deviation is measured on that printed arc, the controller's
spiral included, and the next arc leaves along the printed arc's end tangent.
So no share of the tolerance is reserved for rounding: the march's target is
the tolerance less the sampling shares (see :class:`SplineBudget`), and the
program is measured afterwards by :func:`~camcam.toolpath.deviation.measure_deviation`.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from camcam.errors import FitError
from camcam.toolpath.mapper import IN_PROCESS, Mapper
from camcam.toolpath.arcbatch import unit_rows
from camcam.toolpath.arcclose import quiet_stretches
from camcam.toolpath.arcpolish import fewer_arcs
from camcam.toolpath.arcseed import SMOOTH_RATIO, seeded_chain
from camcam.toolpath.beam import ArcSpline, SplineBudget, march
from camcam.toolpath.quantizer import Quantizer

__all__ = ["SplineBudget", "ArcSpline", "fit_arc_spline", "g1_sections", "starting_near"]

def g1_sections(curve, a: float, b: float, angle_tol: float = 1e-6) -> list[tuple[float, float]]:
    """Split [a, b] at the breaks where the tangent direction jumps (corners); G1 breaks are crossed."""
    br = [float(x) for x in np.asarray(curve.breaks, float) if a < x < b]
    cuts = [a]
    for x in br:
        eps = 1e-9 * max(1.0, abs(x))
        d = curve.evaluate(np.array([x - eps, x + eps]), 1)
        u = unit_rows(d)
        if math.atan2(abs(u[0, 0] * u[1, 1] - u[0, 1] * u[1, 0]), float(u[0] @ u[1])) > angle_tol:
            cuts.append(x)
    cuts.append(b)
    return list(zip(cuts, cuts[1:]))


def starting_near(spline: ArcSpline, t: float, a: float, b: float) -> ArcSpline:
    """The closed ``spline`` (elements starting at the curve parameters ``starts`` on [a, b)) begun at the joint
    cyclically nearest the parameter ``t``: the same elements, in the same turn.

    Examples
    --------
    >>> from camcam.toolpath.elements import Line
    >>> sq = ArcSpline((Line((0, 0), (1, 0)), Line((1, 0), (1, 1)), Line((1, 1), (0, 1)), Line((0, 1), (0, 0))),
    ...                (0.0, 1.0, 2.0, 3.0))
    >>> r = starting_near(sq, 2.2, 0.0, 4.0)
    >>> r.starts, r.elements[0].start
    ((2.0, 3.0, 0.0, 1.0), (1, 1))
    """
    period = b - a
    gap = np.abs(np.mod(np.asarray(spline.starts, float) - t + 0.5 * period, period) - 0.5 * period)
    k = int(np.argmin(gap))
    return ArcSpline(spline.elements[k:] + spline.elements[:k], spline.starts[k:] + spline.starts[:k])


def fit_arc_spline(curve, a: float, b: float, tolerance_mm: float, *, quantizer: Quantizer, max_sweep: float,
                   sag: float, closed: bool = False, budget: SplineBudget = SplineBudget(),
                   mapper: Mapper = IN_PROCESS, lower_bound: float | None = None) -> ArcSpline:
    """A near-minimal printed G1 arc spline over [a, b] within ``tolerance_mm`` (sampled).

    Parameters
    ----------
    curve : PlanarCurve
        The curve (G1 on [a, b]); usually the Chebyshev copy of the exact one.
    tolerance_mm : float
        The band's half width the march keeps its sampled deviation within.
    quantizer : Quantizer
        The post's printed rounding: joints and centres go on its grid as the march goes.
    max_sweep : float
        Largest arc sweep (rad), at most π.
    sag : float
        Arcs whose sagitta is at most this print as lines.
    closed : bool
        The section is a whole closed curve: the spline closes G1 onto its own
        first joint (whose offset and tangent are then free).  Otherwise it
        starts and ends on the curve with the curve's exact tangents.
    budget : SplineBudget
        The search's sizes, start shifts and goal.
    mapper : Mapper
        How the further starts of a closed section are marched: ``mapper.width``
        at a time (:mod:`camcam.toolpath.mapper`; the NC stage hands in
        :class:`camcam.workers.ProcessMap`); taken in the same order as one by
        one, so the spline is the same for any mapper.
    lower_bound : float, optional
        N_lb of the section at ``tolerance_mm``, from the exact curve: the
        goal of a closed section is ``budget.goal`` on it.  Without it, N_lb
        of ``curve`` itself (a trapezoid rule on its samples): on a noisy
        curve's Chebyshev copy that is up to 4 % above the exact curve's, and
        so a looser goal than the exact bound.

    Examples
    --------
    >>> from camcam.geometry.curve import FunctionCurve
    >>> def ellipse(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return np.stack([[40 * c, 25 * s], [-40 * s, 25 * c], [-40 * c, -25 * s], [40 * s, -25 * c]][k], -1)
    >>> E = FunctionCurve(ellipse, 0.0, 2 * np.pi, closed=True)
    >>> from camcam.toolpath.quantizer import Quantizer
    >>> sp = fit_arc_spline(E, 0.0, 2 * np.pi, 0.0097, quantizer=Quantizer(4), max_sweep=np.radians(120), sag=5e-5,
    ...                     closed=True)
    >>> len(sp.elements) <= 1.2 * 14.65 + 4, sp.elements[0].start == sp.elements[-1].end  # N_lb = 14.65
    (True, True)
    """
    if not closed:
        return march(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, False, budget, None)
    stretches, integral = quiet_stretches(curve, a, b)
    own = integral / np.cbrt(192.0 * tolerance_mm)
    n_lb = own if lower_bound is None else lower_bound
    goal = budget.goal[0] * n_lb + budget.goal[1]
    # a smooth curve (its copy's N_lb that of the exact curve) is first fitted without a march, by a chain seeded
    # from the optimal pattern's arc density (camcam.toolpath.arcseed: fewer arcs than the march on 17 of the 30
    # analytic cases of run_nc.py --arcs, as many on 13, in a fraction of its time); the march where that finds
    # nothing
    if budget.seeded and lower_bound is not None and own <= SMOOTH_RATIO * lower_bound:
        for spline in seeded_chain(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, math.floor(goal),
                                   tries=budget.seed_tries):
            # the program starts (and its leads sit) at the joint nearest the longest dwell's middle, where the
            # march starts too (on the disc samples the dwell's end: the seeded chain spans each dwell with one arc)
            return starting_near(spline, stretches[0][0], a, b)
    # the longest stretch first; then the others at least half as long, each start shift in turn
    stretches = [st for st in stretches if st[1] >= 0.5 * stretches[0][1]][:budget.stretches]
    def points(shifts):
        return [a + (mid - a + shift * half) % (b - a) for shift, (mid, half) in
                [(sh, st) for sh in shifts for st in stretches]]

    first = points(budget.start_shifts)
    starts = first[:budget.tries]
    more = (first[budget.tries:] + points(budget.more_shifts))[:budget.more_tries]

    # a contour still over the goal after every start is marched from its first starts again with a wider
    # search (beam, pool, children): the fewest arcs of all marches kept (never more than before), and time
    # spent only where the goal is missed
    wide = replace(budget, beam=budget.wide[0], pool=budget.wide[1], children=budget.wide[2])
    jobs = [(start, budget) for start in starts] + [(start, wide) for start in starts[:budget.wide_tries]]

    def march_from(job):
        """The march from one start, or None where it finds no closure: one start's miss, not the contour's
        (issue 43 C: case 43:448's 5th start of 12, 43:250's first, each beside starts that close)."""
        start, job_budget = job
        try:
            return march(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, True, job_budget, start)
        except FitError:
            return None

    best = None

    def met(spline) -> bool:
        """Keep the spline with the fewest blocks (the first of equals); whether the best meets the goal."""
        nonlocal best
        if spline is not None and (best is None or len(spline.elements) < len(best.elements)):
            best = spline
        return best is not None and len(best.elements) <= goal

    # the first start (most contours meet the goal there); then its spline optimised with the goal's count of
    # arcs (camcam.toolpath.arcpolish: a few LP solves instead of the further starts' whole marches); then,
    # only if that finds nothing, rounds of ``mapper.width`` further starts at once (camcam.toolpath.mapper),
    # taken in the same order as one after the other: the same spline for any count of workers.  (Until
    # 2026-12-06 the second start was marched beside the first in a spare child of lower priority; with the
    # optimised chain it was never needed on the 40 cases of run_nc.py --arcs, and its CPU cost the run
    # 2-4 % of its wall time where the first start meets the goal.)
    if met(march_from(jobs[0])):
        return best
    if budget.fewer and best is not None:
        for spline in fewer_arcs(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, best, math.floor(goal)):
            if met(spline):
                return best
    k, n = 1, max(1, mapper.width)
    while k < len(jobs):
        for spline in mapper(march_from, jobs[k:k + n]):
            if met(spline):
                return best
        k += n
    # within ``near_miss`` blocks of the goal after all that: further starts, in the same rounds (the
    # count is a step function of the start, so one more start is one more chance of a block fewer); a
    # contour farther over the goal is left as it is (the starts would cost time and not reach it); one that no
    # start has closed yet is marched from them too, until one closes
    if best is None or len(best.elements) <= goal + budget.near_miss:
        for k in range(0, len(more), n):
            for spline in mapper(march_from, [(start, budget) for start in more[k:k + n]]):
                if met(spline) or (spline is not None and len(best.elements) > goal + budget.near_miss):
                    return best
    if best is None:
        # every start missed: the caller (camcam.toolpath.arcfit) fits this section another way
        raise FitError(f"cannot fit the curve on t ∈ [{a:g}, {b:g}] within {tolerance_mm:g} mm: the march found no "
                       f"printed arc spline from any of its {len(jobs) + len(more)} starts")
    return best
