"""A program's pieces in one table (camcam.motion.piece_table) give the segment loop's values bit for bit.

The sample programs' bytes rest on it (tests/make_sample_checksums.py records them), so every comparison
here is exact: the table does the loop's arithmetic element by element, only in fewer numpy calls.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.motion.catalog import LAWS, make_law
from camcam.motion.law import PiecewiseLaw
from camcam.motion.piece import TrigPoly
from camcam.motion.piece_table import MAX_INNER_BREAKS, PieceTable
from camcam.motion.program import MotionProgram, Segment
from camcam.motion.standard import dwell
from camcam.optimize.bspline_law import BSplineLaw
from camcam.optimize.space import BSplineSpace


def loop_lifts(program: MotionProgram, theta, K: int) -> np.ndarray:
    """The segment loop: each segment's law on its own angles (what the program did before the table)."""
    idx, T = program.locate(theta)
    out = np.empty((K + 1, len(T)))
    for i in np.unique(idx):
        m = idx == i
        for row, values in zip(out, program.segments[i].lifts(T[m], range(K + 1))):
            row[m] = values
    return out


def angles(program: MotionProgram, n: int, seed: int) -> np.ndarray:
    """Random angles, every segment boundary and its neighbours in float, 0, 2π and angles outside [0, 2π)."""
    rng = np.random.default_rng(seed)
    edges = np.radians([s.start_deg for s in program.segments] + [360.0])
    near = np.concatenate([edges, np.nextafter(edges, -np.inf), np.nextafter(edges, np.inf)])
    return np.concatenate([rng.uniform(0.0, 2 * math.pi, n), near, [-1.0, 7.5, 4 * math.pi + 0.3]])


@st.composite
def programs(draw):
    n = draw(st.integers(1, 6))
    cuts = sorted(draw(st.lists(st.floats(1.0, 359.0), min_size=n - 1, max_size=n - 1, unique=True)))
    edges = [0.0] + cuts + [360.0]
    if min(np.diff(edges)) < 0.5:
        cuts = list(np.linspace(0.0, 360.0, n + 1)[1:-1])
        edges = [0.0] + cuts + [360.0]
    segs, base = [], 0.0
    for a, b in zip(edges, edges[1:]):
        name = draw(st.sampled_from(sorted(LAWS) + ["dwell"]))
        law = dwell() if name == "dwell" else make_law(name)
        scale = 0.0 if name == "dwell" else draw(st.floats(-30.0, 30.0))
        segs.append(Segment(law, a, b, scale, base=base))
        base += scale
    return MotionProgram(tuple(segs), rpm=draw(st.floats(1.0, 3000.0)))


@settings(max_examples=60, deadline=None)
@given(program=programs(), seed=st.integers(0, 2**31), K=st.integers(0, 4))
def test_table_is_the_segment_loop_bit_for_bit(program, seed, K):
    assert program._table is not None  # every catalogue law is piecewise
    theta = angles(program, 300, seed)
    assert np.array_equal(program.lifts(theta, K), loop_lifts(program, theta, K))


def test_an_optimised_bspline_law_is_tabled_too():
    space = BSplineSpace(5, 7, True)
    law = BSplineLaw.from_free(space, space.initial_free() + 0.01 * np.sin(np.arange(space.n_free)))
    program = MotionProgram((Segment(law, 0, 150, 12.0), Segment(dwell(), 150, 200, 0.0, base=12.0),
                             Segment(law, 200, 360, -12.0, base=12.0)), rpm=300)
    assert program._table is not None
    theta = angles(program, 500, 7)
    assert np.array_equal(program.lifts(theta, 4), loop_lifts(program, theta, 4))


def test_a_law_of_many_pieces_keeps_the_loop():
    # more inner breaks than the table compares each angle with: the program evaluates segment by segment
    n = MAX_INNER_BREAKS + 2
    breaks = tuple(np.linspace(0.0, 1.0, n + 1))
    ramp = PiecewiseLaw("ramp", breaks, tuple(TrigPoly((b, 1.0)) for b in breaks[:-1]), rest_to_rest=False)
    program = MotionProgram((Segment(ramp, 0, 180, 10.0), Segment(ramp, 180, 360, -10.0, base=10.0)), rpm=60)
    assert PieceTable.of(program.segments) is None and program._table is None
    assert float(program.lift(math.radians(90.0))) == pytest.approx(5.0, abs=1e-12)  # T = 0.5 of a unit ramp, ×10


@pytest.mark.filterwarnings("ignore:All-NaN slice")  # the law's own check on a segment of NaN angles only
def test_nan_angle_is_refused_as_before():
    program = MotionProgram((Segment(make_law("cycloidal"), 0, 180, 10.0),
                             Segment(make_law("cycloidal"), 180, 360, -10.0, base=10.0)), rpm=60)
    with pytest.raises(ValueError, match="nan"):
        program.lifts(np.array([0.5, np.nan]), 2)


@settings(max_examples=40, deadline=None)
@given(program=programs(), K=st.integers(0, 4))
def test_table_at_the_laws_own_breaks(program, K):
    # T exactly at a law's inner break takes the piece that starts there (searchsorted "right"), and its
    # float neighbours the pieces either side: the pieces meet only up to rounding, so a wrong choice shows
    for i, seg in enumerate(program.segments):
        b = np.asarray(seg.law.breaks, float)
        T = np.unique(np.clip(np.concatenate([b, np.nextafter(b, -np.inf), np.nextafter(b, np.inf), [0.3, 0.7]]),
                              0.0, 1.0))
        got = program._table.lifts(np.full(len(T), i), T, range(K + 1))
        assert np.array_equal(got, np.array(seg.lifts(T, range(K + 1)))), f"segment {i} ({seg.law.name})"
