"""The lines fitting's batched check against its one-at-a-time definition, and its chord search."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.geometry.jet import Jet
from camcam.geometry.jetcurve import JetCurve
from camcam.toolpath.elements import Line, element_distance
from camcam.toolpath.fitcore import GREEDY_TIGHT, Piece, greedy, lines_deviation, lines_fit

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


class _Counted:
    """A deviation function of the chord end for :func:`greedy`, counting its calls."""

    def __init__(self, f):
        self.f, self.calls = f, 0

    def __call__(self, t0, ts):
        self.calls += 1
        return np.array([self.f(float(t)) for t in ts])


@settings(max_examples=200, deadline=None)
@given(t0=st.floats(0.0, 3.0), guess=st.floats(1e-6, 4.0), cut=st.floats(1e-3, 1.2), power=st.floats(1.0, 4.0),
       tol=st.sampled_from([1e-4, 1e-2, 1.0]))
def test_search_ends_next_to_the_tolerance_on_a_growing_deviation(t0, guess, cut, power, tol):
    """A chord's deviation grows with its length (as L² for a chord of a smooth curve): the end found fits, is
    before the exact end t* where the deviation reaches tol, and uses (1 − GREEDY_TIGHT) of the tolerance
    unless it is within 1e-6 of the span of t* (the search's two stops); b itself when b fits."""
    b = math.pi
    t_star = t0 + cut * (b - t0)  # where the deviation reaches tol (past b when cut > 1)
    dev = _Counted(lambda t: tol * ((t - t0) / (t_star - t0)) ** power)
    t1 = greedy(t0, b, dev, tol, guess)
    if t_star >= b:
        assert t1 == b
        return
    # (t1 may pass t* by a rounding of the secant's arithmetic: the search keeps what it measured to fit)
    assert t0 < t1 <= t_star + 1e-12 * (b - t0) and dev.f(t1) <= tol
    assert dev.f(t1) >= (1 - GREEDY_TIGHT) * tol or t_star - t1 <= 1e-6 * (b - t0) * (1 + 1e-9)
    # regula falsi with the Illinois rule: a handful of calls after the expansion (bisection of the bracket
    # to 1e-6 of the span took about 15 halvings; a plain regula falsi creeps on a convex deviation)
    if guess >= 0.1 * (t_star - t0) and guess <= 10 * (t_star - t0):
        assert dev.calls <= 12


@settings(max_examples=60, deadline=None)
@given(t0=st.floats(0.0, 3.0), guess=st.floats(1e-6, 4.0), cut=st.floats(0.0, 1.0), holes=st.integers(1, 3))
def test_search_ends_on_a_fitting_chord_when_the_deviation_does_not_grow(t0, guess, cut, holes):
    # a deviation with bumps over the tolerance before its edge (holes): the end found still fits
    b = math.pi
    edge = t0 + cut * (b - t0)

    def f(t):
        bump = math.sin(holes * 40.0 * t) > 0.95
        return 0.5 + (t - t0) / (b - t0) * 0.1 if t <= edge and not bump else 2.0

    t1 = greedy(t0, b, _Counted(f), 1.0, guess)
    # it fits, or no chord longer than 1e-9 of the span does (t0 inside a bump): the shortest is returned, as
    # the bisection search did, and the caller's measurement of the printed path rejects it
    assert t0 < t1 <= b and (f(t1) <= 1.0 or t1 - t0 <= 2e-9 * (b - t0))


@settings(max_examples=40, deadline=None)
@given(t0=st.floats(0.0, 3.0), guess=st.floats(1e-4, 1.0), tol=st.sampled_from([1e-3, 1e-2, 0.1]))
def test_search_on_the_ellipse_fits_and_uses_the_tolerance(t0, guess, tol):
    b = math.pi
    t1 = greedy(t0, b, lambda a, ts: lines_deviation(PIECE, a, ts, tol), tol, guess)
    d = float(lines_deviation(PIECE, t0, [t1], tol)[0])
    assert d <= tol
    assert t1 == b or d >= (1 - GREEDY_TIGHT) * tol or t1 - t0 <= 1e-6 * (b - t0)


def test_lines_counts_of_the_bisection_search():
    """Regression data: disc-oscillating-flat's profile took 191 and 632 lines at 0.01 and 0.001 mm with the
    bisection to 1e-6 of the span (c3d9bfc, 2026-12-05); the regula falsi ends each chord within 0.025 %
    of the longest, and must not take more."""
    from dataclasses import replace
    from pathlib import Path

    from camcam.geometry.build import build_cam
    from camcam.nc import machine_program
    from camcam.spec import load_spec

    spec = load_spec(Path(__file__).resolve().parents[2] / "samples" / "disc-oscillating-flat.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    for tol, lines in ((0.01, 191), (0.001, 632)):
        r = machine_program(built, replace(spec.machining, tolerance_mm=tol), spec.name, spec.stock)
        assert r.contours[0].fit.line_blocks == lines


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
