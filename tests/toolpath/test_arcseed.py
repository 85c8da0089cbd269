"""A closed contour's arc spline seeded from the optimal pattern's arc density (camcam.toolpath.arcseed)."""

import functools
import math

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from camcam.geometry.curve import FunctionCurve
from camcam.toolpath.arcclose import quiet_stretches
from camcam.toolpath.arcseed import PATTERN_CONSTANT, SMOOTH_RATIO, seed_density, seeded_chain
from camcam.toolpath.arcspline import SplineBudget, fit_arc_spline
from camcam.toolpath.elements import Arc
from camcam.toolpath.lowerbound import lower_bound_blocks
from camcam.toolpath.quantizer import Quantizer
from tests.nc_curves import polar_cam
from tests.toolpath.test_arcpolish import assert_closed_printed_g1
from tests.toolpath.test_arcspline import brute_two_sided

KW = dict(max_sweep=math.radians(120), sag=5e-6)
TWO_PI = 2 * np.pi


def test_the_pattern_constant_is_six_over_the_bernoulli_peak():
    """|e| = |κ′|h³|B₃(s/h)|/6 on an arc of the optimal pattern; B₃(x) = x³ − 3x²/2 + x/2 peaks at
    x = 1/2 − 1/(2√3), √3/36: a dense grid on [0, 1] finds the peak to 1e-12 (the grid's step² × B₃″
    / 8)."""
    x = np.linspace(0.0, 1.0, 2_000_001)
    peak = np.abs(x ** 3 - 1.5 * x ** 2 + 0.5 * x).max()
    assert 6.0 / peak == pytest.approx(72.0 * math.sqrt(3.0), rel=1e-9)  # the grid's 1e-12 on a peak of 0.048
    assert PATTERN_CONSTANT == pytest.approx(6.0 / peak, abs=0.05)  # 124.7: 72√3 = 124.708 to four figures


@pytest.mark.parametrize("tol", [0.0095, 0.00095])
def test_the_seed_count_is_the_optimal_pattern_over_the_lower_bound(tol):
    """Without the sweep limit the seed's count is ∫(|κ′|/124.7δ)^⅓ ds = (192/124.7)^⅓ N_lb = 1.1547 N_lb;
    N_lb by a second method (lowerbound's quadrature between the joins)."""
    curve = polar_cam()
    _, count, turns = seed_density(curve, 0.0, TWO_PI, tol, max_sweep=1e9)
    ratio = float(count[-1]) / lower_bound_blocks(curve, tol)
    # 0.2 %: the seed's rectangle rule on 4096 parameters, across the integrand's kinks at the motion's joins
    # (0.07 % measured)
    assert ratio == pytest.approx((192.0 / PATTERN_CONSTANT) ** (1 / 3), rel=2e-3)
    assert turns == 1  # the polar cam runs counter-clockwise


@functools.lru_cache(maxsize=None)
def seeded(tol):
    curve = polar_cam()
    goal = math.floor(1.18 * lower_bound_blocks(curve, tol) + 4)
    return curve, seeded_chain(curve, 0.0, TWO_PI, tol, Quantizer(4), n_max=goal, **KW)


@pytest.mark.parametrize("tol", [0.0095, 0.0019, 0.00095])
def test_the_seeded_spline_is_printed_g1_and_within_the_band(tol):
    """Closed, on the 10⁻⁴ mm grid, G1 up to the rounding, and within the band on the exact curve by a second
    method (brute_two_sided: dense samples both ways)."""
    curve, out = seeded(tol)
    assert len(out) == 1
    els = out[0].elements
    assert len(out[0].starts) == len(els)
    assert_closed_printed_g1(els)
    # brute_two_sided's own error is below 1e-7 mm (its docstring)
    assert brute_two_sided(curve, list(els)) <= tol + 1e-7


@pytest.mark.parametrize("tol, seeded_arcs, march_arcs", [(0.0095, 16, 16), (0.0019, 25, 26), (0.00095, 31, 32)])
def test_the_seed_spends_no_more_arcs_than_the_march(tol, seeded_arcs, march_arcs):
    """Recorded (2026-12-06) on the polar test cam: the seeded spline's count and the march's from the fitter's
    own first start (seeded off), one arc fewer at the two fine bands."""
    curve, out = seeded(tol)
    march = fit_arc_spline(curve, 0.0, TWO_PI, tol, quantizer=Quantizer(4), closed=True,
                           lower_bound=lower_bound_blocks(curve, tol), budget=SplineBudget(seeded=False), **KW)
    assert (len(out[0].elements), len(march.elements)) == (seeded_arcs, march_arcs)


def test_the_fitter_seeds_a_smooth_curve_and_marches_a_noisy_one():
    """fit_arc_spline returns the seeded spline where the copy's N_lb agrees with the exact curve's, begun at
    the joint nearest the middle of the longest dwell (where the program's leads go; the march starts there); told the
    exact N_lb is 2 % lower (as on a noisy curve, whose copy's N_lb is 4-6 % above), it marches, as with the
    seed turned off."""
    tol = 0.00095
    curve, out = seeded(tol)
    n_lb = lower_bound_blocks(curve, tol)
    kw = dict(quantizer=Quantizer(4), closed=True, **KW)
    got = fit_arc_spline(curve, 0.0, TWO_PI, tol, lower_bound=n_lb, **kw)
    k = out[0].elements.index(got.elements[0])
    assert got.elements == out[0].elements[k:] + out[0].elements[:k]  # the same spline, begun elsewhere
    (mid, _), *_ = quiet_stretches(curve, 0.0, TWO_PI)[0]
    # the joint nearest the dwell's middle (the polar cam's 60° dwell is one arc: its nearest joint is its end)
    assert min(abs(s - mid) for s in got.starts) == abs(got.starts[0] - mid)
    assert got.starts[0] != out[0].starts[0]  # begun elsewhere than the seed's first joint, at the parameter 0
    noisy = n_lb / (SMOOTH_RATIO + 0.01)
    marched = fit_arc_spline(curve, 0.0, TWO_PI, tol, lower_bound=noisy, budget=SplineBudget(seeded=False), **kw)
    assert fit_arc_spline(curve, 0.0, TWO_PI, tol, lower_bound=noisy, **kw).elements == marched.elements
    assert marched.elements != out[0].elements


def test_no_count_within_the_goal_gives_nothing():
    """A goal under the seed's first count: nothing is tried, nothing returned (the fitter then marches)."""
    curve = polar_cam()
    _, count, _ = seed_density(curve, 0.0, TWO_PI, 0.00095 - 0.4e-4, KW["max_sweep"])
    first = math.ceil(float(count[-1]))
    assert seeded_chain(curve, 0.0, TWO_PI, 0.00095, Quantizer(4), n_max=first - 1, **KW) == ()


def test_a_clockwise_contour_is_seeded_turning_the_other_way():
    """An ellipse run clockwise (a cam turning the other way): the seed's turns are −1 and the spline is the
    mirror image's count, within the band (brute_two_sided), every arc clockwise."""

    def ellipse(sign):
        def f(t, k):
            c, s = np.cos(t), np.sin(t)
            rows = [[40 * c, 25 * s], [-40 * s, 25 * c], [-40 * c, -25 * s], [40 * s, -25 * c]][k]
            return np.stack([rows[0], sign * rows[1]], -1)
        return FunctionCurve(f, 0.0, TWO_PI, closed=True)

    tol = 0.0095
    ccw, cw = ellipse(1.0), ellipse(-1.0)
    assert seed_density(cw, 0.0, TWO_PI, tol, KW["max_sweep"])[2] == -1
    (a,) = seeded_chain(ccw, 0.0, TWO_PI, tol, Quantizer(4), n_max=21, **KW)
    (b,) = seeded_chain(cw, 0.0, TWO_PI, tol, Quantizer(4), n_max=21, **KW)
    assert len(b.elements) == len(a.elements)
    assert all(isinstance(e, Arc) and not e.ccw for e in b.elements)
    assert brute_two_sided(cw, list(b.elements)) <= tol + 1e-7



@settings(max_examples=8, deadline=None)
@given(st.floats(20.0, 60.0), st.floats(0.4, 0.95), st.floats(0.002, 0.05), st.sampled_from([1.0, -1.0]),
       st.floats(0.0, 0.3))
def test_whatever_the_seed_returns_is_within_the_band(a_mm, ratio, tol, sign, wobble):
    """A smooth closed curve (an ellipse with a third-harmonic wobble, either way round) at any band: a spline
    the seed returns has at most n_max arcs, is closed, printed and G1, and lies within the band on the exact
    curve by the second method (brute_two_sided); no spline at all is an allowed answer (the fitter marches)."""
    b_mm = ratio * a_mm

    def f(t, k):
        # r(t) = 1 + w cos 3t scales the ellipse: P = r(t)·(a cos t, ±b sin t), derivatives by Leibniz
        r = [1 + wobble * np.cos(3 * t), -3 * wobble * np.sin(3 * t), -9 * wobble * np.cos(3 * t),
             27 * wobble * np.sin(3 * t)]
        e = [np.stack([a_mm * np.cos(t), sign * b_mm * np.sin(t)], -1),
             np.stack([-a_mm * np.sin(t), sign * b_mm * np.cos(t)], -1),
             np.stack([-a_mm * np.cos(t), -sign * b_mm * np.sin(t)], -1),
             np.stack([a_mm * np.sin(t), -sign * b_mm * np.cos(t)], -1)]
        binom = [[1], [1, 1], [1, 2, 1], [1, 3, 3, 1]][k]
        return sum(c * r[j][:, None] * e[k - j] for j, c in enumerate(binom))

    curve = FunctionCurve(f, 0.0, TWO_PI, closed=True)
    n_max = math.floor(1.18 * lower_bound_blocks(curve, tol) + 4)
    out = seeded_chain(curve, 0.0, TWO_PI, tol, Quantizer(4), n_max=n_max, **KW)
    if not out:
        return
    els = out[0].elements
    assert len(els) <= n_max
    assert_closed_printed_g1(els)
    assert brute_two_sided(curve, list(els)) <= tol + 1e-7  # brute_two_sided's own error is below 1e-7 mm
