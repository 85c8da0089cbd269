"""Two-sided deviation between a printed path and the exact curve.

* path → curve: points every ``h`` mm along each printed line/arc; each point's
  distance to the curve comes from its closest point, found by Newton iteration
  on (P(t) − q)·P′(t) = 0 seeded from the nearest point of a dense sample.
* curve → path: curve points every ≤ ``h`` mm of arc length; each point's exact
  distance to the nearest printed element (the element of its nearest path
  sample and that element's neighbours).

Between two samples h apart a distance function g can exceed the larger of
its two sampled values by at most h²/8 · max|g″| there, with |g″| ≤ |κ_curve| +
|κ_path| near them (g is smooth where it is small).  The sample step h is set
from the largest curvatures of either, so that bound is at most the caller's
``margin_mm``; the bound is then taken interval by interval, from the printed
element's own curvature and the curve's largest on the pilot grid about the
interval's feet (one pilot step either side), and added to that interval's
larger sample: ``max_deviation_mm`` is the largest such sum, and bounds the true
two-sided (Hausdorff) deviation.  Taken over the whole curve instead, the bound
let one sharp place (a flat-faced profile at its cusp limit, radius of
curvature 0.0066 mm, where the memory cap widens the step) add 3.9e-4 mm
everywhere: campaign case 43:15's part outline, 0.004664 mm from the profile,
measured 0.005058 mm, over its 0.0049 mm tolerance.

Where the memory cap (:data:`MAX_SAMPLES`) leaves an interval's term over the margin, that interval is
sampled again at the step the margin needs there (:data:`MAX_REFINED` points at most): campaign case
45:63's face groove, cut at the base radius its undercut advice named, has a flank of radius 6.6e-6 mm at
0°; the capped step (1.2e-3 mm, where 7e-5 mm was needed) bounded its part outline's between-sample
deviation by 0.0289 mm about a sampled 0.0045 mm, and the job failed a 0.0052 mm tolerance that its
material check (0.0045 mm) and every contour (0.0045 mm) held.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from camcam.geometry.curve import PlanarCurve, curvature, derivatives, speed
from camcam.toolpath.elements import Arc, element_distance, element_points

__all__ = ["Deviation", "closest_params", "measure_deviation"]

#: The most path samples of one measurement: the step is widened to the path's length over this (memory).
MAX_SAMPLES = 400_000
#: The most samples the intervals over the margin are measured again with (path and curve side each).
MAX_REFINED = 400_000


@dataclass(frozen=True, kw_only=True)
class Deviation:
    """Two-sided deviation of a path from a curve (mm); ``max_deviation_mm`` includes ``margin_mm``."""

    max_deviation_mm: float
    path_to_curve_mm: float
    curve_to_path_mm: float
    margin_mm: float
    worst_point: tuple[float, float]


def _dense(curve: PlanarCurve, lo: float, hi: float, spacing: float, min_n: int = 64):
    """Parameters on [lo, hi] with arc-length steps ≤ ``spacing`` (from |P′| on a pilot grid)."""
    pilot = np.linspace(lo, hi, 513)
    v = speed(curve, pilot)
    vmax = float(v.max())
    n = max(min_n, int(np.ceil((hi - lo) * vmax * 1.05 / spacing)) + 1)
    return np.linspace(lo, hi, n)


class _PilotMax:
    """The largest of ``values`` (the pilot grid's, n even parameters on [lo, hi]) about a parameter interval.

    ``self(ta, tb)`` (arrays alike) is the largest value at the pilot points from one step below min(ta, tb) to
    one step above max(ta, tb), by a sparse table (two lookups an interval).  An interval longer than half
    of [lo, hi] (feet on either side of a closed curve's seam) takes the largest of all.

    Examples
    --------
    >>> m = _PilotMax(np.array([0.0, 1.0, 5.0, 2.0, 0.0, 0.0, 0.0, 3.0]), 0.0, 7.0)
    >>> m(np.array([4.2, 0.0, 6.5]), np.array([4.8, 0.0, 0.5])).tolist()
    [2.0, 1.0, 5.0]
    """

    def __init__(self, values: np.ndarray, lo: float, hi: float):
        v = np.asarray(values, float)
        self.lo, self.step, self.n = lo, (hi - lo) / (len(v) - 1), len(v)
        levels = [v]
        w = 1
        while 2 * w <= len(v):
            prev = levels[-1]
            levels.append(np.maximum(prev[:-w], prev[w:]))
            w *= 2
        self.table = np.full((len(levels), len(v)), -np.inf)
        for k, row in enumerate(levels):
            self.table[k, :len(row)] = row

    def __call__(self, ta, tb) -> np.ndarray:
        t0, t1 = np.minimum(ta, tb), np.maximum(ta, tb)
        i = np.clip(np.floor((t0 - self.lo) / self.step).astype(np.intp) - 1, 0, self.n - 1)
        j = np.clip(np.ceil((t1 - self.lo) / self.step).astype(np.intp) + 1, 0, self.n - 1)
        wide = (t1 - t0) > 0.5 * self.step * (self.n - 1)
        i, j = np.where(wide, 0, i), np.where(wide, self.n - 1, j)
        k = np.floor(np.log2(j - i + 1)).astype(np.intp)
        return np.maximum(self.table[k, i], self.table[k, j - (1 << k) + 1])


def _nearest(points: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Index into ``points`` (m, 2) of the nearest point to each of ``q`` (n, 2), (n,) ints.

    Through shapely's STRtree rather than scipy.spatial's k-d tree: the run's main process measures
    deviations but otherwise needs no scipy, and scipy.spatial's import (0.2 s wall, 0.3 CPU s) was
    more than these queries ever take (a few ms for 2 000 × 2 000 points).  A tie (two points
    exactly as near) may resolve to either; both are seeds of the same Newton iteration.
    """
    tree = shapely.STRtree(shapely.points(points))
    (rows, found) = tree.query_nearest(shapely.points(q), all_matches=False)
    if len(rows) != len(q):  # a point with no nearest: a NaN coordinate, never a silent index
        raise ValueError(f"deviation: {len(q) - len(rows)} of {len(q)} points have no nearest point (NaN coordinates?)")
    k = np.empty(len(q), dtype=np.intp)
    k[rows] = found
    return k


def closest_params(curve: PlanarCurve, q, lo: float, hi: float, seeds_t=None) -> tuple[np.ndarray, np.ndarray]:
    """Closest curve parameters in [lo, hi] to points ``q`` (n, 2) and their distances.

    Examples
    --------
    >>> import numpy as np
    >>> from camcam.geometry.curve import FunctionCurve
    >>> def circ(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return 2.0 * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], axis=-1)
    >>> C = FunctionCurve(circ, 0.0, 2 * np.pi, closed=True)
    >>> t, d = closest_params(C, np.array([[3.0, 3.0]]), 0.0, 2 * np.pi)
    >>> round(float(t[0]), 9), round(float(d[0]), 9)
    (0.785398163, 2.242640687)
    """
    q = np.atleast_2d(np.asarray(q, float))
    if seeds_t is None:
        seeds_t = np.linspace(lo, hi, 2049)
    k = _nearest(curve.evaluate(seeds_t, 0), q)
    t = seeds_t[k].astype(float)
    step = (hi - lo) / max(len(seeds_t) - 1, 1)
    # a closed curve taken whole has no ends: Newton may step across its seam (t_end ≡ t_start)
    seam = bool(getattr(curve, "closed", False)) and lo <= curve.t_start and hi >= curve.t_end
    # eight Newton steps, each point on its own: a point the step leaves where it was (to the bit) is a fixed
    # point of its step and stays there, so it is not evaluated again (on disc-oscillating-roller's contour at
    # 0.001 mm, 2 367 of 6 676 points still move at the third step and 812 at the eighth, an ulp to and fro)
    active = np.arange(len(t))
    for _ in range(8):
        ta = t[active]
        p, d1, d2 = derivatives(curve, ta, 2, first=0)  # one jet evaluation for all three
        r = p - q[active]
        f = np.einsum("ij,ij->i", r, d1)
        fp = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", r, d2)
        dt = np.where(fp > 0, -f / np.where(fp > 0, fp, 1.0), 0.0)
        tn = ta + np.clip(dt, -step, step)
        tn = lo + np.mod(tn - lo, hi - lo) if seam else np.clip(tn, lo, hi)
        t[active] = tn
        active = active[tn != ta]
        if not len(active):
            break
    d = np.hypot(*(curve.evaluate(t, 0) - q).T)
    return t, d


def _longest_run(flags: np.ndarray) -> int:
    """The longest run of consecutive True values in ``flags``, cyclically (a closed path's last and first).

    Examples
    --------
    >>> _longest_run(np.array([False, True, True, False, True]))
    2
    >>> _longest_run(np.array([True, False, True]))
    2
    """
    if flags.all():
        return len(flags)
    best = run = 0
    start = int(np.argmin(flags))  # start at a False: runs across the wrap are counted whole
    for f in np.roll(flags, -start):
        run = run + 1 if f else 0
        best = max(best, run)
    return best


def _to_path(cp: np.ndarray, pts: np.ndarray, idx: np.ndarray, elements, reach: int):
    """Each curve point's exact distance to the path: to the element of its nearest path sample and the
    ``reach`` elements either side of it; (distances, that element's index)."""
    eidx = idx[_nearest(pts, cp)]
    d_cp = np.full(len(cp), np.inf)
    n_el = len(elements)
    for off in range(-reach, reach + 1):
        cand = eidx + off
        if not (off == 0):
            cand = np.mod(cand, n_el)
        # the points of each candidate element, in their own order (a stable sort: the same rows as a mask of
        # cand == j gives, without a pass over all points per element)
        order = np.argsort(cand, kind="stable")
        sorted_cand = cand[order]
        cuts = np.flatnonzero(np.diff(sorted_cand)) + 1
        for rows in (np.split(order, cuts) if len(order) else ()):
            d_cp[rows] = np.minimum(d_cp[rows], element_distance(elements[cand[rows[0]]], cp[rows]))
    return d_cp, eidx


def _worst(b: np.ndarray, points: np.ndarray, d: np.ndarray, m: np.ndarray):
    """(bound, worst point, its between-sample term) of the intervals with bounds ``b`` between the samples
    ``points`` (distances ``d``, terms ``m``): the interval of the largest bound, at its farther sample."""
    if not len(b):
        return -np.inf, None, 0.0
    i = int(np.argmax(b))
    j = i if d[i] >= d[i + 1] else i + 1
    return float(b[i]), points[j], float(m[i])


def _k_path_near(eidx: np.ndarray, k_el: np.ndarray, reach: int) -> np.ndarray:
    """The largest path curvature among each point's nearest element and the ``reach`` either side of it."""
    out = np.zeros(len(eidx))
    for off in range(-reach, reach + 1):
        out = np.maximum(out, k_el[np.mod(eidx + off, len(k_el))])
    return out


def _parts(m: np.ndarray, margin_mm: float) -> np.ndarray:
    """How many equal parts bring each interval's between-sample term ``m`` within ``margin_mm`` (the term falls
    with the step's square), scaled down to :data:`MAX_REFINED` in all (the bound stays a bound, only looser)."""
    parts = np.ceil(np.sqrt(m / margin_mm)).astype(int)
    if parts.sum() > MAX_REFINED:
        parts = np.maximum(1, (parts * (MAX_REFINED / parts.sum())).astype(int))
    return parts


def _refined_path(curve, elements, idx, same, m_pc, t_pc, k_el, k_curve_near, lo, hi, margin_mm):
    """The path-side intervals over ``margin_mm``, each cut into as many equal steps of its element as bring its
    term within the margin (the term falls with the step's square), measured and bounded anew: (those intervals,
    points, distances, bounds, terms), −inf across intervals.  Each part's closest curve point is sought from
    the intervals' feet's (a local minimum of the distance: never less than the closest, so the bound holds)."""
    over = np.flatnonzero(same & (m_pc > margin_mm))
    parts = _parts(m_pc[over], margin_mm)
    first = np.searchsorted(idx, idx[over])  # each interval's element's first sample
    count = np.bincount(idx, minlength=len(elements))[idx[over]]
    q, owner = [], []
    for k, (j, n) in enumerate(zip(over, parts)):
        u0 = (j - first[k]) / (count[k] - 1)
        q.append(elements[idx[j]].at(np.linspace(u0, u0 + 1.0 / (count[k] - 1), n + 1)))
        owner.append(np.full(n + 1, k))
    q = np.concatenate(q) if q else np.empty((0, 2))
    owner = np.concatenate(owner) if owner else np.empty(0, int)
    if not len(q):
        return over, q, np.empty(0), np.empty(0), np.empty(0)
    t_q, d_q = closest_params(curve, q, lo, hi, np.unique(np.concatenate([t_pc[over], t_pc[over + 1]])))
    step = np.array([elements[idx[j]].length / (c - 1) / n for j, c, n in zip(over, count, parts)])[owner[:-1]]
    m_q = step**2 / 8.0 * (k_el[idx[over]][owner[:-1]] + 1.05 * k_curve_near(t_q[:-1], t_q[1:]))
    b_q = np.where(owner[1:] == owner[:-1], np.maximum(d_q[:-1], d_q[1:]) + m_q, -np.inf)
    return over, q, d_q, b_q, m_q


def _refined_curve(curve, seeds, h, m_cp, k_curve_near, eidx, elements, k_el, reach, margin_mm):
    """The curve-side intervals over ``margin_mm`` (arc-length steps of at most ``h``), each cut into as many
    equal parameter steps as bring its term within the margin (the term falls with the step's square),
    measured and bounded anew: (those intervals, points, distances, bounds, terms), −inf across intervals.
    Each part's distance is to the nearest of the elements about its interval's feet's nearest (``eidx``,
    ``reach`` either side and one more): never less than the path's, so the bound holds."""
    over = np.flatnonzero(m_cp > margin_mm)
    parts = _parts(m_cp[over], margin_mm)
    if not len(over):
        return over, np.empty((0, 2)), np.empty(0), np.empty(0), np.empty(0)
    t = np.concatenate([np.linspace(seeds[i], seeds[i + 1], n + 1) for i, n in zip(over, parts)])
    owner = np.repeat(np.arange(len(over)), parts + 1)
    c = curve.evaluate(t, 0)
    n_el = len(elements)
    d_c = np.full(len(c), np.inf)
    k_path = np.zeros(len(c))
    for k, i in enumerate(over):
        rows = np.flatnonzero(owner == k)
        near = {int(np.mod(e + off, n_el)) for e in (eidx[i], eidx[i + 1]) for off in range(-reach - 1, reach + 2)}
        for e in near:
            d_c[rows] = np.minimum(d_c[rows], element_distance(elements[e], c[rows]))
            k_path[rows] = np.maximum(k_path[rows], k_el[e])
    step = (h / parts)[owner[:-1]]  # equal parameter parts of an interval of arc length ≤ h: each ≤ h / parts
    m_c = step**2 / 8.0 * (1.05 * k_curve_near(t[:-1], t[1:]) + np.maximum(k_path[:-1], k_path[1:]))
    b_c = np.where(owner[1:] == owner[:-1], np.maximum(d_c[:-1], d_c[1:]) + m_c, -np.inf)
    return over, c, d_c, b_c, m_c


def measure_deviation(curve: PlanarCurve, elements, lo: float | None = None, hi: float | None = None,
                      margin_mm: float = 1e-5) -> Deviation:
    """Two-sided deviation of ``elements`` (the printed path) from ``curve`` on [lo, hi].

    The sample spacing is chosen so that the between-sample bound stays at or
    below ``margin_mm``.
    """
    lo = curve.t_start if lo is None else lo
    hi = curve.t_end if hi is None else hi
    pilot = np.linspace(lo, hi, 2049)
    k_pilot = np.abs(curvature(curve, pilot))
    k_curve = float(k_pilot.max())
    k_path = max((1.0 / e.radius for e in elements if isinstance(e, Arc)), default=0.0)
    kk = 1.05 * k_curve + k_path + 1e-12
    h = float(np.sqrt(8.0 * margin_mm / kk))
    total = sum(e.length for e in elements)
    h = max(h, total / MAX_SAMPLES)  # memory cap; the bound below is taken with the h used (and refined)
    # path -> curve
    pts, idx = element_points(elements, h)
    seeds = _dense(curve, lo, hi, h)
    t_pc, d_pc = closest_params(curve, pts, lo, hi, seeds)
    # curve -> path
    cp = curve.evaluate(seeds, 0)
    n_el = len(elements)
    # the nearest sample's element and its neighbours; past elements shorter than the sample step too: a
    # curve point nearest to the sampled end of one element may lie closest to the element after a tiny one
    # between them (a part outline's corner arc at a joint the printing left unsmooth: a false 0.0125 mm
    # where the outline was 0.0015 mm away, campaign case 43:225)
    reach = 1 + _longest_run(np.array([e.length for e in elements]) < h)
    d_cp, eidx = _to_path(cp, pts, idx, elements, reach)
    # the between-sample bound interval by interval (module docstring)
    k_el = np.array([max(1.0 / e.radius, 1.0 / e.end_radius) if isinstance(e, Arc) else 0.0 for e in elements])
    k_curve_near = _PilotMax(k_pilot, lo, hi)
    same = idx[1:] == idx[:-1]  # consecutive samples of one element
    step_el = np.array([e.length for e in elements]) / (np.bincount(idx, minlength=n_el) - 1)
    m_pc = step_el[idx[:-1]] ** 2 / 8.0 * (k_el[idx[:-1]] + 1.05 * k_curve_near(t_pc[:-1], t_pc[1:]))
    b_pc = np.where(same, np.maximum(d_pc[:-1], d_pc[1:]) + m_pc, -np.inf)
    k_path_near = _k_path_near(eidx, k_el, reach)
    m_cp = h * h / 8.0 * (1.05 * k_curve_near(seeds[:-1], seeds[1:]) + np.maximum(k_path_near[:-1], k_path_near[1:]))
    b_cp = np.maximum(d_cp[:-1], d_cp[1:]) + m_cp
    a, b = float(d_pc.max()), float(d_cp.max())
    found = [_worst(b_pc, pts, d_pc, m_pc), _worst(b_cp, cp, d_cp, m_cp)]
    if margin_mm > 0 and max(found, key=lambda f: f[0])[2] > margin_mm:
        # the cap widened the step where the curvature is extreme: those intervals measured again, finer
        over, q, d_q, b_q, m_q = _refined_path(curve, elements, idx, same, m_pc, t_pc, k_el, k_curve_near, lo, hi,
                                               margin_mm)
        over_c, c, d_c, b_c, m_c = _refined_curve(curve, seeds, h, m_cp, k_curve_near, eidx, elements, k_el, reach,
                                                  margin_mm)
        b_pc, b_cp = b_pc.copy(), b_cp.copy()
        b_pc[over], b_cp[over_c] = -np.inf, -np.inf  # those intervals: bounded by their parts instead
        found = [_worst(b_pc, pts, d_pc, m_pc), _worst(b_cp, cp, d_cp, m_cp), _worst(b_q, q, d_q, m_q),
                 _worst(b_c, c, d_c, m_c)]
        a, b = max(a, float(d_q.max(initial=0.0))), max(b, float(d_c.max(initial=0.0)))
    bound, worst, margin = max(found, key=lambda f: f[0])
    return Deviation(max_deviation_mm=bound, path_to_curve_mm=a, curve_to_path_mm=b, margin_mm=margin,
                     worst_point=(float(worst[0]), float(worst[1])))
