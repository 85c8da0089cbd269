import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from camcam.errors import InputError
from camcam.geometry.curve import curvature_rate, speed
from camcam.toolpath.quantizer import Quantizer
from camcam.toolpath.arcfit import fit_contour, line_estimate_blocks, lower_bound_blocks
from camcam.toolpath.deviation import measure_deviation
from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.elements import element_tangent
from camcam.workers import ProcessMap
from tests.nc_curves import ellipse, polar_cam, wavy

CASES = {
    ("ellipse", 0.01): ellipse, ("ellipse", 0.001): ellipse,
    ("wavy", 0.01): wavy, ("wavy", 0.001): wavy,
    ("cam", 0.01): polar_cam,
}


@functools.lru_cache(maxsize=None)
def fitted(key):
    curve = CASES[key]()
    return curve, fit_contour(curve, key[1], max_sweep_deg=120)


@pytest.fixture
def fits():
    class Lazy:
        def __getitem__(self, key):
            return fitted(key)

    return Lazy()


@pytest.mark.parametrize("key", list(CASES))
def test_deviation_within_tolerance_measured_again(fits, key):
    curve, fit = fits[key]
    # an independent re-measurement with a 10x smaller between-sample margin
    again = measure_deviation(curve, fit.elements, margin_mm=0.002 * key[1])
    assert again.max_deviation_mm <= key[1]
    assert fit.max_deviation_mm <= key[1]


@pytest.mark.parametrize("key", list(CASES))
def test_blocks_near_lower_bound(fits, key):
    _, fit = fits[key]
    for n, lb in zip(fit.piece_blocks, fit.piece_lower_bounds):
        assert n <= 1.5 * lb + 2, (n, lb)


@pytest.mark.parametrize("key", list(CASES))
def test_no_degenerate_arcs_and_tangent_continuity(fits, key):
    _, fit = fits[key]
    els = fit.elements
    for e in els:
        for p in (e.start, e.end) + ((e.centre,) if isinstance(e, Arc) else ()):
            # every printed number is on the 1e-4 grid (to float rounding of the decimal)
            assert all(abs(v * 1e4 - round(v * 1e4)) < 1e-6 for v in p)
        if isinstance(e, Arc):
            assert abs(e.radius - e.end_radius) < 0.002  # GRBL/LinuxCNC radius check, after rounding
            assert 1e-4 < e.sweep <= math.radians(120) + 1e-6
    for e, f in zip(els, els[1:]):
        assert e.end == f.start  # positional continuity is exact on the grid
        t0, t1 = element_tangent(e, True), element_tangent(f, False)
        kink = abs(math.atan2(t0[0] * t1[1] - t0[1] * t1[0], t0 @ t1))
        # G1 up to rounding: ends and centres moved ≤ 0.71e-4 mm over lengths ≥ ~0.5 mm
        assert kink < 2e-3, kink


def test_lower_bound_by_quadrature():
    from scipy.integrate import quad

    E = ellipse()
    f = lambda t: (abs(curvature_rate(E, [t])[0]) / (192 * 0.01)) ** (1 / 3) * speed(E, [t])[0]
    # κ′ = 0 at the ellipse's four vertices, which are its breaks here: quad needs no cusp inside a piece
    ref = sum(quad(f, a, b, limit=200, epsabs=1e-13, epsrel=1e-13)[0] for a, b in zip(E.breaks, E.breaks[1:]))
    # the mapped Gauss rule is exact to rounding on an analytic piece (12.835 020 279 6 both; Simpson on
    # 20 001 points gave 12.835 008, 1e-6 off)
    assert abs(lower_bound_blocks(E, 0.01) - ref) < 1e-10 * ref


def test_lower_bound_cuts_at_the_cusps():
    from scipy.integrate import quad

    # the same ellipse without breaks at the vertices: the rule finds κ′'s roots itself
    E = ellipse(quarter_breaks=False)
    f = lambda t: (abs(curvature_rate(E, [t])[0]) / (192 * 0.001)) ** (1 / 3) * speed(E, [t])[0]
    vertices = [0.0, math.pi / 2, math.pi, 1.5 * math.pi, 2 * math.pi]
    ref = sum(quad(f, a, b, limit=200, epsabs=1e-13, epsrel=1e-13)[0] for a, b in zip(vertices, vertices[1:]))
    # roots to 1e-10 rad leave ~1e-13 relative; 1e-10 allows for the rule on 4 parts instead of 4 pieces
    assert abs(lower_bound_blocks(E, 0.001) - ref) < 1e-10 * ref
    # and per piece in one batch: the halves add up to the whole
    from camcam.toolpath.lowerbound import lower_bound_pieces

    halves = lower_bound_pieces(E, 0.001, [(0.0, 1.0), (1.0, 2 * math.pi)])
    assert abs(sum(halves) - ref) < 1e-10 * ref  # 1.0 rad is no root: the two parts are smooth


def test_line_estimate_closed_form_on_a_circle():
    from camcam.toolpath.lowerbound import line_estimate_blocks as estimate

    R, tol = 10.0, 0.01
    C = ellipse(R, R)
    # κ = 1/R: ∫√(κ/8δ) ds = 2πR·√(1/(8Rδ)); the rule is exact to rounding on a constant
    assert abs(estimate(C, tol) - 2 * math.pi * R * math.sqrt(1 / (8 * R * tol))) < 1e-12 * 50
    # and κ′ = 0: no arc spline needs more than the circle's own arcs, N_lb = 0 (up to the rounding of κ′)
    assert lower_bound_blocks(C, tol) < 1e-3


def test_lines_mode_chordal():
    E = ellipse()
    fit = fit_contour(E, 0.01, mode="lines")
    assert all(isinstance(e, Line) for e in fit.elements)
    assert fit.max_deviation_mm <= 0.01
    est = line_estimate_blocks(E, 0.01)
    # greedy chords with points on the curve: between the estimate and 1.3× it (rounding budget, whole steps)
    assert est <= len(fit.elements) <= 1.3 * est + 4


def test_lines_pieces_shared_by_two_processes_fit_the_same():
    # the ellipse's four quarter pieces go to two processes, the dearest first: the same lines, pieces and
    # deviation as one after the other (each piece is the same call)
    E = ellipse()
    one = fit_contour(E, 0.002, mode="lines")
    two = fit_contour(E, 0.002, mode="lines", mapper=ProcessMap(2))
    assert len(one.piece_blocks) == 4
    assert (two.elements, two.piece_blocks, two.deviation) == (one.elements, one.piece_blocks, one.deviation)


def test_lines_failure_names_the_first_piece_in_order(monkeypatch):
    # every piece misses (a deviation said to be 1 mm); the error is the first piece's, as one after the
    # other would raise it, although the pieces are taken dearest first by two processes
    import dataclasses

    import camcam.toolpath.arcfit as arcfit

    real = arcfit.measure_deviation
    monkeypatch.setattr(arcfit, "measure_deviation",
                        lambda *a, **k: dataclasses.replace(real(*a, **k), max_deviation_mm=1.0))
    from camcam.errors import FitError

    W = wavy()  # two pieces, the second dearer (65.0 and 73.7 lines estimated at 0.002 mm): taken first
    for workers in (1, 2):
        with pytest.raises(FitError, match=r"t ∈ \[0, 60\]"):
            fit_contour(W, 0.002, mode="lines", mapper=ProcessMap(workers))


def test_arcs_beat_lines_at_a_micron():
    E, arcs = fitted(("ellipse", 0.001))
    est_lines = line_estimate_blocks(E, 0.001)
    # ∫√(κ/8δ) ≈ 345 chords vs 40 arcs on this ellipse (the cam benchmark shows ≈ 14x)
    assert est_lines / len(arcs.elements) > 8


def test_tolerance_too_fine_for_decimals():
    with pytest.raises(InputError, match="too fine for 3 decimals"):
        fit_contour(ellipse(), 0.001, quantizer=Quantizer(3))


@settings(max_examples=4, deadline=None)
@given(st.floats(15, 40), st.floats(8, 14), st.sampled_from([0.05, 0.01]))
def test_random_ellipses(a, b, tol):
    E = ellipse(a, b)
    fit = fit_contour(E, tol)
    again = measure_deviation(E, fit.elements, margin_mm=0.005 * tol)
    assert again.max_deviation_mm <= tol  # guaranteed bound, re-measured
    assert np.isclose(sum(fit.piece_blocks), len(fit.elements))  # counts add up (integers)
