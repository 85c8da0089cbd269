"""Fitted tables as motion laws: exact extremes, derivatives, rise-only normalisation."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.lifttable.bspline import chord_bspline
from camcam.lifttable.interpolate import interpolate
from camcam.lifttable.table_motion import table_law
from camcam.lifttable.table import LiftTable

ANG = np.arange(0.0, 361.0, 6.0)
LIFT = 4 - 4 * np.cos(np.radians(ANG)) + 0.5 * np.sin(np.radians(3 * ANG))


@pytest.mark.parametrize("fit", ["periodic", "natural", "not-a-knot", "clamped", "bspline"])
def test_extremes_are_exact_and_bound_a_dense_grid(fit):
    law = table_law(LiftTable(tuple(ANG), tuple(LIFT)), fit)
    T = np.linspace(0.0, 1.0, 20001)
    for k in range(4):
        lo, hi = law.extreme(k, rest_ends=False)
        v = law.evaluate(T, k)
        # the extreme is attained (value at its own T) and no grid sample beats it; jerk jumps at
        # the knots, where the extreme may be the left-hand limit evaluate() does not return
        if k < 3:
            assert float(law.evaluate(lo.T, k)) == pytest.approx(lo.value, rel=1e-9, abs=1e-9)  # float rounding
            assert float(law.evaluate(hi.T, k)) == pytest.approx(hi.value, rel=1e-9, abs=1e-9)  # float rounding
        span = hi.value - lo.value
        assert v.min() >= lo.value - 1e-9 * span and v.max() <= hi.value + 1e-9 * span  # rounding only
        if k < 3:  # smooth derivatives: the grid comes within its spacing's reach of the exact extreme
            assert v.max() == pytest.approx(hi.value, rel=1e-5, abs=1e-5 * span)  # 5e-5 grid step, quadratic near a max


def test_law_derivatives_match_the_spline_per_degree():
    f = interpolate(ANG, LIFT, "periodic")
    law = table_law(LiftTable(tuple(ANG), tuple(LIFT)), "periodic")
    x = np.array([3.0, 100.0, 359.0])
    for k in range(5):
        assert np.allclose(law.evaluate(x / 360.0, k), f(x, k) * 360.0**k, rtol=1e-10, atol=1e-9)  # rounding of the rescaled coefficients


def test_rise_only_table_is_a_normalised_rise_law():
    x = np.linspace(20.0, 80.0, 31)
    T = (x - 20) / 60
    h = 2.0 + 6.0 * (T - np.sin(2 * np.pi * T) / (2 * np.pi))  # a cycloidal rise of 6 mm from 2 mm
    law = table_law(LiftTable(tuple(x), tuple(h)), "clamped")
    assert law.rest_to_rest
    assert float(law.evaluate(0.0)) == pytest.approx(0.0, abs=1e-12)  # normalisation is exact up to rounding
    assert float(law.evaluate(1.0)) == pytest.approx(1.0, abs=1e-12)  # idem
    assert float(law.evaluate(0.0, 1)) == pytest.approx(0.0, abs=1e-12)  # clamped end slope 0 (eq. 5)
    assert law.characteristics().Vm == pytest.approx(2.0, rel=2e-3)  # cycloidal Vm = 2; 2° spacing spline error


@settings(max_examples=25, deadline=None)
@given(
    steps=st.lists(st.floats(0.5, 3.0), min_size=5, max_size=12),
    lifts=st.lists(st.floats(-2.0, 2.0), min_size=13, max_size=13),
)
def test_chord_bspline_interpolates_and_derivatives_agree_with_differences(steps, lifts):
    x = np.concatenate([[0.0], np.cumsum(steps)])
    y = np.cumsum(np.asarray(lifts[: len(x)]) * 0.2)
    try:
        f = chord_bspline(x, y)
    except ValueError:  # a fold-back is reported as InputError, never a wrong curve
        return
    assert np.allclose(f(x), y, atol=1e-9)  # interpolation, Newton to 1e-15
    xm = 0.5 * (x[:-1] + x[1:])
    h = 1e-5
    for k in range(1, 4):  # central difference of the (k−1)-th derivative, O(h²)
        fd = (f(xm + h, k - 1) - f(xm - h, k - 1)) / (2 * h)
        scale = 1 + np.max(np.abs(f(xm, k)))
        assert np.allclose(f(xm, k), fd, atol=1e-4 * scale * 10**k)  # step error h² f''' plus rounding / h
