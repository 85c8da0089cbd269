import math

import numpy as np
from hypothesis import given, settings, strategies as st

from camcam.toolpath.elements import Arc, Line, arc_from_tangent, element_distance


def test_arc_from_tangent_quarter_circle():
    a = arc_from_tangent((1.0, 0.0), (0.0, 1.0), (0.0, 1.0))
    assert isinstance(a, Arc) and a.ccw
    # closed form: centre at the origin, radius 1, sweep π/2 (float rounding only)
    assert np.allclose(a.centre, (0.0, 0.0), atol=1e-12)
    assert math.isclose(a.sweep, math.pi / 2, rel_tol=1e-12)


def test_flat_arc_becomes_line():
    # sagitta of a 10 mm chord on R = 1e6 mm is 1.25e-5 mm, below the 1e-4 line limit
    e = arc_from_tangent((0.0, 0.0), (1.0, 0.0), (10.0, 10.0**2 / (2 * 1e6)), line_sagitta=1e-4)
    assert isinstance(e, Line)


@settings(max_examples=60, deadline=None)
@given(st.floats(0.5, 20), st.floats(0.1, 3.0), st.floats(-3, 3), st.booleans(),
       st.floats(-30, 30), st.floats(-30, 30))
def test_distance_to_arc_matches_dense_sampling(r, sweep, a0, ccw, qx, qy):
    c = np.array([1.0, -2.0])
    s = -1 if not ccw else 1
    start = c + r * np.array([math.cos(a0), math.sin(a0)])
    end = c + r * np.array([math.cos(a0 + s * sweep), math.sin(a0 + s * sweep)])
    arc = Arc(tuple(start), tuple(end), tuple(c), ccw)
    pts = arc.points(20001)
    q = np.array([[qx, qy]])
    dense = np.hypot(*(pts - q).T).min()
    exact = element_distance(arc, q)[0]
    # the exact distance is a lower bound; dense sampling is within half a sample step (r·sweep/20000)
    assert exact <= dense + 1e-9
    assert dense - exact <= r * sweep / 20000 + 1e-9


def test_element_nearest_is_on_the_element_and_nearest():
    # against a dense sampling of the element: the exact nearest point can only be closer,
    # and by at most the sampling's half spacing (sweep 1.5 rad · r 5 / 20000 ≈ 4e-4 mm)
    import numpy as np

    from camcam.toolpath.elements import Arc, Line, element_nearest

    rng = np.random.default_rng(7)
    q = rng.uniform(-10, 10, size=(200, 2))
    for e in (Line((0.0, 0.0), (3.0, 4.0)), Arc((5.0, 0.0), (5 * np.cos(1.5), 5 * np.sin(1.5)), (0.0, 0.0), True)):
        p = element_nearest(e, q)
        dense = e.points(20001)
        brute = np.min(np.hypot(*(q[:, None, :] - dense[None, :, :]).transpose(2, 0, 1)), axis=1)
        exact = np.hypot(*(q - p).T)
        assert np.all(exact <= brute + 1e-12)
        assert np.all(brute - exact <= 5e-4)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(st.floats(-5, 5), st.floats(-5, 5), st.floats(0.5, 30), st.floats(-3.1, 3.1),
                          st.floats(0.01, 3.0), st.booleans(), st.floats(-1e-3, 1e-3), st.booleans()),
                min_size=1, max_size=6),
       st.integers(0, 2**32 - 1))
def test_element_distances_is_element_distance_bit_for_bit(specs, seed):
    # the closing biarcs' batched measurement must take the same decisions as one element at a time:
    # every row equal to element_distance's to the last bit (no tolerance: the same arithmetic)
    from camcam.toolpath.elements import element_distances

    els = []
    for cx, cy, r0, a0, sweep, ccw, dr, line in specs:
        c = np.array([cx, cy])
        s = 1 if ccw else -1
        p0 = c + r0 * np.array([math.cos(a0), math.sin(a0)])
        p1 = c + (r0 + dr) * np.array([math.cos(a0 + s * sweep), math.sin(a0 + s * sweep)])
        els.append(Line(tuple(p0), tuple(p1)) if line else Arc(tuple(p0), tuple(p1), tuple(c), ccw))
    q = np.random.default_rng(seed).uniform(-40, 40, (57, 2))
    got = element_distances(els, q)
    assert got.shape == (len(els), len(q))
    for k, e in enumerate(els):
        assert np.array_equal(got[k], element_distance(e, q))
