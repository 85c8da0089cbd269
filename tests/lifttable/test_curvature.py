"""Profile curvature through the PlanarCurve protocol, and the comb plots."""

import numpy as np

from camcam.geometry.curve import FunctionCurve
from camcam.lifttable.curvature import profile_curvature
from camcam.plots.comb import profile_comb_png


def ellipse(t, k):
    c, s = np.cos(t), np.sin(t)
    return np.stack([[5 * c, 3 * s], [-5 * s, 3 * c], [-5 * c, -3 * s], [5 * s, -3 * c]][k], axis=-1)


def test_profile_curvature_of_an_ellipse_matches_closed_form():
    pc = profile_curvature(FunctionCurve(ellipse, 0.0, 2 * np.pi, closed=True, breaks_=(np.pi,)))
    exact = 15.0 / (25 * np.sin(pc.t) ** 2 + 9 * np.cos(pc.t) ** 2) ** 1.5  # ab / (a² sin² + b² cos²)^{3/2}
    assert np.allclose(pc.kappa, exact, rtol=1e-12)  # exact derivatives, rounding only
    assert abs(pc.min_radius - 9.0 / 5.0) < 1e-12  # b²/a at t = 0, a sample (break ends are included)


def test_profile_comb_png_is_deterministic():
    c = FunctionCurve(ellipse, 0.0, 2 * np.pi, closed=True)
    a, b = profile_comb_png(c), profile_comb_png(c)
    assert a.startswith(b"\x89PNG") and a == b
