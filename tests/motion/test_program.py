import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from camcam.errors import MotionError
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.motion.standard import dwell


def demo(rpm=120.0):
    return MotionProgram(
        (
            Segment(make_law("modified-sine"), 0, 120, 20.0, base=0.0),
            Segment(dwell(), 120, 180, 0.0, base=20.0),
            Segment(make_law("cycloidal"), 180, 300, -20.0, base=20.0),
            Segment(dwell(), 300, 360, 0.0, base=0.0),
        ),
        rpm,
    )


def test_physical_units_closed_form():
    p = demo()
    w = 2 * math.pi * 120 / 60  # rad/s
    beta = math.radians(120)
    # cycloidal return: peak |v| = h·2·ω/β at its middle (240°); peak |a| = h·2π·(ω/β)²
    assert float(p.physical(math.radians(240), 1)) == pytest.approx(-20 * 2 * w / beta, rel=1e-12)
    lo, hi = p.extremes(2)
    assert hi.value == pytest.approx(20 * 2 * math.pi * (w / beta) ** 2 / 1000, rel=1e-12)  # m/s²
    assert hi.angle_deg == pytest.approx(270.0, abs=1e-9)
    assert lo.angle_deg == pytest.approx(210.0, abs=1e-9)
    # jerk in m/s³: modified sine 69.47 at its start
    _, jhi = p.extremes(3)
    assert jhi.value == pytest.approx(20 * make_law("modified-sine").characteristics().Jmax.value * (w / beta) ** 3 / 1000, rel=1e-12)


def test_lift_wraps_and_is_periodic():
    p = demo()
    th = np.radians([10.0, 370.0, -350.0])
    s = p.lift(th)
    assert s[0] == pytest.approx(s[1], abs=1e-12) and s[0] == pytest.approx(s[2], abs=1e-12)  # same angle


@given(st.lists(st.floats(-20.0, 20.0, allow_nan=False), min_size=1, max_size=40), st.integers(0, 4))
def test_lifts_is_lift_of_every_order(angles, K):
    # lifts() locates the segments once for all orders: the very same arithmetic as lift() per order,
    # so the rows agree exactly (no tolerance)
    p = demo()
    th = np.array(angles)
    rows = p.lifts(th, K)
    assert rows.shape == (K + 1, len(angles))
    for k in range(K + 1):
        np.testing.assert_array_equal(rows[k], p.lift(th, k))


def test_joins_of_a_smooth_program_are_empty():
    assert demo().joins == ()


def test_harmonic_into_dwell_reports_acceleration_jump():
    p = MotionProgram(
        (
            Segment(make_law("harmonic"), 0, 180, 10.0),
            Segment(dwell(), 180, 360, 0.0, base=10.0),
        ),
        60,
    )
    # the rise ends with A = −π²/2·h/β² into a dwell (A = 0), and starts with +π²/2·h/β² out of one
    joins = p.joins
    assert [(j.angle_deg, j.order) for j in joins] == [(0.0, 2), (180.0, 2)]
    w, beta = 2 * math.pi, math.pi
    expect = math.pi**2 / 2 * 10 * (w / beta) ** 2 / 1000  # m/s², closed form
    assert joins[0].jump == pytest.approx(expect, rel=1e-12)
    assert joins[1].jump == pytest.approx(expect, rel=1e-12)  # −(−x): A rises back to 0
    lo, hi = p.extremes(3)
    assert hi.value == math.inf and hi.angle_deg == 0.0  # honest infinite jerk at the jump
    with pytest.raises(MotionError, match="acceleration jumps by .* at 0°"):
        p.check_strict()


def test_harmonic_rise_and_return_is_smooth():
    # a harmonic rise straight into a harmonic return is one cosine: no jump anywhere
    p = MotionProgram(
        (Segment(make_law("harmonic"), 0, 180, 10.0), Segment(make_law("harmonic"), 180, 360, -10.0, base=10.0)), 60
    )
    assert p.joins == ()


def test_tiling_enforced():
    with pytest.raises(MotionError, match="tile 0–360"):
        MotionProgram((Segment(make_law("cycloidal"), 0, 350, 1.0),), 60)
