"""The beam march of :mod:`camcam.toolpath.arcspline`: one near-minimal printed G1 arc spline from one start.

:func:`march` searches the joint sequences breadth-first: every state after k
arcs is expanded to candidate next joints along rays at several offsets
across the band (:class:`_March`, all candidates of a pass measured as one set
of numpy arrays), the states are thinned per cell of (joint offset, tangent
error) like a reachable region (:func:`_frontier`), the ``beam`` reaching
farthest are kept, and a closing biarc or a landing arc ends the spline.  How
hard it searches is a :class:`SplineBudget`; the method, its literature and
its measured counts are in :mod:`camcam.toolpath.arcspline`, which chooses the
starts and keeps the best march.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import FitError
from camcam.toolpath.arcbatch import (MIN_CHORD_STEPS, arc_batch, candidate_deviation, grid_joint, peak_deviation,
                                      printed_element, unit_rows)
from camcam.toolpath.arcclose import BIARC_RATIOS, closing_biarcs, landings
from camcam.toolpath.quantizer import Quantizer

__all__ = ["SplineBudget", "ArcSpline", "march", "TURN_RANGE"]


@dataclass(frozen=True, kw_only=True)
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
    search, ``wide`` = (beam, pool, children); one still over it by at most
    ``near_miss`` blocks then from up to ``more_tries`` further starts (the
    shifts left of ``start_shifts``, then ``more_shifts``).  With ``fewer``,
    a closed section over the goal after its first start is first optimised
    with the goal's count of arcs (:func:`camcam.toolpath.arcpolish.fewer_arcs`);
    the further starts are marched only if that finds nothing.  With ``seeded``, a closed section of a
    smooth curve is first fitted by a chain seeded from the optimal pattern's arc density, with up to
    ``seed_tries`` counts (:func:`camcam.toolpath.arcseed.seeded_chain`), and marched only if that finds
    nothing within the goal.
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
    # the rest of the 0.08 grid on (−1, 1), each the farthest from every shift before it (ties: the
    # smaller |shift|, then the positive): chosen by that rule alone, not by any march's count
    more_shifts: tuple[float, ...] = (0.96, -0.96, 0.8, -0.8, -0.24, 0.48, -0.48, 0.72, -0.72, 0.88, -0.88, 0.08,
                                      -0.08, 0.16, -0.16, 0.32, -0.32, 0.4, -0.4, 0.56, -0.56, 0.64, -0.64)
    near_miss: float = 1.0
    more_tries: int = 50
    fewer: bool = True
    seeded: bool = True
    seed_tries: int = 3


@dataclass(frozen=True)
class ArcSpline:
    """Printed elements of one G1 section and the curve parameter each starts at."""

    elements: tuple
    starts: tuple[float, ...]


class _March:
    """Candidate arcs of one section against the curve, from a dense table of the curve (the Chebyshev copy).

    Joints are table indices: the curve's points and unit normals are
    evaluated once on ``budget.table`` parameters, and a candidate arc's
    curve samples are table rows, so a whole batch of candidates is a few
    array operations.
    """

    def __init__(self, curve, a, b, tolerance_mm, max_sweep, sag, quantizer: Quantizer, budget: SplineBudget, start=None):
        self.curve, self.a, self.b = curve, a, b
        self.tolerance_mm, self.max_sweep, self.sag, self.q = tolerance_mm, max_sweep, sag, quantizer
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
        ok = (dev <= self.tolerance_mm) & (is_line | (sweep <= self.max_sweep)) & (i1 > i0) & long_enough
        return ok, (p1, centre, ccw, is_line, t_end, dev)

    def expand(self, states, offsets, append: bool = False) -> None:
        """Fill each state's rays (feasible next joints) and reach; all candidates of all states as one batch a pass.

        A state is tried along rays: next joints on the curve and offset from it
        by ``offsets`` × the band (an off-curve joint is how a tangent error is
        undone, e.g. on a dwell circle).  Along each ray, candidates are spread
        over [0.4, 1.8] × the state's last step; a ray whose candidates are all
        feasible widens, one with none narrows, until its farthest feasible
        joint is bracketed; one more pass refines between it and the next
        infeasible candidate.  Each ray's joints are its own (the same for any
        other rays in the batch), so with ``append`` the rays at ``offsets`` are
        added to a state's earlier ones, and its reach is then over all of them.
        """
        K = self.budget.candidates
        stop = self.stop
        grid = np.linspace(0.4, 1.8, K)
        rays = [_Ray(s, o * self.tolerance_mm, max(s.h, 2.0)) for s in states for o in offsets]
        for s in states:
            s.rays = (s.rays if append else []) + [r for r in rays if r.state is s]
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
    unit = m.tolerance_mm / max(arc_len, 1e-12)
    for o in budget.offsets:
        for f in budget.start_turns:
            if o == 0.0 and f == 0.0:
                continue
            ang = f * unit
            c, s = math.cos(ang), math.sin(ang)
            tan = np.array([c * m.T[0, 0] - s * m.T[0, 1], s * m.T[0, 0] + c * m.T[0, 1]])
            states.append(_State(0, m.q.snap(m.P[0] + o * m.tolerance_mm * m.N[0]), tan, h0, None, None))
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
    off = np.einsum("ij,ij->i", p - m.P[rows], m.N[rows]) / m.tolerance_mm
    turn = np.arctan2(m.T[rows, 0] * tan[:, 1] - m.T[rows, 1] * tan[:, 0], np.einsum("ij,ij->i", m.T[rows], tan))
    d = p - np.array([c.parent.p for c in children])
    step = np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-12)  # each child's last chord
    turn = turn * step / m.tolerance_mm
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


def march(curve, a, b, tolerance_mm, quantizer, max_sweep, sag, closed, budget, start) -> ArcSpline:
    """One beam march over [a, b] (closed: from ``start`` once round and closing onto its own first joints)."""
    m = _March(curve, a, b, tolerance_mm, max_sweep, sag, quantizer, budget, start)
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
        # 3b. one-step lookahead: the pool ranked by the reach of each state's on-curve ray alone (the first
        # offset), the farthest W kept, and only they get their off-curve rays (the children come from all
        # of a kept state's rays; the others' off-curve rays were never used but to rank)
        m.expand(level, budget.offsets[:1])
        level.sort(key=lambda c: -c.reach)
        level = level[:W]
        m.expand(level, budget.offsets[1:], append=True)
    if best is None:
        # the march's own limit on a valid curve and tolerance (the spec checks the tolerance against the post's
        # decimals), so a fault of camcam's: exit 1, as README's exit statuses put fit failures
        raise FitError(f"cannot fit the curve on t ∈ [{a:g}, {b:g}] within {tolerance_mm:g} mm: the march found no printed "
                       f"arc spline")
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
