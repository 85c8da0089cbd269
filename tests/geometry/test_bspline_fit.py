"""The B-splines the STEP is made of (camcam.geometry.bspline_fit, camcam.export.step_solids.fit_curve): measured
at parameters of the test's own choosing."""

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from camcam.geometry.bspline_fit import analytic_spans, fit_surface
from camcam.geometry.curve import FunctionCurve


def ellipse(a: float, b: float, breaks: tuple[float, ...]) -> FunctionCurve:
    def f(t, order):
        c, s = np.cos(t), np.sin(t)
        return np.stack([[a * c, b * s], [-a * s, b * c], [-a * c, -b * s], [a * s, -b * c]][order], axis=-1)

    return FunctionCurve(f, 0.0, 2 * np.pi, closed=True, breaks_=breaks)


@settings(max_examples=25, deadline=None)
@given(a=st.floats(5, 80), b=st.floats(5, 80), tol=st.floats(1e-5, 1e-3),
       breaks=st.lists(st.floats(0.1, 6.1), max_size=4, unique=True),
       probe=st.lists(st.floats(0, 1), min_size=50, max_size=50))
@example(a=5.0, b=5.0, tol=0.001, breaks=[0.1, 0.10000000000000002], probe=[0.0] * 50)  # CI at 8331af8: two
# breaks one rounding apart made a 1e-17 rad span OpenCascade refused (Standard_ConstructionError)
def test_curve_fit_stays_within_its_tolerance_between_its_checks(a, b, tol, breaks, probe):
    pytest.importorskip("OCP", reason="the cad extra (cadquery-ocp-novtk) is not installed")
    from camcam.export.step_solids import fit_curve

    C = ellipse(a, b, tuple(sorted(breaks)))
    pieces, deviation = fit_curve(C, tol / 2)
    assert deviation < tol / 2
    spans = analytic_spans(C.breaks)
    assert len(spans) == len(pieces)
    worst = 0.0
    for (lo, hi, _), piece in zip(spans, pieces):
        t = lo + (hi - lo) * np.asarray(probe)
        got = np.array([[piece.Value(float(u)).X(), piece.Value(float(u)).Y()] for u in t])
        worst = max(worst, float(np.hypot(*(got - C.evaluate(t)).T).max()))
    # parameters the fit never looked at: the half of the tolerance it kept back covers them
    assert worst <= tol
    # the pieces share their ends exactly, round the whole curve
    for p, q in zip(pieces, pieces[1:] + pieces[:1]):
        assert p.Pole(p.NbPoles()).IsEqual(q.Pole(1), 0.0)


def _band_point(t, r):
    """A warped band: the surface both surface tests fit."""
    T, R = np.meshgrid(t, r, indexing="ij")
    return np.stack([R * np.cos(T), R * np.sin(T), 3 * np.sin(2 * T) + 0.01 * R**2], axis=-1)


def _band_tangent(t, r, piece):
    T, R = np.meshgrid(t, r, indexing="ij")
    return np.stack([-R * np.sin(T), R * np.cos(T), 6 * np.cos(2 * T)], axis=-1)


def test_surface_fit_of_a_warped_band():
    rho = np.linspace(30, 40, 6)
    fit = fit_surface(_band_point, _band_tangent, [(0.0, 2.0, None), (2.0, 2 * np.pi, None)], rho, 5e-5)
    assert fit.deviation_mm < 5e-5
    rng = np.random.default_rng(1)
    for (lo, hi), piece in zip([(0.0, 2.0), (2.0, 2 * np.pi)], fit.pieces):
        u, v = np.sort(rng.uniform(lo, hi, 40)), np.sort(rng.uniform(30, 40, 15))
        # random points never measured by the fit: within twice its target
        assert np.linalg.norm(piece.evaluate(u, v) - _band_point(u, v), axis=-1).max() <= 1e-4


def test_surface_fit_predicts_its_node_counts_from_the_h4_law():
    """The surface fit grows its node counts by the cubic interpolant's h⁴ law (next_nodes): within its
    tolerance with fewer nodes over the band than doubling until the tolerance is met."""
    from camcam.geometry.bspline_fit import _surface_piece, check_params, next_nodes, refined

    def deviation(piece, s):
        u, v = check_params(s.knots_u), check_params(s.knots_v)
        return float(np.max(np.linalg.norm(s.evaluate(u, v) - _band_point(u, v), axis=-1)))

    rho, spans = np.linspace(30, 40, 6), [(0.0, 2.0, None), (2.0, 2 * np.pi, None)]

    def nodes(order):
        pieces, worst = refined(spans, lambda piece, a, b, n: _surface_piece(_band_point, _band_tangent, a, b, piece, rho, n),
                                deviation, lambda s, nxt: None, 5e-5, "surface", order=order)
        assert worst < 5e-5
        return sum(len(np.unique(p.knots_u)) - 1 for p in pieces)

    assert nodes(4) < nodes(None)
    # a deviation that barely falls still grows the count by a quarter at least, and never past MAX_NODES
    assert next_nodes(100, 5.0001e-5, 5e-5, 4) == 125
    assert next_nodes(4000, 1.0, 5e-5, 4) == 4096
