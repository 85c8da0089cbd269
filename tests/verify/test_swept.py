"""The slabs swept one per process (camcam.verify.swept) give the figures of one pass over moves and slabs together."""

import numpy as np
import shapely
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st
from shapely.geometry import LineString, Point

from camcam.verify.swept import (CUT_QUAD_SEGS, PROBE_INSET_MM, SAMPLE_MM, TOUCH_MM, cut_below, front_extent, moves_of,
                             sweep_slabs, where)
from camcam.verify.rs274 import CanonMove

R_T = 5.0  # tool radius (Ø10)
RECT = shapely.box(0.0, 0.0, 100.0, 50.0)  # the blank, top at Z0
SLOT_KINDS = ("slot",)
#: How far a swept polygon (CUT_QUAD_SEGS segments a quarter circle) falls short of its circles, for R_T (mm).
_SHORTFALL = R_T * (1.0 - np.cos(np.pi / (4 * CUT_QUAD_SEGS)))


def _one_pass(moves, slabs, bounds, r_t, slope, rounding, slot_kinds):
    """The sweep as it was before the slabs were split (camcam.verify.removal._remove at a161acf): every move in
    program order against every slab in turn, each plunge and rapid counted once (the first slab that
    meets it), the largest engagement the first met.  Kept here as the oracle."""
    slabs = list(slabs)
    eng, eng_at, slot_eng = 0.0, "", 0.0
    plunges, plunge_at, rapids, rapid_at = 0, "", 0, ""

    def slab_hits(i, geom) -> bool:
        return float(shapely.distance(slabs[i], geom)) < r_t - TOUCH_MM if not slabs[i].is_empty else False

    for m in moves:
        z0, z1 = m.p0[2], m.p1[2]
        zlo = min(z0, z1)
        if m.kind == "rapid":
            geom = LineString([m.p0[:2], m.p1[:2]]) if m.p0[:2] != m.p1[:2] else Point(m.p1[:2])
            for i in range(len(slabs)):
                if bounds[i] > zlo + 1e-6 and slab_hits(i, geom):
                    rapids += 1
                    rapid_at = rapid_at or where(m.pass_label, m.p1)
                    break
            continue
        pts = m.samples(SAMPLE_MM)
        xy_len = m.xy_length
        if z1 < z0 - 1e-9 and (z0 - z1) > xy_len * slope + rounding:
            geom = LineString(pts[:, :2]) if xy_len > 0 else Point(m.p1[:2])
            for i in range(len(slabs)):
                if bounds[i] > z1 + 1e-6 and bounds[i + 1] < z0 - 1e-6 and slab_hits(i, geom):
                    plunges += 1
                    plunge_at = plunge_at or where(m.pass_label, m.p1)
                    break
        if xy_len > 0 and len(pts) > 1:
            d = np.diff(pts[:, :2], axis=0)
            norm = np.hypot(d[:, 0], d[:, 1])
            ok = norm > 0
            probe_pts, tang, zs = pts[1:][ok], d[ok] / norm[ok, None], pts[1:, 2][ok]
            for i in range(len(slabs)):
                sel = zs <= bounds[i + 1] + 1e-6
                if not sel.any() or slabs[i].is_empty:
                    continue
                w = front_extent(slabs[i], probe_pts[sel, :2], tang[sel], r_t - PROBE_INSET_MM)
                k = int(np.argmax(w))
                if m.pass_kind in slot_kinds:
                    slot_eng = max(slot_eng, float(w[k]))
                elif w[k] > eng:
                    eng, eng_at = float(w[k]), where(m.pass_label, probe_pts[sel][k])
        for i in range(len(slabs)):
            slabs[i] = cut_below(slabs[i], pts, bounds[i + 1], r_t)  # the same cut as before, shared
    return slabs, eng, eng_at, slot_eng, plunges, plunge_at, rapids, rapid_at


_coord = st.sampled_from([-12.0, 0.0, 8.0, 25.0, 40.0, 60.0, 92.0, 112.0])
_step = st.one_of(
    st.tuples(st.just("marker"), st.sampled_from(["rough", "slot", "finish"])),
    st.tuples(st.sampled_from(["line", "line", "rapid"]), _coord, _coord, st.sampled_from([5.0, 0.0, -1.0, -2.0, -3.0])))


def _program(steps):
    events, n = [], 0
    for s in steps:
        if s[0] == "marker":
            n += 1
            events.append(f"pass {n}/9: {s[1]}, test")
        else:
            events.append(CanonMove(s[0], s[1], s[2], s[3], a=0.0))
    return events


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.lists(_step, min_size=3, max_size=9))
# a plunge through three slabs, one into one, a rapid through two: each counted once
@example([("marker", "rough"), ("rapid", 40.0, 25.0, 5.0), ("line", 40.0, 25.0, -3.0), ("line", 60.0, 25.0, -3.0),
          ("rapid", 60.0, 25.0, 5.0), ("rapid", -12.0, 40.0, 5.0), ("line", -12.0, 40.0, -1.0),
          ("line", 8.0, 40.0, -1.0), ("line", 8.0, 40.0, -2.0), ("line", 25.0, 40.0, -2.0), ("rapid", 92.0, 40.0, -2.0)])
# a run of three lines cut as one line's buffer: a region GEOS does not call equal to the moves' own cuts
@example([("line", -12.0, -12.0, 5.0), ("line", 0.0, 0.0, -1.0), ("line", 0.0, -12.0, -1.0),
          ("line", -12.0, -12.0, -1.0)])
def test_split_sweep_is_the_one_pass_sweep(steps):
    moves = moves_of(_program(steps))
    levels = sorted({round(m.p1[2], 6) for m in moves if m.kind != "rapid" and m.p0[2] == m.p1[2] and m.p1[2] < 0.0},
                    reverse=True)
    bounds = [0.0] + levels
    slope, rounding = np.tan(np.radians(3.0)), 2e-4

    def fresh():
        slabs = [shapely.Polygon(RECT) for _ in levels]
        for s in slabs:
            shapely.prepare(s)
        return slabs

    want = _one_pass(moves, fresh(), bounds, R_T, slope, rounding, SLOT_KINDS)
    if len(steps) == 11:  # the example above
        assert want[4] == 2 and want[6] == 1  # the plunges at X40 (three slabs) and X8 (one), the rapid
    for workers in (1, 2):
        got = sweep_slabs(moves, fresh(), bounds, R_T, slope, rounding, SLOT_KINDS, workers)
        # the same figures to the bit and the same places: the same computations, only regrouped
        assert (got.engagement_mm, got.engagement_where, got.slot_engagement_mm, got.plunges, got.plunge_where,
                got.rapids, got.rapid_where) == want[1:]
        assert len(got.slabs) == len(want[0])
        # the same regions left, up to how they are noded: a slab skips a path it has cleared already (the
        # test below), and cuts a run of moves as one line's buffer (_batch_step), not move by move; both
        # polygons fall short of the true region by at most r·(1 − cos(π/128)), so what one holds and the
        # other does not is slivers no thicker than that
        for a, b in zip(got.slabs, want[0]):
            assert a.symmetric_difference(b).buffer(-_SHORTFALL).is_empty
            assert abs(a.area - b.area) <= _SHORTFALL * (a.length + b.length)


def test_ties_go_to_the_first_move_and_slab():
    # a ramp from Z0 to Z-3 through untouched material meets the full width 2·r at every sample of every slab;
    # slab i probes only its samples at or below its floor, so each slab names a different first point: the
    # figure is the top slab's (the first of the tie in (move, slab) order), at the first sample below Z-1.
    # The flat cuts afterwards only make the levels (and meet the same width again, later: not named)
    events = ["pass 1/2: rough, ramp", CanonMove("rapid", -12.0, 25.0, 5.0, a=0.0),
              CanonMove("line", -12.0, 25.0, 0.0, a=0.0),
              CanonMove("line", 112.0, 25.0, -3.0, a=0.0), "pass 2/2: rough, levels"]
    for z in (-1.0, -2.0, -3.0):
        events += [CanonMove("rapid", -12.0, 5.0, 5.0, a=0.0), CanonMove("line", -12.0, 5.0, z, a=0.0),
                   CanonMove("line", 112.0, 5.0, z, a=0.0), CanonMove("rapid", 112.0, 5.0, 5.0, a=0.0)]
    moves = moves_of(events)
    bounds = [0.0, -1.0, -2.0, -3.0]
    slope = np.tan(np.radians(3.0))
    slabs = [shapely.Polygon(RECT) for _ in bounds[1:]]
    got = sweep_slabs(moves, slabs, bounds, R_T, slope, 2e-4, SLOT_KINDS, 2)
    want = _one_pass(moves, slabs, bounds, R_T, slope, 2e-4, SLOT_KINDS)
    # both ends of the span at the tool's edge: (r − inset) + inset on each side, exactly 2·r up to rounding
    assert abs(got.engagement_mm - 2 * R_T) < 1e-9
    assert (got.engagement_mm, got.engagement_where) == want[1:3]
    z = float(got.engagement_where.rsplit("Z", 1)[1])
    assert "ramp" in got.engagement_where and -1.1 < z <= -1.0  # samples every 0.5 mm fall 0.012 mm in Z


def test_a_path_cut_again_one_level_deeper_is_not_swept_again_in_the_slab_above(monkeypatch):
    """The finishing contour at Z-2 passes through the slab above along the path the Z-1 pass has cleared: that
    slab skips it (nothing lies in front of it, nothing is left to cut), with the figures of the one-pass sweep
    that probes and cuts it, and the same regions left (not re-noded by a difference that removes nothing)."""
    import camcam.verify.swept as sweep_module

    events = ["pass 1/2: finish, Z-1"]
    for z in (-1.0, -2.0):
        events += [CanonMove("rapid", -12.0, 25.0, 5.0, a=0.0), CanonMove("line", -12.0, 25.0, z, a=0.0),
                   CanonMove("line", 112.0, 25.0, z, a=0.0), CanonMove("rapid", 112.0, 25.0, 5.0, a=0.0)]
        events.append("pass 2/2: finish, Z-2")
    moves = moves_of(events[:-1])
    bounds = [0.0, -1.0, -2.0]
    slope = np.tan(np.radians(3.0))
    real = sweep_module.front_extent
    # r_t = 40 mm: the swept polygons fall 0.012 mm short of their circles, more than the probe's 0.01 mm inset,
    # so a probe of the repeated path could find a sliver the first pass left: it is probed again
    for r_t, probes in ((R_T, 2), (40.0, 3)):
        blank = RECT if r_t == R_T else shapely.box(0.0, 0.0, 100.0, 200.0)  # material left above the big tool
        fresh = lambda: [shapely.Polygon(blank) for _ in bounds[1:]]  # noqa: E731
        want = _one_pass(moves, fresh(), bounds, r_t, slope, 2e-4, SLOT_KINDS)
        probed = []
        monkeypatch.setattr(sweep_module, "front_extent", lambda *a: probed.append(1) or real(*a))
        got = sweep_slabs(moves, fresh(), bounds, r_t, slope, 2e-4, SLOT_KINDS, 1)
        # R_T: the Z-1 line in the top slab and the Z-2 line in the lower one, not the Z-2 line in the top slab
        assert len(probed) == probes
        assert (got.engagement_mm, got.engagement_where, got.plunges, got.rapids) == \
            (want[1], want[2], want[4], want[6])
        for a, b in zip(got.slabs, want[0]):
            # the same region: nothing of either outside the other (GEOS's own test), the same area to rounding
            assert a.equals(b) and abs(a.area - b.area) <= 1e-9 * b.area


_pocket = st.tuples(st.floats(-20.0, 20.0), st.floats(-20.0, 20.0), st.floats(0.5, 15.0))


@settings(max_examples=60, deadline=None)
@given(st.lists(_pocket, min_size=0, max_size=4), st.floats(-1.0, 1.0), st.floats(-1.0, 12.0),
       st.integers(1, 6), st.booleans())
# one sample at (-8, -3) heading +X, a pocket to its left, then to its right: the span's high end, then its low
# end, inside the semicircle; over 0.015 mm below the width (a bound one step too tight drops it)
@example([(-7.0, 1.0, 3.0)], 0.0, 5.0, 1, True)
@example([(-7.0, -7.0, 3.0)], 0.0, 5.0, 1, True)
def test_a_width_that_cannot_exceed_over_is_not_bisected_and_the_largest_is_the_same(pockets, turn, over, n, near):
    """``front_extent(..., over)`` against the full bisection: every sample it returns above 0 has its full
    width, and whenever the largest full width exceeds ``over`` it is found at the same (first) sample.
    ``near``: ``over`` within ±0.2 mm of the largest width (about two probe steps), where a bound one step
    too tight would drop it."""
    slab = shapely.box(-30.0, -30.0, 30.0, 30.0)
    for x, y, r in pockets:  # material already cut: the spans break up and end inside the semicircle
        slab = slab.difference(Point(x, y).buffer(r, quad_segs=16))
    shapely.prepare(slab)
    pts = np.column_stack([np.linspace(-8.0, 8.0, n), np.linspace(-3.0, 5.0, n)])
    t = np.tile([np.cos(turn), np.sin(turn)], (n, 1))
    full = front_extent(slab, pts, t, R_T - PROBE_INSET_MM)
    if near:
        over = float(full.max()) - 0.2 + 0.4 * (over + 1.0) / 13.0
    some = front_extent(slab, pts, t, R_T - PROBE_INSET_MM, over)
    kept = some > 0
    # the same arithmetic on the same probes for the samples it bisects: equal to the bit
    assert np.array_equal(some[kept], full[kept])
    assert np.all(full[~kept] <= max(over, 0.0))  # the ones it left could not exceed over (or met nothing)
    if full.max() > over:
        assert int(np.argmax(some)) == int(np.argmax(full)) and some.max() == full.max()


def _spiral_program(turns: float, drop: float, seg_mm: float, start_deg: float, levels: int, arcs_every: int):
    """A roughing spiral of tool centres from 40 mm to 40 − ``drop`` mm about (50, 50), around a Ø76 mm disc of
    material, in lines about ``seg_mm`` long (every ``arcs_every``-th move an arc instead), at ``levels``
    depths; then a finishing circle of 180 lines at 35.5 mm, at the last depth.  The spiral meets more
    material move after move; after a drop of 4 mm the finishing circle takes a ring 0.5 mm thick."""
    events = []
    for lv in range(1, levels + 1):
        z = -1.0 * lv
        events += [f"pass {lv}/9: rough, spiral Z{z:g}", CanonMove("rapid", 95.0, 50.0, 5.0, a=0.0),
                   CanonMove("line", 95.0, 50.0, z, a=0.0)]
        a0 = np.radians(start_deg)
        n = int(turns * 2 * np.pi * 40.0 / seg_mm)
        for k in range(n + 1):
            a = a0 + 2 * np.pi * turns * k / n
            r = 40.0 - drop * k / n
            x, y = 50.0 + r * np.cos(a), 50.0 + r * np.sin(a)
            if arcs_every and k % arcs_every == 0 and k:
                events.append(CanonMove("arc", x, y, z, a=0.0, centre=(50.0, 50.0), ccw=True))
            else:
                events.append(CanonMove("line", x, y, z, a=0.0))
        events.append(CanonMove("rapid", x, y, 5.0, a=0.0))
    events.append("pass 9/9: finish, circle")
    events += [CanonMove("rapid", 85.5, 50.0, 5.0, a=0.0), CanonMove("line", 85.5, 50.0, -levels, a=0.0)]
    for k in range(1, 181):
        a = np.radians(2.0 * k)
        events.append(CanonMove("line", 50.0 + 35.5 * np.cos(a), 50.0 + 35.5 * np.sin(a), -levels, a=0.0))
    return events


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.floats(0.6, 2.2), st.floats(1.0, 9.0), st.floats(0.2, 2.5), st.floats(0.0, 360.0), st.integers(1, 2),
       st.sampled_from([0, 7]))
@example(1.5, 4.0, 0.3, 0.0, 2, 0)
@example(2.0, 7.0, 1.0, 0.0, 1, 0)  # regions whose difference is slivers up to 0.013 mm from the other's outline
def test_batched_moves_give_the_move_by_move_figures(turns, drop, seg_mm, start_deg, levels, arcs_every):
    """Runs of feed moves probed and cut in batches (camcam.verify.swept._batch_step): the figures of the one-pass
    sweep to the bit, where its engagement grows move after move (a spiral inwards) and where it does not (the
    finishing ring), and the regions the same up to the swept polygons' shortfall from their circles."""
    moves = moves_of(_spiral_program(turns, drop, seg_mm, start_deg, levels, arcs_every))
    bounds = [0.0] + [-1.0 * lv for lv in range(1, levels + 1)]
    disc = shapely.Point(50.0, 50.0).buffer(38.0, quad_segs=64)
    slope = np.tan(np.radians(3.0))
    fresh = lambda: [shapely.Polygon(disc) for _ in bounds[1:]]  # noqa: E731
    want = _one_pass(moves, fresh(), bounds, R_T, slope, 2e-4, SLOT_KINDS)
    got = sweep_slabs(moves, fresh(), bounds, R_T, slope, 2e-4, SLOT_KINDS, 1)
    # the batch's widths are the move-by-move widths wherever a move can set a figure: the same arithmetic
    assert (got.engagement_mm, got.engagement_where, got.slot_engagement_mm, got.plunges, got.rapids) == \
        (want[1], want[2], want[3], want[4], want[6])
    assert got.engagement_mm > 0.0  # the spiral meets material
    # a batch's swept region is one line's buffer, not the union of its moves' buffers: both fall short of the
    # true region by at most r·(1 − cos(π/128)) (1.5e-3 mm for R_T), so what one holds and the other does not
    # is slivers no thicker than that (taking it off every side leaves nothing)
    for a, b in zip(got.slabs, want[0]):
        assert a.symmetric_difference(b).buffer(-_SHORTFALL).is_empty
        assert abs(a.area - b.area) <= _SHORTFALL * (a.length + b.length)


def test_a_contour_of_short_lines_is_probed_in_batches(monkeypatch):
    """The finishing ring of 180 lines (one sample each side of every joint) takes far fewer probes than moves,
    with the one-pass sweep's figures; without batches (BATCH_SAMPLES = 0) one probe a move."""
    import camcam.verify.swept as sweep_module

    moves = moves_of(_spiral_program(1.0, 4.0, 2.0, 0.0, 1, 0))
    bounds = [0.0, -1.0]
    disc = shapely.Point(50.0, 50.0).buffer(38.0, quad_segs=64)
    real = sweep_module.front_extent
    counts, batched = {}, sweep_module.BATCH_SAMPLES
    for size in (batched, 0):
        probed = []
        monkeypatch.setattr(sweep_module, "front_extent", lambda *a: probed.append(1) or real(*a))
        monkeypatch.setattr(sweep_module, "BATCH_SAMPLES", size)
        got = sweep_slabs(moves, [shapely.Polygon(disc)], bounds, R_T, np.tan(np.radians(3.0)), 2e-4, SLOT_KINDS, 1)
        counts[size] = (len(probed), got.engagement_mm, got.engagement_where)
    feed = sum(m.kind != "rapid" for m in moves)
    assert counts[0][0] >= feed - 2  # one a feed move (the plunge and a zero-width move aside)
    assert counts[batched][0] < feed / 4
    assert counts[0][1:] == counts[batched][1:]
