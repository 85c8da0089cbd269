"""The envelope of a moving cylinder on a roller section of a barrel cam: the groove wall it makes.

:func:`envelope` gives, at radius ρ and part angles γ, each wall's extreme x over a whole motion (the
roller's, for the designed wall; the program's tool, for the cut one), and the motion parameter where
it is reached: the motion sampled (:meth:`~camcam.verify.groove_motion.Motion.samples`) and the best
sample refined by vectorised golden-section search between its neighbours.
:mod:`camcam.verify.groove3d` measures the cut groove against the designed one with it (its module
notes say how, and what the sampling can miss).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.verify.groove_motion import Motion, section_interval, side_extent, sincos_sum, wall_extents

__all__ = ["Envelope", "envelope"]

_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0

#: Golden-section steps refining a motion extreme between two samples (bracket × 0.618²⁰ ≈ 7e-5).
_MOTION_STEPS = 20


@dataclass(frozen=True)
class Envelope:
    value: np.ndarray  # (k,) the wall extent (hi, or −lo), −inf where nothing reaches
    p: np.ndarray  # (k,) motion parameter of the extreme, NaN where nothing reaches


#: (sample, angle) pairs evaluated at once in a regular envelope.  Arrays of this size
#: (0.5 MB) stay in the allocator's reuse and the CPU caches; at 2 million pairs each of
#: :func:`section_interval`'s ~30 temporaries was fresh memory and the pass ran 2.5 x slower
#: (benchmarked on the cylindrical samples; the figures do not depend on the chunking).
_PAIRS_PER_CHUNK = 65_536


def _golden(f, lo, hi, iterations: int):
    """Vectorised golden-section maximisation of f on [lo, hi] (arrays); returns (p, f(p))."""
    a, b = np.array(lo, float), np.array(hi, float)
    c = b - _GOLDEN * (b - a)
    d = a + _GOLDEN * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(iterations):
        left = fc >= fd  # keep [a, d]
        b = np.where(left, d, b)
        a = np.where(left, a, c)
        c_new = b - _GOLDEN * (b - a)
        d_new = a + _GOLDEN * (b - a)
        c2 = np.where(left, c_new, d)
        d2 = np.where(left, c, d_new)
        f_new = f(np.where(left, c_new, d_new))
        fc, fd = np.where(left, f_new, fd), np.where(left, fc, f_new)
        c, d = c2, d2
    best = np.where(fc >= fd, c, d)
    return best, np.maximum(fc, fd)


def _reachable(poses: tuple, r: float, rho: float) -> np.ndarray:
    """Samples whose cylinder can reach the cylinder r = ρ (a conservative test)."""
    X, Y, Z, a, B = poses
    return (Z - r * np.abs(np.sin(B)) <= rho) & (np.abs(Y) <= rho + r)


def _windows(poses: tuple, r: float, rho):
    """Each sample's β window [lo, hi] on r = ρ (|ρ sin β + Y| ≤ r) and whether it may reach r = ρ at all:
    (keep, lo, hi), each (n,) for a scalar ``rho`` or (len(rho), n) for an array of radii."""
    Y = poses[1]
    rho = rho if np.ndim(rho) == 0 else np.asarray(rho, float)[:, None]
    lo_s = np.arcsin(np.clip((-r - Y) / rho, -1, 1))
    hi_s = np.arcsin(np.clip((r - Y) / rho, -1, 1))
    return _reachable(poses, r, rho), lo_s, hi_s


def envelope(motion: Motion, samples: np.ndarray, poses: tuple, rho, gamma: np.ndarray,
              iterations: int = _MOTION_STEPS) -> tuple[Envelope, Envelope]:
    """The extreme wall extents over the motion at each γ: (side 0: −lo, side 1: hi).

    ``gamma`` is either a full periodic grid (ascending or descending) at one radius ``rho``, or a few
    scattered angles, each at ``rho`` or at its own radius (``rho`` an array like ``gamma``).
    """
    g0, dg, regular = _grid_of(gamma)
    if regular and np.ndim(rho) == 0 and dg < 0:
        e = envelope(motion, samples, poses, rho, gamma[::-1], iterations)
        return tuple(Envelope(x.value[::-1], x.p[::-1]) for x in e)
    k = len(gamma)
    best_v = np.full((2, k), -np.inf)
    best_j = np.full((2, k), -1)
    if regular and np.ndim(rho) == 0:
        X, Y, Z, a, B = poses
        r, L = motion.r, motion.L
        reach, lo_s, hi_s = _windows(poses, r, rho)
        keep = np.nonzero(reach)[0]
        lo_s, hi_s, ak = lo_s[keep], hi_s[keep], a[keep]
        i0 = np.ceil((lo_s - ak - g0) / dg).astype(int)
        i1 = np.minimum(np.floor((hi_s - ak - g0) / dg).astype(int), i0 + k - 1)
        cnt = np.maximum(i1 - i0 + 1, 0)
        # no pose reaches ρ (a cut stopped above it: depth < groove depth) leaves cnt empty, its mean NaN
        chunk = max(1, int(_PAIRS_PER_CHUNK // max(1, (int(cnt.mean()) if cnt.size else 0) + 1)))
        # every grid index a pair may take (before its wrap onto [0, k)): the angles g0 + i·dg as the pairs had
        # them, with their sines and cosines; and each kept sample's pose with the sines and cosines of its a
        # and B (taken for every angle it reaches)
        i_min = int(i0.min(initial=0))
        grid = g0 + np.arange(i_min, int((i0 + np.maximum(cnt, 1)).max(initial=1))) * dg
        grid_sc = np.stack([np.sin(grid), np.cos(grid)])
        Bk = B[keep]
        kept = np.stack([X[keep], Y[keep], Z[keep], np.sin(Bk), np.cos(Bk), np.sin(ak), np.cos(ak)])
        for s0 in range(0, len(keep), chunk):
            c = cnt[s0:s0 + chunk]
            width = int(c.max())
            if width == 0:
                continue
            # a chunk's pairs as a table: sample j of the chunk (a row) with grid angles i0[j], i0[j] + 1, …,
            # i0[j] + c[j] − 1 (its first c[j] columns; the rest padding, no pair).  A sample's pose is one
            # column broadcast along its row, where a list of pairs repeated it for each angle
            ii = i0[s0:s0 + chunk, None] + np.arange(width)
            pad = np.arange(width) >= c[:, None]
            sin_g, cos_g = np.take(grid_sc, np.where(pad, i_min, ii) - i_min, axis=1)
            Xj, Yj, Zj, sin_b, cos_b, sin_a, cos_a = kept[:, s0:s0 + chunk, None]
            # sin and cos of β = γ + a by the angle-addition formulas: one sine and cosine per grid angle and
            # per sample instead of per pair (groove_motion.sincos_sum)
            lo, hi = section_interval(Xj, Yj, Zj, None, None, r, L, rho, None, (sin_b, cos_b),
                                      sincos_sum(sin_g, cos_g, sin_a, cos_a))
            ii = np.mod(ii, k).ravel()
            js = np.repeat(keep[s0:s0 + chunk], width)
            for side, v in enumerate(wall_extents(lo, hi)):
                v[pad] = -np.inf  # padding never beats anything: the pairs' figures and order as in a list
                _scatter_best(ii, v.ravel(), js, best_v[side], best_j[side])
    else:
        _scattered_best(poses, motion.r, motion.L, rho, gamma, best_v, best_j)
    return _refine_motion(motion, samples, rho, gamma, best_v, best_j, iterations)


#: (angle, sample) window tests of a scattered envelope made at once: its tables stay about 8 MB each.
_SCATTERED_TESTS = 1_000_000

#: Margin (rad) of the scattered envelope's prefilter on the windows' centres: far above the rounding of a
#: centre and a half-width (1e-15 rad), far below any window.
_CENTRE_SLACK_RAD = 1e-9


def _candidates(centre: np.ndarray, half: float, g: np.ndarray):
    """(angle, sample) pairs, by angle and then sample, whose sample's window centre lies within ``half`` (+ a
    slack) of the angle, on the circle: every pair whose angle lies in the sample's window, and others.

    ``centre`` (n,) are the samples' window centres in [0, 2π), ``g`` (m,) the angles in [0, 2π)."""
    order = np.argsort(centre, kind="stable")
    cs = centre[order]
    n = len(cs)
    ext = np.concatenate([cs - 2 * math.pi, cs, cs + 2 * math.pi])  # a range about an angle never wraps twice
    lo = np.searchsorted(ext, g - half - _CENTRE_SLACK_RAD, side="left")
    hi = np.searchsorted(ext, g + half + _CENTRE_SLACK_RAD, side="right")
    count = hi - lo
    ii = np.repeat(np.arange(len(g)), count)
    js = order[np.mod(np.repeat(lo - np.cumsum(count) + count, count) + np.arange(int(count.sum())), n)]
    by = np.lexsort((js, ii))
    return ii[by], js[by]


def _scattered_best(poses, r, L, rho, gamma, best_v, best_j) -> None:
    """Each scattered angle's best sample on both sides, into ``best_v`` and ``best_j`` (2, k): of the samples
    that may reach r = ρ and whose β window holds γ + a (:func:`_windows`), the one with the largest extent
    (the first of equals, as ``np.argmax``), where it is finite.  ``rho`` is one radius or one per angle.

    The pairs are found in two steps: those whose sample's window centre is near the angle (a sorted
    search, :func:`_candidates`: a window is at most as wide as its arcsines, 2·asin(r/ρ) for a pose on the
    axis' plane), then of them those whose window holds the angle, by the same arithmetic as a test of
    every pair; the pairs, their order and so the figures are those of every pair tested (each angle's in a
    run, by sample).  Every pair of a group of angles is one array: the same section of each pair, element
    by element, as one :func:`section_interval` per angle and radius.
    """
    X, Y, Z, a, B = poses
    sin_b, cos_b = np.sin(B), np.cos(B)  # each sample's, taken for every angle it reaches
    # each distinct radius's windows once: (radii, n), and each angle's row of them
    radii, row = (np.asarray([rho], float), np.zeros(len(gamma), int)) if np.ndim(rho) == 0 else \
        np.unique(np.asarray(rho, float), return_inverse=True)
    reach, lo_s, hi_s = _windows(poses, r, radii)
    for w_row in range(len(radii)):
        of_row = np.flatnonzero(row == w_row)
        keep = np.flatnonzero(reach[w_row])
        if len(of_row) == 0 or len(keep) == 0:
            continue
        lo_k, hi_k = lo_s[w_row, keep], hi_s[w_row, keep]
        centre = np.mod(0.5 * (lo_k + hi_k) - a[keep], 2 * math.pi)
        half = float(0.5 * (hi_k - lo_k).max())
        ci, cj = _candidates(centre, half, np.mod(gamma[of_row], 2 * math.pi))
        step = max(1, _SCATTERED_TESTS // max(len(a), 1))
        for s0 in range(0, len(of_row), step):  # blocks of angles as before: the tables stay small
            p0, p1 = np.searchsorted(ci, (s0, s0 + step))  # the candidates come by angle
            ai, js = of_row[ci[p0:p1]], keep[cj[p0:p1]]
            g = gamma[ai]
            d_lo = np.mod(g + a[js] - lo_s[w_row, js] + math.pi, 2 * math.pi) - math.pi
            d_hi = np.mod(hi_s[w_row, js] - g - a[js] + math.pi, 2 * math.pi) - math.pi
            hold = (d_lo >= 0) & (d_hi >= 0)
            ai, js = ai[hold], js[hold]
            if len(ai) == 0:
                continue
            lo, hi = section_interval(X[js], Y[js], Z[js], a[js], None, r, L, radii[w_row], gamma[ai],
                                      (sin_b[js], cos_b[js]))
            starts = np.flatnonzero(np.r_[True, ai[1:] != ai[:-1]])
            rows = ai[starts]
            counts = np.diff(np.r_[starts, len(ai)])
            for side, v in enumerate(wall_extents(lo, hi)):
                top = np.maximum.reduceat(v, starts)
                # the first pair of each run at its run's largest value (np.argmax's choice among equals)
                at = np.where(v == np.repeat(top, counts), np.arange(len(v)), len(v))
                first = np.minimum.reduceat(at, starts)
                ok = np.isfinite(top)
                best_v[side, rows[ok]] = top[ok]
                best_j[side, rows[ok]] = js[first[ok]]


def _refine_motion(motion, samples, rho, gamma, best_v, best_j, iterations) -> tuple[Envelope, Envelope]:
    """Golden-section refinement of each γ's best sample between its two neighbours, both sides.

    ``best_v`` and ``best_j`` are (2, k): per side (0: −lo, 1: hi) and γ.  Both
    sides run as one array (one pose and one section a step): the search is
    elementwise, so each γ's figure is the one a search of its side alone finds.
    """
    k = len(gamma)
    found = best_j >= 0  # (2, k)
    p = np.full((2, k), np.nan)
    if not found.any():
        return Envelope(best_v[0], p[0]), Envelope(best_v[1], p[1])
    j = best_j[found]
    n = len(samples)
    if motion.periodic:
        lo_p = np.where(j > 0, samples[np.maximum(j - 1, 0)], samples[-1] - 2 * math.pi)
        hi_p = np.where(j < n - 1, samples[np.minimum(j + 1, n - 1)], samples[0] + 2 * math.pi)
    else:
        lo_p = samples[np.maximum(j - 1, 0)]
        hi_p = samples[np.minimum(j + 1, n - 1)]
    g = np.broadcast_to(gamma, (2, k))[found]
    side = np.broadcast_to(np.array([[0], [1]]), (2, k))[found]
    rho = rho if np.ndim(rho) == 0 else np.broadcast_to(rho, (2, k))[found]

    def f(pp):
        return side_extent(*motion.pose(motion.clamp(pp)), motion.r, motion.L, rho, g, side)

    pr, vr = _golden(f, lo_p, hi_p, iterations)
    better = vr > best_v[found]
    v_out = best_v.copy()
    v_out[found] = np.where(better, vr, best_v[found])
    p[found] = np.where(better, pr, samples[j])
    return Envelope(v_out[0], p[0]), Envelope(v_out[1], p[1])


def _grid_of(gamma: np.ndarray):
    k = len(gamma)
    if k >= 8:
        dg = (gamma[-1] - gamma[0]) / (k - 1)
        if abs(abs(dg * k) - 2 * math.pi) < 1e-9 and np.allclose(np.diff(gamma), dg, atol=1e-12):
            return float(gamma[0]), float(dg), True
    return 0.0, 1.0, False


def _scatter_best(ii, v, js, best_v, best_j):
    """best_v[i] = max over the pairs with index i (and a sample that gives it)."""
    if len(ii) == 0:
        return
    before = best_v.copy()
    np.maximum.at(best_v, ii, v)
    hit = (v == best_v[ii]) & (v > before[ii])
    best_j[ii[hit]] = js[hit]
