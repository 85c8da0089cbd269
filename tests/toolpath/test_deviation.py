import math

import numpy as np

from camcam.toolpath.deviation import closest_params, measure_deviation
from camcam.toolpath.elements import Arc, Line
from tests.nc_curves import ellipse


def circle_curve(r):
    from camcam.geometry.curve import FunctionCurve

    def f(t, k):
        c, s = np.cos(t), np.sin(t)
        return r * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], axis=-1)

    return FunctionCurve(f, 0.0, 2 * math.pi, closed=True)


def test_concentric_arcs_deviate_by_radius_difference():
    C = circle_curve(10.0)
    arcs = [Arc((10.01 * math.cos(a), 10.01 * math.sin(a)), (10.01 * math.cos(b), 10.01 * math.sin(b)), (0.0, 0.0), True)
            for a, b in zip(np.linspace(0, 2 * math.pi, 5)[:-1], np.linspace(0, 2 * math.pi, 5)[1:])]
    d = measure_deviation(C, arcs, margin_mm=1e-5)
    # both ways the distance is exactly 0.01 (closed form); the report adds the stated margin
    assert abs(d.path_to_curve_mm - 0.01) < 1e-9
    assert abs(d.curve_to_path_mm - 0.01) < 1e-9
    assert d.max_deviation_mm <= 0.01 + 1e-5 + 1e-9


def test_missing_piece_is_seen_from_the_curve_side():
    C = circle_curve(10.0)
    half = [Arc((10.0, 0.0), (-10.0, 0.0), (0.0, 0.0), True)]
    d = measure_deviation(C, half, 0.0, 2 * math.pi)
    # the bottom of the circle (0, -10) is 10√2 from either end of the upper half; sampling is exact to 1e-6
    assert abs(d.curve_to_path_mm - 10 * math.sqrt(2)) < 1e-6
    assert d.path_to_curve_mm < 1e-9  # the half lies on the circle: rounding only


def test_closest_point_on_ellipse_is_normal_foot():
    E = ellipse()
    q = np.array([[40.0, 5.0], [-3.0, 25.0], [0.0, 0.5]])
    t, d = closest_params(E, q, 0.0, 2 * math.pi)
    p, dp = E.evaluate(t, 0), E.evaluate(t, 1)
    # at the foot (P − q) ⟂ P′: Newton converged to rounding level
    assert np.all(np.abs(np.einsum("ij,ij->i", p - q, dp)) < 1e-8)
    dense = E.evaluate(np.linspace(0, 2 * math.pi, 200001), 0)
    ref = np.array([np.hypot(*(dense - x).T).min() for x in q])
    # dense reference is within (step)²·κ/8 ≈ 1e-8 of the true distance
    assert np.allclose(d, ref, atol=1e-6)


def test_line_through_points_measures_sagitta():
    C = circle_curve(10.0)
    a, b = 0.0, 0.2
    line = [Line((10 * math.cos(a), 10 * math.sin(a)), (10 * math.cos(b), 10 * math.sin(b)))]
    d = measure_deviation(C, line, a, b, margin_mm=1e-7)
    sag = 10 * (1 - math.cos(0.1))
    # the chord's sagitta is the deviation both ways (closed form); margin 1e-7 plus sampling
    assert abs(d.path_to_curve_mm - sag) < 1e-6 and abs(d.curve_to_path_mm - sag) < 1e-6
