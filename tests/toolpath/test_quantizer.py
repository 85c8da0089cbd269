"""One printed rounding: the Quantizer agrees with exact decimal rounding, also on half-way values, and the
fitter, the writer and the rotary path all print through it."""

from __future__ import annotations

from decimal import ROUND_HALF_EVEN, Decimal

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.post.gcode import format_number
from camcam.post.post import load_post
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.toolpath.elements import Arc
from camcam.toolpath.quantizer import Quantizer


def _exact(v: float, d: int) -> int:
    """Reference: the exact binary value of v rounded to d decimals, ties to even (independent of the module)."""
    return int((Decimal(v) * Decimal(10) ** d).to_integral_value(rounding=ROUND_HALF_EVEN))


halfway = st.builds(lambda k, d, s: ((k + 0.5) / 10**d * s, d), st.integers(-10**7, 10**7), st.integers(3, 6),
                    st.sampled_from([1.0, -1.0]))


@settings(max_examples=400, deadline=None)
@given(halfway)
def test_half_way_values_round_exactly(vd):
    v, d = vd
    q = Quantizer(d)
    assert q.count(v) == _exact(v, d)
    assert int(q.count(np.array([v]))[0]) == _exact(v, d)  # the vector path decides the same way


def test_the_issue_value():
    # 292.66865 lies just above the half-way point in binary: the product 292.66865e4 rounds first, to
    # 2926686.5 exactly, and int(round(·)) then goes to even (…86) — one count short of the printed truth
    assert Quantizer(4).count(292.66865) == 2926687 == _exact(292.66865, 4)
    assert int(round(292.66865 * 10**4)) == 2926686
    assert format_number(292.66865, load_post("linuxcnc")) == "292.6687"


@settings(max_examples=300, deadline=None)
@given(st.floats(-5000, 5000, allow_nan=False), st.integers(3, 6))
def test_printed_text_reads_back_as_the_snapped_value(v, d):
    # the writer prints the count; parsing the printed text gives exactly the value the fitter measured
    post = load_post("linuxcnc")
    q = Quantizer(post.decimals)
    assert float(format_number(v, post)) == q.snap(v)
    assert Quantizer(d).snap(v) == _exact(v, d) / 10**d


def test_snap_elements_shares_joints_and_drops_collapsed():
    q = Quantizer(3)
    a = Arc((1.00049, 0.0), (0.0, 1.00049), (0.0, 0.0), True)
    b = Arc((0.0, 1.00049), (0.0, 1.0004), (0.0, 0.0), True)  # collapses to one printed point
    out = q.snap_elements((a, b))
    assert out == (Arc((1.0, 0.0), (0.0, 1.0), (0.0, 0.0), True),)


def test_r_format_rebuilds_the_centre_from_the_printed_radius():
    q = Quantizer(4, "r")
    e = Arc((10.00004, 0.0), (0.0, 10.00004), (0.00002, 0.00001), True)
    (p,) = q.printed_elements((e,))
    r = q.value(q.radius_count(e.start, e.centre))
    # the rebuilt centre lies at the printed radius from both printed ends (to float rounding)
    assert abs(np.hypot(*np.subtract(p.start, p.centre)) - r) < 1e-9
    assert abs(np.hypot(*np.subtract(p.end, p.centre)) - r) < 1e-9


def test_budget_floor_is_derived():
    # the README's floor 10^-d / 0.56: rounding over what is left after two sampling margins and the fit's share
    b = FitBudget()
    assert abs(b.floor_mm(Quantizer(4)) - 1e-4 / 0.56) < 1e-15
    assert b.holds(b.floor_mm(Quantizer(4)) * (1 + 1e-9), Quantizer(4))
    assert not b.holds(b.floor_mm(Quantizer(4)) * (1 - 1e-6), Quantizer(4))
    targets = list(DEFAULT_BUDGET.targets(0.01, Quantizer(4)))
    assert len(targets) == DEFAULT_BUDGET.attempts
    assert all(abs(t1 / t0 - DEFAULT_BUDGET.retry_factor) < 1e-12 for t0, t1 in zip(targets, targets[1:]))


@st.composite
def _coordinates(draw, decimals: int):
    """Any coordinate, or a printed value or a half-way point between two, or a few ulps off one of those:
    where the rounding is decided exactly."""
    if draw(st.booleans()):
        return draw(st.floats(-1e4, 1e4, allow_nan=False))
    v = (draw(st.integers(-10**6, 10**6)) + draw(st.sampled_from([0.0, 0.5, -0.5]))) / 10**decimals
    n = draw(st.integers(-4, 4))
    for _ in range(abs(n)):
        v = float(np.nextafter(v, np.inf if n > 0 else -np.inf))
    return v


@settings(max_examples=200, deadline=None)
@given(data=st.data(), decimals=st.integers(0, 9))
def test_snap_points_is_snap_point_of_each(data, decimals):
    """The contour's points counted as one array give the same floats, bit for bit, as point by point."""
    q = Quantizer(decimals)
    points = data.draw(st.lists(st.lists(_coordinates(decimals), min_size=1, max_size=3), max_size=8))
    got = q.snap_points(points)
    want = [q.snap_point(p) for p in points]
    assert [tuple(x.hex() for x in p) for p in got] == [tuple(x.hex() for x in p) for p in want]


@settings(max_examples=150, deadline=None)
@given(decimals=st.integers(3, 6), cx=st.floats(-500, 500), cy=st.floats(-500, 500), r=st.floats(0.05, 2000),
       a0=st.floats(0, 6.283), sweep=st.floats(0.01, 2.0), ccw=st.booleans())
def test_writer_prints_the_quantizers_r_word(decimals, cx, cy, r, a0, sweep, ccw):
    """The R word the writer prints is the Quantizer's (Quantizer.radius_count, the fitter's model of the
    printed arc), on random arcs at 3–6 decimals."""
    import dataclasses
    import math
    import re
    from decimal import Decimal

    from camcam.post.gcode import write_program
    from camcam.toolpath.path import ArcMove, Feed, Rapid, Toolpath

    post = dataclasses.replace(load_post("linuxcnc"), arc_format="r", decimals=decimals, max_radius_error_mm=1.0)
    q = post.quantizer
    a1 = a0 + (sweep if ccw else -sweep)
    start = (cx + r * math.cos(a0), cy + r * math.sin(a0))
    end = (cx + r * math.cos(a1), cy + r * math.sin(a1))
    if q.snap_point(start) == q.snap_point(end):
        return
    moves = (Rapid(x=start[0], y=start[1], z=1.0), Feed(x=start[0], y=start[1], z=0.0, feed_mm_min=300.0),
             ArcMove(x=end[0], y=end[1], cx=cx, cy=cy, ccw=ccw, z=0.0, feed_mm_min=300.0))
    text = write_program(Toolpath.of_moves("r", moves, 1000), post).text
    (word,) = re.findall(r"^G[23] .*\bR(-?[0-9.]+)", text, re.M)
    printed = int(Decimal(word).scaleb(decimals))
    assert printed == q.radius_count(start, (cx, cy))
    # and the contour the fitter measures (printed_elements) turns about a centre at that printed radius
    (arc,) = q.printed_elements((Arc(start, end, (cx, cy), ccw),))
    assert abs(math.dist(arc.start, arc.centre) - q.value(printed)) < 1e-9 * max(1.0, r)
