"""The Complex method's search coordinates: scaling and the mirror-symmetric subspace."""

import numpy as np
from hypothesis import given, settings, strategies as st

from camcam.optimize.coordinates import _metric, mirror_map, search_coordinates
from camcam.optimize.evaluation import EvaluationFunction, Problem
from camcam.optimize.exact import exact_optimum

TABLE4 = Problem(5, 18, False, "A", limits=(("V", 1.91), ("J", 81.0)))


@settings(max_examples=20, deadline=None)
@given(degree=st.sampled_from([3, 5, 7]), segments=st.integers(6, 24), seed=st.integers(0, 2**16))
def test_mirror_map_is_the_point_mirror_and_an_involution(degree, segments, seed):
    from camcam.optimize.space import BSplineSpace

    sp = BSplineSpace(degree, segments, False)
    R, r = mirror_map(sp)
    x = sp.initial_free() + 0.05 * np.random.default_rng(seed).standard_normal(sp.n_free)
    T = np.linspace(0.0, 1.0, 41)
    # S values are O(1); 1e-9 is float noise of the control-point solve
    assert np.allclose(sp.spline(R @ x + r)(T), 1.0 - sp.spline(x)(1.0 - T), atol=1e-9)
    assert np.allclose(R @ (R @ x + r) + r, x, atol=1e-9)  # mirroring twice is the identity


def test_symmetric_subspace_holds_the_asymmetric_optimum():
    f = EvaluationFunction(TABLE4)
    c = search_coordinates(f, TABLE4.space.initial_free(), scaled=False)
    assert c.symmetric and c.size == 8  # 17 free points, 9 tied by the mirror
    # the exact optimum, symmetrised, is feasible with the same objective (convexity, module docstring)
    e = exact_optimum(TABLE4)
    R, r = mirror_map(TABLE4.space)
    xs = (e.x + R @ e.x + r) / 2
    ic, ir = f.terms(xs)
    assert float(np.abs(R @ xs + r - xs).max()) < 1e-12  # it is in the subspace
    assert (ic <= 1e-9 * np.array([1.91, 81.0])).all()  # within the LP's 2e-9 relative tightening
    assert ir <= e.objective * (1 + 1e-9)  # not worse than the exact optimum (float noise only)
    y = np.linalg.lstsq(c.basis, xs - c.origin, rcond=None)[0]
    assert np.allclose(c.free(y), xs, atol=1e-9)  # and the search coordinates reach it


def test_scaled_coordinates_are_round_in_the_minimised_quantity():
    for p in (TABLE4, Problem(5, 7, True, "J", limits=(("V", 1.76), ("A", 5.53)))):
        f = EvaluationFunction(p)
        c = search_coordinates(f, p.space.initial_free(), scaled=True)
        # a unit step in any search direction changes the sampled objective quantity by 1 r.m.s.
        assert np.allclose(c.basis.T @ _metric(f) @ c.basis, np.eye(c.size), atol=1e-8)


def test_a_limit_on_a_v_keeps_the_whole_space():
    f = EvaluationFunction(Problem(5, 18, False, "A", limits=(("V", 1.91), ("AV", 8.0))))
    c = search_coordinates(f, f.problem.space.initial_free())
    assert not c.symmetric and c.size == 17  # A·V is not convex: the averaging argument fails
