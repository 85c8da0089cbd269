"""Cycle time: the printed moves timed (camcam.verify.cycle_time) against sums worked out by hand on small programs."""

import math

import pytest

from camcam.post.gcode import write_program
from camcam.post.post import load_post
from camcam.verify.cycle_time import cycle_time
from camcam.toolpath.path import ArcMove, Feed, Rapid, Toolpath


def test_three_axis_program_against_a_hand_sum():
    moves = (Rapid(None, None, 25.0), Rapid(10.0, 0.0, None), Rapid(None, None, 2.0), Feed(None, None, -3.0, 100.0),
             ArcMove(0.0, 10.0, 0.0, 0.0, ccw=True, z=-3.0, feed_mm_min=400.0), Feed(0.0, 30.0, -3.0, 400.0),
             Rapid(None, None, 25.0))
    post = load_post("linuxcnc")  # rapid_mm_min 5000, tool_change_s 10
    t = cycle_time(write_program(Toolpath.of_moves("hand", moves, 1000.0), post).printed_moves, post.rapid_mm_min)
    # by hand: rapids 25 (from Z0, where rs274 starts) + 10 + 23 + 28 = 86 mm at 5000 mm/min = 1.032 s;
    # plunge 5 mm at 100 mm/min = 3 s; quarter circle π·10/2 mm at 400 mm/min = 2.356194 s;
    # line 20 mm at 400 mm/min = 3 s; one tool change 10 s
    hand_s = 86 / 5000 * 60 + 3.0 + math.pi * 5 / 400 * 60 + 3.0 + 10.0
    # same constant-rate model on exactly printable numbers: equal to rounding (the 2 % allows for
    # acceleration, which neither sum counts)
    assert t.total_s == pytest.approx(hand_s, rel=1e-12)
    assert t.rapid_mm == pytest.approx(86.0, rel=1e-12) and t.feed_mm == pytest.approx(25 + 5 * math.pi, rel=1e-12)
    assert t.tool_change_s == 10.0 and t.moves == 7


def test_inverse_time_moves_take_one_over_f_minutes():
    # G93: F = feed / length is printed; the controller takes 1/F minutes whatever the axes travel
    moves = (Rapid(None, None, 30.0), Feed(0.0, None, 20.0, 100.0, a_deg=0.0, length_mm=10.0),
             Feed(5.0, None, 20.0, 400.0, a_deg=90.0, length_mm=20.0))
    tp = Toolpath.of_moves("rot", moves, 1000.0, rotary=True)
    t = cycle_time(write_program(tp, load_post("linuxcnc")).printed_moves, load_post("linuxcnc").rapid_mm_min)
    # F10 → 6 s, F20 → 3 s; rapid 30 mm at 5000 mm/min = 0.36 s; tool change 10 s
    assert t.feed_s == pytest.approx(6.0 + 3.0, rel=1e-12)
    assert t.total_s == pytest.approx(9.0 + 0.36 + 10.0, rel=1e-12)


@pytest.mark.parametrize("name", ["heidenhain", "grbl", "haas"])
def test_rates_come_from_the_post(name):
    moves = (Rapid(None, None, 25.0), Feed(30.0, 0.0, 25.0, 300.0))
    post = load_post(name)
    t = cycle_time(write_program(Toolpath.of_moves("x", moves, 1000.0), post).printed_moves, post.rapid_mm_min)
    expected = 25 / post.rapid_mm_min * 60 + math.hypot(30.0, 0.0) / 300 * 60 + (post.tool_change_s if post.tool_change else 0)
    assert t.total_s == pytest.approx(expected, rel=1e-12)  # same arithmetic: equal to rounding
    assert (t.tool_change_s == 0) == (name == "grbl")  # GRBL has no tool changer
