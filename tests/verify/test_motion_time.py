"""The motion-model cycle time (camcam.verify.motion_time): closed forms, GRBL's planner as published
(tests/verify/grbl_planner.py) on the GRBL sample, and the bound the feed-only figure gives."""

import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from camcam.errors import InputError
from camcam.geometry.build import build_cam
from camcam.nc.job import machine_program
from camcam.post.post import load_post, parse_post
from camcam.spec import load_spec
from camcam.verify.cycle_time import cycle_time
from camcam.verify.motion_time import junction_speed_sqr, motion_time

sys.path.insert(0, str(Path(__file__).parent))
from grbl_planner import grbl_time_of_text_s, grbl_time_s  # noqa: E402  (the test-side reference, not a package)

ROOT = Path(__file__).resolve().parents[2]


def _post(a_mm_s2=100.0, deviation_mm=0.01, rapid_mm_min=1e6, a_deg_s2=None, lookahead_blocks=0, arc_tolerance_mm=0.0):
    """GRBL's post with other limits; by default planning over the whole program, arcs as arcs."""
    return replace(load_post("grbl"), max_accel_mm_s2=a_mm_s2, max_accel_deg_s2=a_deg_s2 or a_mm_s2,
                   junction_deviation_mm=deviation_mm, rapid_mm_min=rapid_mm_min, lookahead_blocks=lookahead_blocks,
                   arc_tolerance_mm=arc_tolerance_mm)


def _line(start, end, feed_mm_min):
    return ("line", start, end, feed_mm_min, 0.0, 0.0)


def test_a_long_line_from_rest_to_rest():
    # 200 mm at 600 mm/min (10 mm/s), a = 100 mm/s²: ramps of 0.5 mm each way: t = L/v + v/a
    t = motion_time((_line((0.0, 0.0, 0.0), (200.0, 0.0, 0.0), 600.0),), _post()).total_s
    assert t == pytest.approx(200 / 10 + 10 / 100, rel=1e-12)  # closed form, same arithmetic: equal to rounding


def test_a_short_line_never_reaches_the_feed():
    # 0.4 mm: reaching 10 mm/s would take 1 mm; a triangle: t = 2·sqrt(L/a)
    t = motion_time((_line((0.0, 0.0, 0.0), (0.0, 0.4, 0.0), 600.0),), _post()).total_s
    assert t == pytest.approx(2 * math.sqrt(0.4 / 100), rel=1e-12)  # closed form: equal to rounding


def test_a_diagonal_takes_the_axes_share():
    # GRBL's limit_value_by_axis_maximum: along (1, 1)/√2 each axis carries 1/√2, so a = 100·√2
    t = motion_time((_line((0.0, 0.0, 0.0), (0.3, 0.3, 0.0), 600.0),), _post()).total_s
    assert t == pytest.approx(2 * math.sqrt(0.3 * math.sqrt(2) / (100 * math.sqrt(2))), rel=1e-12)  # closed form


def test_a_right_angle_corner():
    a, dev = 100.0, 0.01
    v2 = junction_speed_sqr(np.array([1.0, 0, 0, 0]), np.array([0.0, 1, 0, 0]), np.full(4, a), dev)[0]
    s = math.sqrt(0.5)  # sin(θ/2), θ = 90°; the junction vector (−1, 1)/√2 allows a·√2
    assert v2 == pytest.approx(a * math.sqrt(2) * dev * s / (1 - s), rel=1e-12)  # GRBL's formula: equal to rounding
    # two 50 mm lines at 10 mm/s through the corner: each from/to rest and to/from the corner speed
    moves = (_line((0.0, 0.0, 0.0), (50.0, 0.0, 0.0), 600.0), _line((50.0, 0.0, 0.0), (50.0, 50.0, 0.0), 600.0))
    vj, v = math.sqrt(v2), 10.0
    one = v / a + (v - vj) / a + (50 - (2 * v * v - vj * vj) / (2 * a)) / v
    assert motion_time(moves, _post(a, dev)).total_s == pytest.approx(2 * one, rel=1e-12)  # closed form


def test_straight_on_is_not_a_corner_and_a_reversal_stops():
    straight = (_line((0.0, 0.0, 0.0), (50.0, 0.0, 0.0), 600.0), _line((50.0, 0.0, 0.0), (100.0, 0.0, 0.0), 600.0))
    back = (_line((0.0, 0.0, 0.0), (50.0, 0.0, 0.0), 600.0), _line((50.0, 0.0, 0.0), (0.0, 0.0, 0.0), 600.0))
    assert motion_time(straight, _post()).total_s == pytest.approx(100 / 10 + 10 / 100, rel=1e-12)  # one ramp pair
    assert motion_time(back, _post()).total_s == pytest.approx(2 * (50 / 10 + 10 / 100), rel=1e-12)  # two


def test_an_arc_is_held_to_its_centripetal_limit():
    # a half circle of r = 1 mm at 6000 mm/min (100 mm/s); the arc's acceleration, along it and across it, is
    # a / mean max(|cos|, |sin|) = a / (2√2/π) over the half turn; v² ≤ a_arc·r, far under the feed
    arc = ("arc", (1.0, 0.0, 0.0), (-1.0, 0.0, 0.0), (0.0, 0.0), True, 6000.0)
    t = motion_time((arc,), _post()).total_s
    a_arc = 100 * math.pi / (2 * math.sqrt(2))
    v = math.sqrt(a_arc * 1.0)
    assert t == pytest.approx(math.pi / v + v / a_arc, rel=1e-12)  # closed form: equal to rounding


def test_a_short_look_ahead_is_grbls_buffer():
    # 100 collinear 0.1 mm blocks at 3000 mm/min, a = 100 mm/s²: GRBL's 16-block buffer plans each entry to a
    # stop 14 blocks on, v² ≤ 2·a·1.4 mm, far under the feed; the model's window says the same
    moves = tuple(_line((0.1 * i, 0.0, 0.0), (0.1 * (i + 1), 0.0, 0.0), 3000.0) for i in range(100))
    model = motion_time(moves, _post(lookahead_blocks=16)).total_s
    grbl = grbl_time_s(moves, acceleration_mm_s2=100.0, rapid_mm_min=1e6, junction_deviation_mm=0.01)
    # the same planner equations, in another order (0.1 mm = 25 steps: no step rounding): equal to rounding
    assert model == pytest.approx(grbl, rel=1e-9)
    # planning over the whole program: one 10 mm triangle, 2·sqrt(L/a) (a sum of 100 blocks: to rounding)
    assert motion_time(moves, _post()).total_s == pytest.approx(2 * math.sqrt(10.0 / 100.0), rel=1e-9)
    assert model > 1.15 * 2 * math.sqrt(10.0 / 100.0)  # the buffer costs 20 % here


@pytest.mark.parametrize("r_mm, feed_mm_min", [(0.5, 600.0), (2.0, 3000.0), (5.0, 1000.0), (20.0, 3000.0), (50.0, 6000.0)])
def test_an_arc_as_grbl_cuts_it(r_mm, feed_mm_min):
    # a 2 rad arc after a crawl to its start (1 mm/min: the join is all but a stop in both); GRBL cuts it
    # into chords at $12 = 0.002 mm and plans them over its buffer
    end = (r_mm * math.cos(2.0), r_mm * math.sin(2.0), 0.0)
    moves = (_line((0.0, 0.0, 0.0), (r_mm, 0.0, 0.0), 1.0), ("arc", (r_mm, 0.0, 0.0), end, (0.0, 0.0), True, feed_mm_min))
    crawl_s = 60.0 * r_mm
    model = motion_time(moves, _post(lookahead_blocks=16, arc_tolerance_mm=0.002)).total_s - crawl_s
    grbl = grbl_time_s(moves, acceleration_mm_s2=100.0, rapid_mm_min=1e6, junction_deviation_mm=0.01) - crawl_s
    # one arc with its mean axis share against chords each with its own (measured within 2.5 %)
    assert abs(model - grbl) <= 0.03 * grbl


def test_a_rotary_move_is_limited_by_its_a_share():
    # G93: 20 mm along X while A turns 90°; axis space |(20, 0, 0, 90)|; A carries 90/|d| of it
    d = math.hypot(20.0, 90.0)
    move = ("inverse", (0.0, 0.0, 30.0), (20.0, 0.0, 30.0), 600.0, 0.0, 90.0)  # 1/600 min = 0.1 s nominal
    post = _post(a_mm_s2=1e9, a_deg_s2=1000.0)
    a = 1000.0 / (90.0 / d)  # the slowest axis (A) limits the block
    v = d / 0.1
    expected = d / v + v / a if v * v / a < d else 2 * math.sqrt(d / a)
    assert motion_time((move,), post).total_s == pytest.approx(expected, rel=1e-12)  # closed form


@pytest.fixture(scope="module")
def grbl_sample():
    spec = load_spec(ROOT / "samples" / "posts" / "grbl.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    return machine_program(built, spec.machining, spec.name, spec.stock)


def test_grbl_sample_within_two_percent_of_grbls_planner(grbl_sample):
    post, moves = grbl_sample.post, grbl_sample.program.printed_moves
    model = motion_time(moves, post)
    # GRBL reads the program's text (not the writer's record of it)
    grbl = grbl_time_of_text_s(grbl_sample.program.text, acceleration_mm_s2=post.max_accel_mm_s2,
                               rapid_mm_min=post.rapid_mm_min, junction_deviation_mm=post.junction_deviation_mm)
    # the 2 % (measured 0.005 %): one arc with its mean axis share against GRBL's chords
    assert abs(model.total_s - grbl) <= 0.02 * grbl
    # and acceleration matters here: GRBL's default 10 mm/s² adds more than 2 % to the feed-only figure
    assert grbl > 1.02 * model.feed_only_s


@pytest.mark.parametrize("feed_mm_min, a_mm_s2", [(400.0, 1.0), (3000.0, 10.0), (3000.0, 1000.0)])
def test_grbl_sample_where_the_buffer_and_the_rapid_rate_bind(feed_mm_min, a_mm_s2):
    # GRBL's stopping distance beyond its 15 blocks of ~0.9 mm chords (a planner over the whole program was
    # 11 % and 21 % fast at the first two), and a feed above the 2500 mm/min axis rate (the third)
    spec = load_spec(ROOT / "samples" / "posts" / "grbl.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    result = machine_program(built, replace(spec.machining, feed_mm_min=feed_mm_min), spec.name, spec.stock)
    post = replace(result.post, max_accel_mm_s2=a_mm_s2, max_accel_deg_s2=a_mm_s2)
    model = motion_time(result.program.printed_moves, post).total_s
    grbl = grbl_time_of_text_s(result.program.text, acceleration_mm_s2=a_mm_s2, rapid_mm_min=post.rapid_mm_min,
                               junction_deviation_mm=post.junction_deviation_mm)
    assert abs(model - grbl) <= 0.02 * grbl  # the 2 % (measured within 0.85 %)


def test_the_reference_reproduces_the_closed_forms():
    # the transcription itself on one long line and on a short one (steps of 1/250 mm: exact here)
    long_s = grbl_time_s((_line((0.0, 0.0, 0.0), (200.0, 0.0, 0.0), 600.0),), acceleration_mm_s2=100.0,
                         rapid_mm_min=1e6, junction_deviation_mm=0.01)
    short_s = grbl_time_s((_line((0.0, 0.0, 0.0), (0.4, 0.0, 0.0), 600.0),), acceleration_mm_s2=100.0,
                          rapid_mm_min=1e6, junction_deviation_mm=0.01)
    assert long_s == pytest.approx(200 / 10 + 10 / 100, rel=1e-12)  # closed form: equal to rounding
    assert short_s == pytest.approx(2 * math.sqrt(0.4 / 100), rel=1e-12)  # closed form: equal to rounding


def test_passes_split_both_figures_and_sum_to_the_feed_only_total(grbl_sample):
    post, moves = grbl_sample.post, grbl_sample.program.printed_moves
    model = motion_time(moves, post)
    kinds = [p.label.split(" ", 1)[1] for p in model.passes[1:]]
    assert model.passes[0].label == "start" and set(kinds) == {"rough", "finish"}
    # the same lengths over the same rates as cycle_time, summed in another order: equal to rounding
    assert model.feed_only_s == pytest.approx(cycle_time(moves, post.rapid_mm_min).total_s, rel=1e-12)
    assert all(p.model_s >= p.feed_only_s for p in model.passes)


_coords = st.floats(-50, 50, allow_nan=False)


@st.composite
def programs(draw):
    pos = (0.0, 0.0, 0.0)
    moves = []
    for _ in range(draw(st.integers(1, 12))):
        kind = draw(st.sampled_from(["rapid", "line", "arc", "inverse", "tool change"]))
        if kind == "tool change":
            moves.append(("tool change", 5.0))
            continue
        if kind == "arc":
            r = draw(st.floats(0.5, 30))
            phi0, sweep = draw(st.floats(-3.1, 3.1)), draw(st.floats(0.05, 2.0))
            ccw = draw(st.booleans())
            centre = (pos[0] - r * math.cos(phi0), pos[1] - r * math.sin(phi0))
            phi1 = phi0 + (sweep if ccw else -sweep)
            end = (centre[0] + r * math.cos(phi1), centre[1] + r * math.sin(phi1), pos[2] + draw(_coords) / 10)
            moves.append(("arc", pos, end, centre, ccw, draw(st.floats(10, 2000))))
        else:
            end = (draw(_coords), draw(_coords), draw(_coords))
            if end == pos:
                continue
            if kind == "rapid":
                moves.append(("rapid", pos, end))
            elif kind == "line":
                moves.append(_line(pos, end, draw(st.floats(10, 2000))))
            else:
                moves.append(("inverse", pos, end, draw(st.floats(1, 500)), 0.0, draw(st.floats(-90, 90))))
        pos = moves[-1][2]
    return tuple(moves)


@settings(max_examples=200, deadline=None)
@given(programs(), st.floats(1.0, 5000.0), st.floats(0.001, 1.0), st.sampled_from([0, 3, 16]),
       st.sampled_from([0.0, 0.002]))
def test_acceleration_only_ever_slows(moves, a, dev, lookahead, arc_tol):
    # feeds within the rapid rate: the nominal durations are the feed-only ones
    post = _post(a, dev, rapid_mm_min=1e6, lookahead_blocks=lookahead, arc_tolerance_mm=arc_tol)
    t = motion_time(moves, post)
    # every block at or under its nominal speed takes at least its nominal time (rounding of a sum of ~12)
    assert t.total_s >= t.feed_only_s * (1 - 1e-12)
    fast = motion_time(moves, _post(1e12, dev, rapid_mm_min=1e6, a_deg_s2=1e12, lookahead_blocks=lookahead,
                                    arc_tolerance_mm=arc_tol))
    # a → ∞: the ramps take ~v/a ≤ 1e6/1e12 s each and the corners pass at full speed
    assert fast.total_s == pytest.approx(fast.feed_only_s, rel=1e-5, abs=1e-5)


@pytest.mark.parametrize("key, value", [("max_accel_mm_s2", 0.0), ("max_accel_deg_s2", -5.0),
                                        ("junction_deviation_mm", float("inf")), ("max_accel_mm_s2", "fast"),
                                        ("lookahead_blocks", 2), ("lookahead_blocks", 16.0),
                                        ("arc_tolerance_mm", 5.0)])
def test_bad_machine_limits_are_refused_naming_the_key(key, value):
    data = {"description": "d", "extension": "nc", "units": "G21", "decimals": 3, "arc_format": "r",
            "max_arc_sweep_deg": 120.0, "header": ["G21"], "footer": ["M2"], key: value}
    with pytest.raises(InputError, match=rf"post p: {key}: expected"):
        parse_post(data, "p")


def test_every_bundled_post_states_its_limits():
    for name in ("fanuc", "grbl", "haas", "heidenhain", "linuxcnc", "sinumerik"):
        text = (ROOT / "camcam" / "post" / "data" / f"{name}.toml").read_text()
        assert all(key in text for key in ("max_accel_mm_s2", "max_accel_deg_s2", "junction_deviation_mm"))
