import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

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


def _eight_steps(curve, q, lo, hi, seeds_t):
    """closest_params as it was before a point at its fixed point stopped being evaluated (camcam at 1c7d3af):
    eight Newton steps for every point.  The oracle."""
    from camcam.geometry.curve import derivatives
    from camcam.toolpath.deviation import _nearest

    t = seeds_t[_nearest(curve.evaluate(seeds_t, 0), q)].astype(float)
    step = (hi - lo) / max(len(seeds_t) - 1, 1)
    seam = bool(getattr(curve, "closed", False)) and lo <= curve.t_start and hi >= curve.t_end
    for _ in range(8):
        p, d1, d2 = derivatives(curve, t, 2, first=0)
        r = p - q
        f = np.einsum("ij,ij->i", r, d1)
        fp = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", r, d2)
        dt = np.where(fp > 0, -f / np.where(fp > 0, fp, 1.0), 0.0)
        t = t + np.clip(dt, -step, step)
        t = lo + np.mod(t - lo, hi - lo) if seam else np.clip(t, lo, hi)
    return t, np.hypot(*(curve.evaluate(t, 0) - q).T)


@settings(max_examples=30, deadline=None)
@given(st.integers(0, 2**32 - 1), st.sampled_from([(0.0, 2 * math.pi), (0.3, 2.9), (4.0, 2 * math.pi)]))
def test_points_at_their_fixed_point_are_left_there_with_the_same_bits(seed, span):
    """Newton's points that stop moving are not stepped again: the same parameters and distances, to the bit,
    as eight steps for every point (seam included: the whole closed ellipse)."""
    lo, hi = span
    E = ellipse()
    rng = np.random.default_rng(seed)
    ang = rng.uniform(0.0, 2 * math.pi, 300)
    rad = rng.uniform(0.2, 1.6, 300)
    q = np.column_stack([30.0 * rad * np.cos(ang), 20.0 * rad * np.sin(ang)])
    seeds = np.linspace(lo, hi, 257)
    t, d = closest_params(E, q, lo, hi, seeds)
    t0, d0 = _eight_steps(E, q, lo, hi, seeds)
    assert np.array_equal(t, t0) and np.array_equal(d, d0)


def test_measured_deviation_of_many_lines_is_the_recorded_one():
    """The curve-to-path side measures each curve point against its nearest path sample's element and that
    element's neighbours, grouped by element.  Regression against the figures of camcam at 1c7d3af (one
    mask over all points per element): 600 chords of the ellipse, read to the bit.  The total with the
    between-sample bound is the one taken interval by interval (issue 49's session, case 43:15): 9.44e-6 mm
    where the curve is most curved near the worst interval, not the 1e-5 mm of its largest curvature anywhere."""
    E = ellipse()
    t = np.linspace(0.0, 2 * math.pi, 601)
    p = E.evaluate(t, 0) + 1e-4 * np.column_stack([np.sin(7 * t), np.cos(5 * t)])
    lines = [Line(tuple(a), tuple(b)) for a, b in zip(p[:-1], p[1:])]
    d = measure_deviation(E, lines, margin_mm=1e-5)
    assert (d.path_to_curve_mm, d.curve_to_path_mm, d.max_deviation_mm) == RECORDED_MANY_LINES


#: measure_deviation of the 600 chords above at 1c7d3af: (path → curve, curve → path, with the margin), mm.
RECORDED_MANY_LINES = (0.0005034897772427819, 0.0005113244257237478, 0.0005207644783140712)


def thin_ellipse(a=400.0, b=1.0):
    """x = a cos t, y = b sin t: radius of curvature b²/a = 0.0025 mm at its ends, a²/b = 160 m mid-side."""
    from camcam.geometry.curve import FunctionCurve

    def f(t, k):
        c, s = np.cos(t), np.sin(t)
        return np.stack([[a * c, b * s], [-a * s, b * c], [-a * c, -b * s], [a * s, -b * c]][k], axis=-1)

    return FunctionCurve(f, 0.0, 2 * math.pi, closed=True)


def test_one_sharp_place_does_not_inflate_the_bound_everywhere():
    """Real failing data, campaign case 43:15 after its own advice (a flat-faced disc at its cusp limit, radius
    of curvature 0.0066 mm at 206°): its part outline lay 0.004664 mm from the profile, but the bound between
    samples, taken with the largest curvature anywhere and the memory cap's step, added 3.9e-4 mm everywhere
    and the run said FAIL at 0.005058 mm over 0.0049.  Here a 1600 mm thin ellipse, radius 0.0025 mm at its
    ends (the cap's step is 4 µm, where 0.4 µm would be needed there), and chords through points lifted off it
    along its normal by 0.004·sin²t mm: exactly 0.004 mm off at the flat mid-sides (t = π/2, 3π/2, vertices
    there: the offset of a flat curve), nothing at the sharp ends."""
    E = thin_ellipse()
    t = np.linspace(0.0, 2 * math.pi, 4001)
    p, d1 = E.evaluate(t, 0), E.evaluate(t, 1)
    normal = np.column_stack([d1[:, 1], -d1[:, 0]]) / np.hypot(d1[:, 0], d1[:, 1])[:, None]  # outward (ccw curve)
    q = p + (0.004 * np.sin(t) ** 2)[:, None] * normal
    q[-1] = q[0]
    lines = [Line(tuple(a), tuple(b)) for a, b in zip(q[:-1], q[1:])]
    d = measure_deviation(E, lines, margin_mm=1e-5)
    # the vertex at t = π/2 is 0.004 mm off (to rounding); nothing is farther (the lift is at most that, and a
    # chord across the flat side sags 1e-6 mm towards the curve at most)
    assert abs(max(d.path_to_curve_mm, d.curve_to_path_mm) - 0.004) < 1e-9
    # the bound adds what the flat side's curvature and the sample step allow there, not the ends' 8e-4 mm
    assert d.margin_mm < 1e-7
    assert 0.004 <= d.max_deviation_mm < 0.004 + 1e-7
    # the bound still holds where the ends are sharp: ten times as many path points, each measured exactly
    dense = np.concatenate([np.linspace(a, b, 40, endpoint=False) for a, b in zip(q[:-1], q[1:])])
    _, exact = closest_params(E, dense, 0.0, 2 * math.pi)
    assert exact.max() <= d.max_deviation_mm


def test_a_sharper_place_than_the_capped_step_resolves_is_measured_again_there():
    """Campaign case 45:63: a face groove cut at the base radius its undercut advice named has a flank of radius
    6.6e-6 mm; the memory cap's step (1.2e-3 mm, where 7e-5 mm was needed) bounded its part outline's deviation
    between samples there by 0.0289 mm about a sampled 0.0045 mm, and the job failed its 0.0052 mm tolerance.
    The intervals whose term is over the margin are now cut finer and measured again.  Here a 1600 mm ellipse of
    radius 6.25e-6 mm at its ends (the capped step 8 µm there would add 1.3 mm) and chords through points lifted
    off it by 0.004 mm along its normal: 0.004 mm off at the flat mid-sides, less at the sharp ends, where the
    chords cut across the tip."""
    E = thin_ellipse(400.0, 0.05)
    t = np.linspace(0.0, 2 * math.pi, 4001)
    p, d1 = E.evaluate(t, 0), E.evaluate(t, 1)
    normal = np.column_stack([d1[:, 1], -d1[:, 0]]) / np.hypot(d1[:, 0], d1[:, 1])[:, None]  # outward (ccw curve)
    q = p + 0.004 * normal
    q[-1] = q[0]
    lines = [Line(tuple(a), tuple(b)) for a, b in zip(q[:-1], q[1:])]
    d = measure_deviation(E, lines, margin_mm=1e-5)
    # the samples' largest is the lift, 0.004 mm to rounding; the bound adds a few margins to it (2.3e-5 mm
    # measured: a part's feet can find the curve where it bends even faster than the interval's did), not 1.3 mm
    assert abs(max(d.path_to_curve_mm, d.curve_to_path_mm) - 0.004) < 1e-9
    assert 0.004 <= d.max_deviation_mm <= 0.004 + 5e-5
    # and it holds: the path sampled ten times as finely and measured exactly, each point's Newton seeded from a
    # grid 1e-7 rad fine about the tips (from a 2049-point grid a point by a tip found a farther foot, 0.00413 mm)
    dense = np.concatenate([np.linspace(a, b, 40, endpoint=False) for a, b in zip(q[:-1], q[1:])])
    tip = np.linspace(-0.02, 0.02, 400001)
    seeds = np.unique(np.concatenate([np.linspace(0.0, 2 * math.pi, 200001), np.mod(tip, 2 * math.pi), math.pi + tip]))
    _, exact = closest_params(E, dense, 0.0, 2 * math.pi, seeds)
    assert exact.max() <= d.max_deviation_mm
    from camcam.toolpath.elements import element_distance

    tips = E.evaluate(np.concatenate([np.linspace(-0.01, 0.01, 4001), math.pi + np.linspace(-0.01, 0.01, 4001)]), 0)
    near = [ln for ln in lines if min(abs(ln.start[0]), abs(ln.end[0])) > 399.0]
    assert min(len(near), 1) == 1
    assert np.min([element_distance(ln, tips) for ln in near], axis=0).max() <= d.max_deviation_mm
