"""The Chebyshev copy's evaluation: the single-interval fast path and the in-place Clenshaw steps give the
bits of the plain recurrence, on one sub-interval and across several."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.geometry.curve import FunctionCurve
from camcam.toolpath.surrogate import ChebyshevCurve, chebyshev_curve


def _ellipse(t, k):
    c, s = np.cos(t), np.sin(t)
    return np.stack([[40 * c, 25 * s], [-40 * s, 25 * c], [-40 * c, -25 * s], [40 * s, -25 * c]][k], axis=-1)


# breaks every 0.5 rad: many sub-intervals, so a batch of parameters may fall in one or in several
CURVE = chebyshev_curve(FunctionCurve(_ellipse, 0.0, 2 * np.pi, closed=True,
                                      breaks_=tuple(np.linspace(0.0, 2 * np.pi, 13)[1:-1])))


def plain(c: ChebyshevCurve, t, order: int) -> np.ndarray:
    """The recurrence as first written (every point's terms gathered, fresh arrays each step)."""
    t = np.atleast_1d(np.asarray(t, float))
    idx = np.clip(np.searchsorted(c.knots, t, side="right") - 1, 0, len(c.series) - 1)
    lo, hi = c.knots[idx], c.knots[idx + 1]
    u = ((2.0 * t - lo - hi) / (hi - lo))[:, None]
    cc = c._tables[order][:, idx]
    u2 = 2.0 * u
    b1 = np.zeros((t.size, 2))
    b2 = np.zeros((t.size, 2))
    for k in range(cc.shape[0] - 1, 0, -1):
        b1, b2 = cc[k] + u2 * b1 - b2, b1
    return cc[0] + u * b1 - b2


@settings(max_examples=200, deadline=None)
@given(lo=st.floats(0.0, 2 * np.pi), width=st.floats(0.0, 2 * np.pi), n=st.integers(0, 50),
       order=st.integers(0, 3))
def test_evaluate_is_the_plain_recurrence_bit_for_bit(lo, width, n, order):
    # exact equality: the fitter's decisions (and so the printed program) depend on every bit
    t = np.linspace(lo, min(lo + width, 2 * np.pi), n)
    got, want = CURVE.evaluate(t, order), plain(CURVE, t, order)
    assert got.shape == want.shape == (n, 2)
    assert got.tobytes() == want.tobytes()


def test_one_sub_interval_and_several():
    one = np.linspace(0.1, 0.2, 7)  # inside the first sub-interval
    several = np.linspace(0.1, 6.0, 7)
    assert len({int(np.searchsorted(CURVE.knots, x, side="right")) for x in one}) == 1
    assert len({int(np.searchsorted(CURVE.knots, x, side="right")) for x in several}) > 1
    for t in (one, several, 3.0):
        assert CURVE.evaluate(t, 0).tobytes() == plain(CURVE, t, 0).tobytes()
    # and the copy is the ellipse (to its accuracy, 1e-7 mm, with the margin of the check's own sampling)
    np.testing.assert_allclose(CURVE.evaluate(several, 0), _ellipse(several, 0), atol=1e-6)
