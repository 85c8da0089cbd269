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
only the farthest survives (:func:`_frontier`; the tangent error is measured
in δ/h, the optimum's joints sit at ±10.4), then the ``beam`` whose next arc
reaches farthest (one-step lookahead).

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

Measured (``benchmarks/run_nc.py --arcs``, the eight disc samples at 0.1–0.0005 mm,
band 0.95·δ): 39 of 40 contour × tolerance cases within 1.2·N_lb + 4 (24
with the biarc closure and one start; 27 with the landing closure alone; 38
before the wider last resort),
1.28–1.57·N_lb at 0.01–0.0005 mm where N_lb is honest (1.48–1.76 at 0.1 mm,
where the +4 matters).
The miss, by one block: disc-translating-flat at 0.0005 mm (40 against
39.8); 32 starts (an earlier sweep) and the 2 wide marches found no spline
with one arc fewer.  The default sample's curve: 9,
16, 25, 32 and 39 blocks at 0.1, 0.01, 0.002, 0.001, 0.0005 mm (9, 16, 26,
33, 40 before the landing closure; 15, 20, –, 40 and 48 with the earlier
one-step-lookahead march split at every break).  The remaining gap to
1.155·N_lb is the transitions into and out of dwells, where κ′ jumps (about
an arc each), and the beam's myopia in smooth stretches (arcs reach
0.85–0.97 of the optimum's length there).  The further starts cost time only
where the first misses the goal: up to ``tries`` marches (≈ 3 s each at
0.001 mm), 6–40 s of fit on the contours that need further starts.  With two workers the second start is
marched beside the first in a spare child of lower priority
(:func:`camcam.forked.spare`), so a contour that misses the goal at its first
start has its second march (mostly) done when the first ends; one that meets
it drops the child, which took only the CPU the run's other processes left
idle (disc-groove at 0.001 mm, whose second start meets the goal: 3.79 →
3.07 s median of 6 alternated runs on a loaded machine; the default sample
2.16 → 2.01 s, within the spread).

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

import functools
import math
from dataclasses import dataclass, replace

import numpy as np

from camcam.errors import InputError
from camcam.forked import parallel_map, resolve, spare
from camcam.toolpath.arcbatch import (MIN_CHORD_STEPS, arc_batch, candidate_deviation, grid_joint, peak_deviation,
                                      printed_element, unit_rows)
from camcam.toolpath.arcclose import BIARC_RATIOS, closing_biarcs, landings, quiet_stretches
from camcam.toolpath.quantizer import Quantizer

__all__ = ["SplineBudget", "ArcSpline", "fit_arc_spline", "g1_sections"]


@dataclass(frozen=True)
class SplineBudget:
    """How the march spends the tolerance δ and how hard it searches.

    The band itself comes from :meth:`~camcam.toolpath.budget.FitBudget.spline_targets`.
    ``samples``: curve samples per candidate arc (the peak refined by a
    parabola); ``table``: rows of the curve table; ``beam``: states kept per
    level after the lookahead, ``pool``: states the frontier keeps before it;
    ``children``: joints kept per ray; ``candidates``: candidate joints per ray
    and pass; ``shortest``: the shortest child as a fraction of the ray's reach;
    ``offsets``: the rays' joint offsets (× the band); ``state_bins``: frontier
    cells (offset, tangent error); ``start_turns``: first-joint tangent errors
    of a closed section (× δ/h); ``wrap_joints``: first joints a closing biarc
    may replace.  A closed section still over ``goal`` after ``tries`` starts
    is marched from its first ``wide_tries`` starts once more with a wider
    search, ``wide`` = (beam, pool, children).
    """

    samples: int = 28
    beam: int = 16
    pool: int = 40
    children: int = 5
    candidates: int = 14
    shortest: float = 0.7
    table: int = 16385
    start_turns: tuple[float, ...] = (0.0, -5.0, 5.0, -10.0, 10.0)
    offsets: tuple[float, ...] = (0.0, -0.3, 0.3, -0.65, 0.65)
    state_bins: tuple[int, int] = (5, 33)
    wrap_joints: int = 6
    start_shifts: tuple[float, ...] = (0.0, -0.12, 0.12, 0.36, -0.6, 0.6, 0.24, -0.36)
    stretches: int = 2
    tries: int = 12
    goal: tuple[float, float] = (1.18, 4.0)
    wide: tuple[int, int, int] = (24, 60, 7)
    wide_tries: int = 2


@dataclass(frozen=True)
class ArcSpline:
    """Printed elements of one G1 section and the curve parameter each starts at."""

    elements: tuple
    starts: tuple[float, ...]


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


class _March:
    """Candidate arcs of one section against the curve, from a dense table of the curve (the Chebyshev copy).

    Joints are table indices: the curve's points and unit normals are
    evaluated once on ``budget.table`` parameters, and a candidate arc's
    curve samples are table rows, so a whole batch of candidates is a few
    array operations.
    """

    def __init__(self, curve, a, b, tol, max_sweep, sag, quantizer: Quantizer, budget: SplineBudget, start=None):
        self.curve, self.a, self.b = curve, a, b
        self.tol, self.max_sweep, self.sag, self.q = tol, max_sweep, sag, quantizer
        self.budget = budget
        self.u = np.linspace(0.0, 1.0, budget.samples)
        self.t = np.linspace(a, b, budget.table)
        self.last = budget.table - 1
        self.stop = self.last - 1  # the end itself is reached only by the closing biarc
        if start is not None:
            # a closed section marched from ``start`` once round and on past it by a third of a turn, where
            # the closing biarc may meet the spline's first joints
            extra = budget.table // 3
            steps = np.arange(budget.table + extra) * ((b - a) / self.last)
            self.t = a + np.mod(start - a + steps, b - a)
            self.stop = self.last + extra - 1
        self.P = curve.evaluate(self.t, 0)
        d1 = unit_rows(curve.evaluate(self.t, 1))
        self.T = d1
        self.N = np.stack([-d1[:, 1], d1[:, 0]], -1)

    def arcs(self, i0, p0, tan0, i1, o1):
        """Candidate arcs from joints (i0, p0, tan0) to joints at rows i1 offset o1 along the normal (N,)."""
        p1 = grid_joint(self.P[i1] + o1[:, None] * self.N[i1], self.N[i1], self.q)
        centre, ccw, is_line, t_end, a0, sweep = arc_batch(p0, tan0, p1, self.q, self.sag)
        rows = np.rint(i0[:, None] + (i1 - i0)[:, None] * self.u[None, :]).astype(int)
        q = self.P[rows]
        dev = peak_deviation(candidate_deviation(q, p0, p1, centre, ccw, is_line, a0, sweep))
        long_enough = np.hypot(*(p1 - p0).T) >= MIN_CHORD_STEPS * self.q.step_mm
        ok = (dev <= self.tol) & (is_line | (sweep <= self.max_sweep)) & (i1 > i0) & long_enough
        return ok, (p1, centre, ccw, is_line, t_end, dev)

    def expand(self, states, offsets) -> None:
        """Fill each state's rays (feasible next joints) and reach; all candidates of all states as one batch a pass.

        A state is tried along rays: next joints on the curve and offset from it
        by ``offsets`` × the band (an off-curve joint is how a tangent error is
        undone, e.g. on a dwell circle).  Along each ray, candidates are spread
        over [0.4, 1.8] × the state's last step; a ray whose candidates are all
        feasible widens, one with none narrows, until its farthest feasible
        joint is bracketed; one more pass refines between it and the next
        infeasible candidate.
        """
        K = self.budget.candidates
        stop = self.stop
        grid = np.linspace(0.4, 1.8, K)
        rays = [_Ray(s, o * self.tol, max(s.h, 2.0)) for s in states for o in offsets]
        for s in states:
            s.rays = [r for r in rays if r.state is s]
        todo = rays
        brackets = []
        for _ in range(24):
            if not todo:
                break
            i0 = np.repeat([r.state.i for r in todo], K)
            i1 = np.minimum(i0 + np.rint(np.outer([r.h for r in todo], grid).ravel()).astype(int), stop)
            i1 = np.maximum(i1, np.minimum(i0 + 1, stop))
            ok, data = self.arcs(i0, np.repeat([r.state.p for r in todo], K, axis=0),
                                 np.repeat([r.state.tan for r in todo], K, axis=0), i1,
                                 np.repeat([r.offset for r in todo], K))
            again = []
            # the verdicts as Python lists: a ray's bookkeeping is a few list operations, not numpy calls
            for k, (ray, rows, ii) in enumerate(zip(todo, ok.reshape(len(todo), K).tolist(),
                                                    i1.reshape(len(todo), K).tolist())):
                if not any(rows):
                    ray.h *= 0.3
                    if ray.h >= 1.0:
                        again.append(ray)
                    continue
                if all(rows) and ii[-1] < stop:
                    ray.h *= 2.0
                    again.append(ray)
                    continue
                hits = [j for j, good in enumerate(rows) if good]
                ray.feasible.extend((ii[j], data, k * K + j) for j in hits)  # the arc: row k·K + j of the batch
                jmax = hits[-1]
                if jmax + 1 < K and ii[jmax + 1] > ii[jmax] + 1:
                    brackets.append((ray, ii[jmax], ii[jmax + 1]))
            todo = again
        if brackets:
            # K rows strictly between each bracket's ends, as np.unique(np.rint(np.linspace(lo, hi, K + 2)[1:-1]))
            # per bracket gives them: linspace takes arrays of ends (elementwise the same arithmetic; no
            # bracket is empty, hi ≥ lo + 2), and a row's rounded values never fall, so its unique values
            # are the first of each run
            lo = np.array([b[1] for b in brackets])
            hi = np.array([b[2] for b in brackets])
            ii = np.rint(np.linspace(lo, hi, K + 2, axis=1)[:, 1:-1]).astype(int)
            take = np.ones(ii.shape, bool)
            take[:, 1:] = ii[:, 1:] != ii[:, :-1]
            take &= (ii > lo[:, None]) & (ii < hi[:, None])
            owners = [ray for (ray, _, _), n in zip(brackets, take.sum(axis=1).tolist()) for _ in range(n)]
            i1 = ii[take]
            ok, data = self.arcs(np.array([r.state.i for r in owners]), np.array([r.state.p for r in owners]),
                                 np.array([r.state.tan for r in owners]), i1, np.array([r.offset for r in owners]))
            for j in np.flatnonzero(ok).tolist():
                owners[j].feasible.append((int(i1[j]), data, j))
        for s in states:
            for r in s.rays:
                r.feasible.sort(key=lambda c: c[0])
            s.reach = max((r.feasible[-1][0] for r in s.rays if r.feasible), default=s.i)


class _State:
    """A joint of a partial spline: table row, printed point, tangent, last step (rows), parent, element to it.

    ``arc`` holds the element's data (start, end, centre, ccw, is_line); the
    element itself is built only for the states the spline keeps.
    """

    __slots__ = ("i", "p", "tan", "h", "parent", "arc", "root", "first", "rays", "reach")

    def __init__(self, i, p, tan, h, parent, arc):
        self.i, self.p, self.tan, self.h, self.parent, self.arc = int(i), p, tan, h, parent, arc
        self.root = self if parent is None else parent.root
        self.first = None if parent is None else (self if parent.parent is None else parent.first)
        self.rays: list = []
        self.reach = self.i

    @property
    def element(self):
        return printed_element(*self.arc)


class _Ray:
    """Next joints of a state at one normal offset: the step guess (rows) and the feasible (row, batch data, index)."""

    __slots__ = ("state", "offset", "h", "feasible")

    def __init__(self, state, offset, h):
        self.state, self.offset, self.h = state, offset, h
        self.feasible: list = []


@functools.lru_cache(maxsize=None)
def _spread(n: int, k: int) -> tuple[int, ...]:
    """At most ``k`` indices spread evenly over ``range(n)``, the last first, each once."""
    return tuple(int(i) for i in np.unique(np.round(np.linspace(n - 1, 0, k)).astype(int)))


def _start_states(m: _March, closed: bool, budget: SplineBudget) -> list:
    """The first joints: the curve's start with its exact tangent; for a closed section also offset and turned ones.

    A closed section closes onto its own first joint, so that joint's offset
    and tangent are free: starting in the optimal pattern's state saves the
    run-in of arcs from the exact tangent.
    """
    h0 = max(2.0, m.last / 12.0)
    p = m.q.snap(m.P[0])
    states = [_State(0, p, m.T[0], h0, None, None)]
    if not closed:
        return states
    # tangent errors in units of δ/h (h: a first guess of an arc's length); the optimum's joints turn ≈ 10.4 δ/h
    arc_len = float(np.hypot(*np.diff(m.P[: max(3, int(h0)) + 1], axis=0).T).sum())
    unit = m.tol / max(arc_len, 1e-12)
    for o in budget.offsets:
        for f in budget.start_turns:
            if o == 0.0 and f == 0.0:
                continue
            ang = f * unit
            c, s = math.cos(ang), math.sin(ang)
            tan = np.array([c * m.T[0, 0] - s * m.T[0, 1], s * m.T[0, 0] + c * m.T[0, 1]])
            states.append(_State(0, m.q.snap(m.P[0] + o * m.tol * m.N[0]), tan, h0, None, None))
    return states


#: Tangent errors the frontier tells apart, in units of δ/h (the optimum sits at ±10.4).
TURN_RANGE = 16.0


def _frontier(m: _March, children: list, W: int, bins: tuple[int, int]) -> list:
    """The states worth keeping after k arcs: per (offset, tangent error) cell the one that got farthest.

    A joint's future depends on where it is (row), how far it sits off the
    curve and how far its tangent turns from the curve's; two joints in the
    same cell behave alike, so only the farthest of each survives (the
    reachable region after k arcs, sampled as in Maier's method).  The
    tangent error is scaled by δ/h: the optimal pattern's joints turn by
    κ′h²/12 = (124.7/12)·δ/h ≈ 10.4·δ/h, so the cells span ±``TURN_RANGE``.
    """
    rows = np.array([c.i for c in children])
    p = np.array([c.p for c in children])
    tan = np.array([c.tan for c in children])
    off = np.einsum("ij,ij->i", p - m.P[rows], m.N[rows]) / m.tol
    turn = np.arctan2(m.T[rows, 0] * tan[:, 1] - m.T[rows, 1] * tan[:, 0], np.einsum("ij,ij->i", m.T[rows], tan))
    d = p - np.array([c.parent.p for c in children])
    step = np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-12)  # each child's last chord
    turn = turn * step / m.tol
    lim = TURN_RANGE
    bo = np.clip(np.rint((off + 1.0) / 2.0 * (bins[0] - 1)), 0, bins[0] - 1).astype(int)
    bt = np.clip(np.rint((np.clip(turn, -lim, lim) + lim) / (2 * lim) * (bins[1] - 1)), 0, bins[1] - 1).astype(int)
    best: dict = {}
    for k in np.argsort(-rows, kind="stable"):
        key = (bo[k], bt[k])
        if key not in best:
            best[key] = children[k]
    kept = sorted(best.values(), key=lambda c: -c.i)
    return kept[:W]


def fit_arc_spline(curve, a: float, b: float, tolerance_mm: float, *, quantizer: Quantizer, max_sweep: float,
                   sag: float, closed: bool = False, budget: SplineBudget = SplineBudget(),
                   workers: int = 1, lower_bound: float | None = None) -> ArcSpline:
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
    workers : int
        Processes the further starts of a closed section are marched in, that
        many at a time (:func:`camcam.forked.parallel_map`); taken in the same
        order as one by one, so the spline is the same for any count.
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
        return _march(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, False, budget, None)
    stretches, integral = quiet_stretches(curve, a, b)
    n_lb = integral / np.cbrt(192.0 * tolerance_mm) if lower_bound is None else lower_bound
    goal = budget.goal[0] * n_lb + budget.goal[1]
    # the longest stretch first; then the others at least half as long, each start shift in turn
    stretches = [st for st in stretches if st[1] >= 0.5 * stretches[0][1]][:budget.stretches]
    starts = [a + (mid - a + shift * half) % (b - a)
              for shift, (mid, half) in [(sh, st) for sh in budget.start_shifts for st in stretches][:budget.tries]]

    # a contour still over the goal after every start is marched from its first starts again with a wider
    # search (beam, pool, children): the fewest arcs of all marches kept (never more than before), and time
    # spent only where the goal is missed
    wide = replace(budget, beam=budget.wide[0], pool=budget.wide[1], children=budget.wide[2])
    jobs = [(start, budget) for start in starts] + [(start, wide) for start in starts[:budget.wide_tries]]

    def march_from(job):
        start, job_budget = job
        return _march(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, True, job_budget, start)

    best = None

    def met(spline) -> bool:
        """Keep the spline with the fewest blocks (the first of equals); whether the best meets the goal."""
        nonlocal best
        if best is None or len(spline.elements) < len(best.elements):
            best = spline
        return len(best.elements) <= goal

    # the first start here (most contours meet the goal there), the second meanwhile in a spare child of lower
    # priority (camcam.forked.spare: it takes a core only when the run's other processes leave one idle, and
    # is dropped when the first meets the goal); then rounds of ``workers`` starts at once
    # (camcam.forked.parallel_map).  The marches are taken in the same order as one after the other: the
    # same spline for any count of workers
    second = spare(march_from, jobs[1]) if workers > 1 and len(jobs) > 1 else None
    try:
        if met(march_from(jobs[0])):
            return best
        if second is not None and met(resolve(second)):
            return best
    finally:
        if second is not None:
            second.cancel()  # nothing happens to a collected result
    k, n = (1 if second is None else 2), max(1, workers)
    while k < len(jobs):
        for spline in parallel_map(march_from, jobs[k:k + n], n):
            if met(spline):
                return best
        k += n
    return best


def _march(curve, a, b, tol, quantizer, max_sweep, sag, closed, budget, start) -> ArcSpline:
    """One beam march over [a, b] (closed: from ``start`` once round and closing onto its own first joints)."""
    m = _March(curve, a, b, tol, max_sweep, sag, quantizer, budget, start)
    W = budget.beam
    level = _start_states(m, closed, budget)
    m.expand(level, budget.offsets)
    end_p, end_t = m.q.snap(m.P[-1]), m.T[-1]
    best, best_level = None, None
    for level_no in range(8 * m.last):
        # 1. closing biarcs; a closed section looks two levels further (a later closure may skip more arcs)
        for st in level:
            targets = [(end_p, end_t, m.last, 0)]
            if closed:
                # onto the start (row ``last`` once round), or on past it to the j-th joint: the biarc then
                # replaces the first j arcs
                chain = []
                c = st
                while c.parent is not None:
                    chain.append(c)
                    c = c.parent
                chain.reverse()  # chain[j - 1]: the j-th joint
                targets = [(st.root.p, st.root.tan, m.last, 0)]
                for j in range(1, min(budget.wrap_joints, len(chain) - 1) + 1):
                    jt = chain[j - 1]
                    targets.append((jt.p, jt.tan, jt.i + m.last, j))
            cap = min(st.i + 2.0 * (st.reach - st.i) + 1, len(m.P) - 1)  # the farthest row a closure may end on
            if closed:
                for j, dev, e1, e2 in landings(m, st, chain, min(budget.wrap_joints, len(chain) - 1), cap):
                    total = level_no + 2 - j  # one closing arc; arcs 1 … j−1 drop out, the j-th is lengthened
                    if best is None or (total, dev) < (best[5], best[0]):
                        best, best_level = (dev, st, e1, e2, j, total), level_no
            for p1, t1, row, saved in targets:
                if not st.i < row <= cap:
                    continue
                total = level_no + 2 - saved
                if best is not None and total > best[5]:  # more arcs than the best closure: cannot win
                    continue
                for dev, e1, e2 in closing_biarcs(m, st, p1, t1, BIARC_RATIOS, row):
                    if best is None or (total, dev) < (best[5], best[0]):
                        best, best_level = (dev, st, e1, e2, saved, total), level_no
        if best is not None and (not closed or level_no - best_level >= 2):
            break
        # 2. children: along each ray of each state, the farthest joint and some shorter ones
        children = []
        for st in level:
            for ray in st.rays:
                if not ray.feasible:
                    continue
                reach = ray.feasible[-1][0]
                near = [c for c in ray.feasible if c[0] >= st.i + budget.shortest * (reach - st.i)]
                for k in _spread(len(near), budget.children):
                    i1, data, j = near[k]
                    p1, centre, ccw, is_line, t_end = (x[j] for x in data[:5])
                    children.append(_State(i1, p1, t_end, i1 - st.i, st, (st.p, p1, centre, ccw, is_line)))
        if not children:
            break
        # 3. keep the farthest child of each joint state (normal offset, tangent error), then the farthest W
        level = _frontier(m, children, budget.pool, budget.state_bins)
        m.expand(level, budget.offsets)
        level.sort(key=lambda c: -c.reach)  # one-step lookahead: the farthest next reach first
        level = level[:W]
    if best is None:
        raise InputError(f"cannot fit the curve on t ∈ [{a:g}, {b:g}] within {tol:g} mm")
    _, st, e1, e2, saved, _ = best
    elems, starts = [e2, e1], [st.i, st.i]  # the closing biarc's second arc counts with the first
    while st.parent is not None:
        elems.append(st.element)
        starts.append(st.parent.i)
        st = st.parent
    elems.reverse()
    starts.reverse()
    if saved:  # the biarc ends at the saved-th joint: drop the arcs before it, start with the biarc's end
        elems, starts = elems[saved:], starts[saved:]
        elems = [elems[-1]] + elems[:-1]
        starts = [starts[-1]] + starts[:-1]
    return ArcSpline(tuple(elems), tuple(float(m.t[i]) for i in starts))
