"""A groove pass's ramp ends at a joint of its contour, so every move of the pass is a fitted element, measured
as printed (campaign case 49:29, tests/nc/data/slot-ramp-dwell-arc-49-29.toml)."""

import math
from pathlib import Path

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.geometry.build import build_cam
from camcam.nc.passes import ramp_loop_passes
from camcam.spec import load_spec
from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.path import ArcMove, CutSettings, Feed
from camcam.verify import checked

SPEC = Path(__file__).parent / "data" / "slot-ramp-dwell-arc-49-29.toml"


def _contour(radius, fractions, lines):
    """A closed contour about the origin: arcs of a circle (or its chords), cut at the angles ``fractions``."""
    a = 2 * math.pi * np.cumsum(np.asarray(fractions) / np.sum(fractions))
    a = np.concatenate([[0.0], a])
    p = [(float(radius * math.cos(t)), float(radius * math.sin(t))) for t in a]
    p[-1] = p[0]
    if lines:
        return tuple(Line(s, e) for s, e in zip(p[:-1], p[1:]))
    return tuple(Arc(s, e, (0.0, 0.0), True) for s, e in zip(p[:-1], p[1:]))


def _xy_moves(passes):
    """(pass index, move) of every move that ends at a stated XY and cuts (feeds and arcs below the top)."""
    return [(k, m) for k, p in enumerate(passes) for m in p.moves
            if isinstance(m, (Feed, ArcMove)) and m.x is not None and m.z is not None and m.z < 0]


@settings(max_examples=60, deadline=None)
@given(st.floats(5.0, 80.0), st.lists(st.floats(0.05, 1.0), min_size=3, max_size=9), st.booleans(),
       st.floats(0.5, 30.0), st.floats(0.2, 30.0), st.floats(1.0, 10.0), st.booleans())
def test_ramps_end_at_joints_within_the_angle(radius, fractions, lines, depth, stepdown, angle, spring):
    elements = _contour(radius, fractions, lines)
    joints = {e.end for e in elements}
    lengths = [e.length for e in elements]
    levels = [-min(depth, stepdown * k) for k in range(1, math.ceil(depth / stepdown - 1e-9) + 1)]
    cs = CutSettings(depth_mm=depth, stepdown_mm=stepdown, feed_mm_min=300.0, spindle_rpm=2000.0)
    passes = ramp_loop_passes(0, "slot", elements, levels, 0.0, angle, cs, spring)
    slope = math.tan(math.radians(angle))
    head = passes[0].moves[0]  # the rapid over the start: a joint
    at, z_prev = (head.x, head.y), 0.0
    assert at in {e.start for e in elements}
    total_ramp = 0.0
    for k, z in enumerate(levels):
        moves = [m for j, m in _xy_moves(passes) if j == k]
        assert all((m.x, m.y) in joints for m in moves)  # no point but the contour's own joints
        # the ramp: the whole elements from where the last lap ended whose length first reaches the drop at the angle
        i = next(j for j, e in enumerate(elements) if e.start == at)
        need, run, n = (z_prev - z) / slope, 0.0, 0
        while run < need * (1 + 1e-9):
            run, n = run + lengths[(i + n) % len(elements)], n + 1
        assert (z_prev - z) / run <= slope  # never steeper than the angle (the planner's hair of 1e-9 over the run)
        assert run - need < max(lengths) + 1e-9 * need  # and no more than one element past the drop's length
        assert all(m.z > z for m in moves[:n - 1]) and abs(moves[n - 1].z - z) <= 1e-12 * max(1.0, abs(z))
        lap = moves[n:]  # one lap at the level, back to where the ramp ended
        assert len(lap) == len(elements) and all(m.z == z for m in lap)
        assert (lap[-1].x, lap[-1].y) == (moves[n - 1].x, moves[n - 1].y)
        at, z_prev, total_ramp = (moves[n - 1].x, moves[n - 1].y), z, total_ramp + run
    # the start overshoots least: no joint's ramps add up to less (each joint's walked as the planner walks)
    for j in range(len(elements)):
        whole, i, z_prev = 0.0, j, 0.0
        for z in levels:
            run = 0.0
            while run < (z_prev - z) / slope * (1 + 1e-9):
                run, i = run + lengths[i], (i + 1) % len(elements)
            whole, z_prev = whole + run, z
        assert total_ramp <= whole + 1e-9 * whole  # float sums in another order
    if spring:
        assert passes[-1].kind == "spring"


def test_the_slot_of_case_49_29_cuts_within_its_tolerance():
    spec = load_spec(SPEC)
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    m = spec.machining
    r = checked(built, m, spec.name, spec.stock)
    (c,) = r.contours
    printed = c.deviation.max_deviation_mm
    joints = {e.end for e in c.fit.elements}
    cuts = [mv for mv in r.toolpath.moves if isinstance(mv, (Feed, ArcMove)) and mv.x is not None]
    assert all((mv.x, mv.y) in joints for mv in cuts)  # the ramp ended inside a dwell arc: (-65.328, 6.937)
    # the ramp of the one level: whole elements from the joint they overshoot the 293.9 mm run least from (from
    # the contour's first joint it took the 137 mm dwell arc whole, 82 mm over)
    (p,) = [p for p in r.toolpath.passes if p.kind == "slot"]
    cut = [mv for mv in p.moves if isinstance(mv, (Feed, ArcMove)) and mv.x is not None]
    ramp = cut[:len(cut) - len(c.fit.elements)]  # then one lap, element by element
    run = m.depth_mm / math.tan(math.radians(m.ramp_angle_deg))
    by_end = {e.end: e for e in c.fit.elements}
    length = sum(by_end[(mv.x, mv.y)].length for mv in ramp)
    assert run <= length < run + 5.0  # 3 mm over here: the nearest joint past the run from the best start
    assert 0.0041 < printed < m.tolerance_mm  # the fit's figure on the printed contour (4 decimals as reported)
    # the material check reads the program back: what is left and overcut is the contour's own figure, within the
    # check's resolution (it was 0.00537 left and 0.0047 overcut at the split)
    assert r.removal.material_left_mm <= m.tolerance_mm and r.removal.overcut_mm <= m.tolerance_mm
    assert all(ck.ok for ck in r.checks)
