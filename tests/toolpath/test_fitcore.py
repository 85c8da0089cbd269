"""The lines fitting's batched check and search against their one-at-a-time definitions."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.geometry.jet import Jet
from camcam.geometry.jetcurve import JetCurve
from camcam.toolpath.elements import Line, element_distance
from camcam.toolpath.fitcore import Piece, greedy, lines_fit

ELLIPSE = JetCurve(lambda t, K, piece=None: (Jet.variable(t, K).cos() * 30.0, Jet.variable(t, K).sin() * 20.0),
                   np.array([0.0, np.pi, 2 * np.pi]))
PIECE = Piece(ELLIPSE, 0.0, np.pi)


def _seg_dist(q, poly):
    """Distance from points q (n,2) to the polyline poly (m,2)."""
    a, b = poly[:-1], poly[1:]
    d = b - a
    L2 = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    rel = q[:, None, :] - a[None, :, :]
    u = np.clip(np.einsum("nmj,mj->nm", rel, d) / L2, 0, 1)
    foot = a[None] + u[..., None] * d[None]
    return np.hypot(*(q[:, None, :] - foot).transpose(2, 0, 1)).min(axis=1)


def dev(piece, elems, t0, t1) -> float:
    """The lines fit's check as it was written for one chord at a time (the reference): two-sided, 41 curve
    points to the elements, the elements' 9 points each to the polyline through 81 curve points."""
    cp = piece.point(np.linspace(t0, t1, 41))
    d1 = np.min([element_distance(e, cp) for e in elems], axis=0).max()
    ep = np.concatenate([e.points(9) for e in elems])
    dense = piece.point(np.linspace(t0, t1, 81))
    d2 = _seg_dist(ep, dense).max()
    return float(max(d1, d2))


def sequential_greedy(t0, b, ok, guess):
    """The search as it was written before it judged candidates in batches (the reference)."""
    if ok(t0, b):
        return b
    span = b - t0
    lo, hi = t0, None
    step = min(guess, span)
    while True:
        t = t0 + step
        if t >= b:
            hi = b
            break
        if ok(t0, t):
            lo = t
            step *= 1.6
        else:
            hi = t
            break
    if lo == t0:
        while True:
            step *= 0.5
            if step < span * 1e-9:
                return t0 + step * 2
            if ok(t0, t0 + step):
                lo, hi = t0 + step, t0 + 2 * step
                break
    for _ in range(30):
        if hi - lo <= 1e-6 * span:
            break
        mid = 0.5 * (lo + hi)
        if ok(t0, mid):
            lo = mid
        else:
            hi = mid
    return lo


@settings(max_examples=60, deadline=None)
@given(t0=st.floats(0.0, 3.0), frac=st.lists(st.floats(0.0, 1.0), min_size=1, max_size=12),
       tol=st.sampled_from([1e-3, 1e-2, 0.1, 1.0]))
def test_batched_check_is_the_single_check(t0, frac, tol):
    ts = t0 + np.array(frac) * (math.pi - t0)
    got = lines_fit(PIECE, t0, ts, tol)
    for t1, g in zip(ts, got):
        q0, q1 = PIECE.point(t0)[0], PIECE.point(t1)[0]
        want = bool(np.hypot(*(q1 - q0)) > 0) and dev(PIECE, [Line(tuple(q0), tuple(q1))], t0, t1) <= tol
        assert bool(g) == want, (t0, t1, tol)


@settings(max_examples=60, deadline=None)
@given(t0=st.floats(0.0, 3.0), guess=st.floats(1e-6, 4.0), cut=st.floats(0.0, 1.0), holes=st.integers(0, 3))
def test_batched_search_makes_the_sequential_decisions(t0, guess, cut, holes):
    # a feasibility that need not be monotone (holes), so every branch of the search is exercised
    b = math.pi
    edge = t0 + cut * (b - t0)

    def ok1(a, t):
        return t <= edge and not (holes and math.sin(holes * 40.0 * t) > 0.95)

    def ok_many(a, ts):
        return np.array([ok1(a, float(t)) for t in ts], bool)

    # the same floats, so the same answer bit for bit
    assert greedy(t0, b, ok_many, guess) == sequential_greedy(t0, b, ok1, guess)


def test_chord_of_length_zero_never_fits():
    assert not lines_fit(PIECE, 1.0, np.array([1.0]), 1.0)[0]


@settings(max_examples=300, deadline=None)
@given(t0=st.floats(-1e4, 1e4), spans=st.lists(st.one_of(st.just(0.0), st.floats(1e-290, 1e3)), min_size=1, max_size=9))
def test_every_other_of_81_samples_is_the_41_samples_to_the_bit(t0, spans):
    # lines_fit evaluates the curve at the 81 polyline samples only and takes every other one as the chord's
    # 41 samples: exact equality, since the fitter's decisions depend on every bit of them (spans under
    # 1e-290, where Δ/80 may be subnormal and the halving inexact, take both sets apart; hypothesis found
    # 1.1e-308 with t0 = 0)
    ts = t0 + np.asarray(spans)
    assert np.linspace(t0, ts, 41, axis=1).tobytes() == np.ascontiguousarray(np.linspace(t0, ts, 81, axis=1)[:, ::2]).tobytes()
