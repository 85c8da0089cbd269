
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.motion.piece import TrigPoly


@settings(max_examples=100, deadline=None)
@given(
    c0=st.floats(-5, 5), c1=st.floats(-5, 5),
    a=st.floats(-5, 5), b=st.floats(-5, 5), w=st.floats(0.5, 40), L=st.floats(0.05, 1.0),
)
def test_stationary_points_are_roots_and_complete(c0, c1, a, b, w, L):
    f = TrigPoly((c0, c1), a, b, w)
    roots = f.stationary_points(L)
    d = f.derivative()
    scale = abs(c1) + w * (abs(a) + abs(b)) + 1
    for r in roots:
        assert 0 < r < L
        # a root of f' in closed form: |f'(r)| within rounding of its terms (1e-9 relative)
        assert abs(float(d(r))) <= 1e-9 * scale
    # completeness: f' keeps its sign between consecutive roots (checked on a fine grid)
    u = np.linspace(0, L, 20001)
    sign = np.sign(d(u))
    changes = np.count_nonzero(np.diff(sign[np.abs(d(u)) > 1e-6 * scale]) != 0)
    assert changes <= len(roots)


def test_integral_and_derivative_invert():
    f = TrigPoly((1.0,), a=0.5, b=-0.25, omega=3.0)
    g = f.integral(7.0)
    assert float(g(0.0)) == pytest.approx(7.0, abs=1e-15)  # defined value at 0, exact
    u = np.linspace(0, 2, 11)
    assert np.allclose(g.derivative()(u), f(u), atol=1e-14)  # exact identities, rounding only


def test_degree_limit_with_sinusoid():
    with pytest.raises(ValueError, match="degree <= 1"):
        TrigPoly((0, 0, 1), a=1.0, omega=1.0)
    with pytest.raises(ValueError, match="omega must be > 0"):
        TrigPoly((0,), a=1.0)
