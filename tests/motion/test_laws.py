"""Characteristic values of the textbook laws, and properties every law must have."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.motion.catalog import LAWS, make_law

# Reference values: Rothbart, Cam Design Handbook (2004), table 3.x; Norton, Cam Design
# and Manufacturing Handbook (2009), table 3-2; MCV 50 from Makino's カム機構 tables;
# Yu–Lee from seed 000 Table 3 (Vm 1.910, Am ±4.850 as printed, Jm 81.0) and the issue
# (1.911, ±4.88, +81.0).  Values printed to 4 significant digits: rtol 5e-4 is half a
# unit in the 4th digit.
TEXTBOOK = {
    "cycloidal": dict(Vm=2.0, Am=2 * math.pi, Jmax=4 * math.pi**2, Jmin=-4 * math.pi**2),
    "polynomial-345": dict(Vm=1.875, Am=5.7735, Jmax=60.0, Jmin=-30.0),
    "polynomial-4567": dict(Vm=2.1875, Am=7.5132, Jmax=42.0, Jmin=-52.5),
    "modified-trapezoid": dict(Vm=2.000, Am=4.888, Jmax=61.43, Jmin=-61.43),
    "modified-sine": dict(Vm=1.760, Am=5.528, Jmax=69.47, Jmin=-23.16),
    "modified-constant-velocity": dict(Vm=1.275, Am=8.013, Jmax=201.4, Jmin=-67.13),
    "yu-lee": dict(Vm=1.911, Am=4.88, Jmax=81.0),
    "harmonic": dict(Vm=math.pi / 2, Am=math.pi**2 / 2, Jmax=math.inf, Jmin=-math.pi**3 / 2),
    "parabolic": dict(Vm=2.0, Am=4.0, Jmax=math.inf, Jmin=-math.inf),
}
RTOL_TEXTBOOK = 5e-4  # half a unit in the 4th significant digit of the printed tables
RTOL_YU_LEE_AM = 2e-3  # issue quotes Am as 4.88 (3 digits): half a unit in the 3rd


@pytest.mark.parametrize("name", sorted(TEXTBOOK))
def test_characteristic_values_match_textbook(name):
    got = make_law(name).characteristics().as_dict()
    for key, ref in TEXTBOOK[name].items():
        if math.isinf(ref):
            assert got[key] == ref, f"{name} {key}: a jump of A must be reported as {ref}"
        else:
            rtol = RTOL_YU_LEE_AM if (name, key) == ("yu-lee", "Am") else RTOL_TEXTBOOK
            assert got[key] == pytest.approx(ref, rel=rtol), f"{name} {key}"


def test_every_law_has_a_reference():
    assert set(TEXTBOOK) == set(LAWS)


def test_closed_forms_exact():
    # Cycloidal and 3-4-5 extremes are exact closed forms: 1e-12 allows float rounding only.
    c = make_law("cycloidal").characteristics()
    assert c.Am == pytest.approx(2 * math.pi, abs=1e-12)
    assert c.Amax.T == pytest.approx(0.25, abs=1e-12)
    p = make_law("polynomial-345").characteristics()
    assert p.Am == pytest.approx(10 / math.sqrt(3), abs=1e-12)
    assert p.Amax.T == pytest.approx(0.5 - math.sqrt(3) / 6, abs=1e-12)


def test_extremes_are_not_beaten_by_a_dense_grid():
    # A 200,001-point grid can only come close to an exact extreme from inside.
    T = np.linspace(0, 1, 200_001)
    for name in LAWS:
        law = make_law(name)
        for order in (1, 2, 3):
            lo, hi = law.extreme(order, rest_ends=False)
            vals = law.evaluate(T, order)
            # 1e-9 relative: the grid evaluates the same formulas; only rounding may differ.
            assert vals.max() <= hi.value + 1e-9 * max(1, abs(hi.value)), (name, order)
            assert vals.min() >= lo.value - 1e-9 * max(1, abs(lo.value)), (name, order)
            # and the grid gets within its resolution of it (dT = 5e-6, |J'| < 1e4 → 0.05 in J)
            assert vals.max() == pytest.approx(hi.value, abs=0.05), (name, order)


@pytest.mark.parametrize("name", sorted(LAWS))
def test_boundary_values(name):
    law = make_law(name)
    # S(0) = 0 and S(1) = 1; the degree-11 Yu–Lee polynomial sums coefficients of
    # size ~4e3, so 1e-11 covers its rounding (others are exact to 1e-15).
    assert float(law.evaluate(0.0)) == pytest.approx(0.0, abs=1e-11)
    assert float(law.evaluate(1.0)) == pytest.approx(1.0, abs=1e-11)


@settings(max_examples=60, deadline=None)
@given(name=st.sampled_from(sorted(LAWS)), T=st.floats(0.01, 0.99))
def test_derivatives_match_finite_differences(name, T):
    law = make_law(name)
    h = 1e-6
    for order in (1, 2, 3):
        num = (law.evaluate(T + h, order - 1) - law.evaluate(T - h, order - 1)) / (2 * h)
        exact = law.evaluate(T, order)
        # A piece boundary between T±h makes a one-sided jump: skip those points.
        if hasattr(law, "breaks") and any(abs(T - b) < 2 * h for b in law.breaks):
            continue
        # Central difference error ~ h²·|f'''|/6 + rounding ε·|f|/h: ~1e-9·1e4 + 1e-16·1e2/1e-6 → 1e-4 abs.
        assert float(num) == pytest.approx(float(exact), abs=1e-4 * max(1, abs(float(exact)))), (name, order, T)


@settings(max_examples=40, deadline=None)
@given(b7=st.floats(-2, 2), b9=st.floats(-2, 2), b11=st.floats(-2, 2))
def test_yu_lee_family_keeps_its_boundary_conditions(b7, b9, b11):
    law = make_law("yu-lee", beta7=b7, beta9=b9, beta11=b11)
    s0, s1 = law.end_values()
    # Coefficients up to ~1e4·|β|; 1e-9 covers rounding of the sums.
    assert np.allclose(s0[:3], [0, 0, 0], atol=1e-9)
    assert np.allclose(s1[:3], [1, 0, 0], atol=1e-9)


def test_unknown_law_and_parameter():
    with pytest.raises(KeyError, match="unknown law 'foo'; known: cycloidal"):
        make_law("foo")
    with pytest.raises(KeyError, match="no parameter 'beta8'"):
        make_law("yu-lee", beta8=1.0)


@pytest.mark.parametrize("name", sorted(LAWS))
def test_evaluate_orders_is_evaluate_bit_for_bit(name):
    # evaluate_orders shares the piece lookup and the sinusoid between orders; it must change no value (the
    # sample programs' bytes rest on it), so the comparison is exact
    law = make_law(name)
    T = np.concatenate([np.linspace(0.0, 1.0, 401), [0.25, 0.5, 0.75]])
    got = law.evaluate_orders(T, range(5))
    for k in range(5):
        assert np.array_equal(got[k], law.evaluate(T, k)), f"{name} order {k}"
    with pytest.raises(ValueError, match="order"):
        law.evaluate_orders(T, (0, 5))
