import numpy as np
import pytest

from camcam.geometry.curve import FunctionCurve, PlanarCurve, arc_length, curvature, curvature_rate


def ellipse(a=3.0, b=2.0):
    def f(t, order):
        c, s = np.cos(t), np.sin(t)
        rows = [(a * c, b * s), (-a * s, b * c), (-a * c, -b * s), (a * s, -b * c)][order]
        return np.stack(rows, axis=-1)

    return FunctionCurve(f, 0.0, 2 * np.pi, closed=True)


def test_protocol():
    assert isinstance(ellipse(), PlanarCurve)


def test_ellipse_curvature_closed_form():
    E = ellipse()
    t = np.linspace(0, 6, 13)
    k = curvature(E, t)
    ref = 3 * 2 / (9 * np.sin(t) ** 2 + 4 * np.cos(t) ** 2) ** 1.5
    assert np.allclose(k, ref, rtol=1e-13)  # same closed form: rounding only


def test_curvature_rate_matches_finite_difference():
    E = ellipse()
    t = np.linspace(0.1, 6, 17)
    h = 1e-6
    from camcam.geometry.curve import speed

    num = (curvature(E, t + h) - curvature(E, t - h)) / (2 * h) / speed(E, t)
    # central difference O(h²) ≈ 1e-12 plus rounding ε/h ≈ 1e-10
    assert np.allclose(curvature_rate(E, t), num, atol=1e-8)


def test_arc_length_circle():
    E = ellipse(2.0, 2.0)
    assert arc_length(E, 0.0, np.pi) == pytest.approx(2 * np.pi, rel=1e-12)  # quad to 1e-12
