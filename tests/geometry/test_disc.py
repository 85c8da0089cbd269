"""Disc cams checked against closed forms and independent polyline computations."""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.errors import GeometryError
from camcam.geometry.analysis import analyse, check_undercut, flat_radius
from camcam.geometry.curve import curvature
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import OscillatingFlat, OscillatingRoller, TranslatingFlat, TranslatingRoller
from camcam.geometry.groove import GrooveCam
from camcam.geometry.smallest_cam import size_cam
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.motion.standard import dwell

from tests.geometry.cam_programs import program

T = np.linspace(0, 2 * math.pi, 2001)


def cams():
    mm, deg = program("mm"), program("deg", 15.0)
    return [
        DiscCam(TranslatingRoller(10.0, 5.0), mm, 40.0),
        DiscCam(TranslatingRoller(10.0, -5.0), mm, 40.0, "cw"),
        DiscCam(OscillatingRoller(10.0, 110.0, 85.0), deg, 40.0),
        DiscCam(OscillatingRoller(8.0, 100.0, 80.0), deg, 45.0, "cw"),
        DiscCam(TranslatingFlat(0.0), mm, 40.0),
        DiscCam(OscillatingFlat(130.0), program("deg", 10.0), 50.0),
    ]


@pytest.mark.parametrize("cam", cams()[:4], ids=lambda c: f"{c.kind}-{c.rotation}")
def test_profile_at_roller_radius_on_normal(cam):
    P, Q = cam.pitch.evaluate(T), cam.profile.evaluate(T)
    d = P - Q
    # 1e-9 mm: the bound; the construction is exact to float rounding (~1e-14 mm)
    assert np.abs(np.hypot(*d.T) - cam.roller_radius).max() < 1e-9
    tangent = cam.pitch.evaluate(T, 1)
    assert np.abs(np.einsum("ij,ij->i", d, tangent) / np.hypot(*tangent.T)).max() < 1e-9  # on the normal, same bound


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
def test_profile_simple_closed_and_runs_against_rotation(cam):
    ring = shapely.LinearRing(cam.profile.polyline(400))
    assert ring.is_simple
    assert ring.is_ccw == (cam.rotation == "cw")  # a ccw cam's curves run clockwise (module docstring)
    assert np.allclose(cam.profile.evaluate([0.0]), cam.profile.evaluate([2 * math.pi]), atol=1e-9)  # closed


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
def test_derivatives_match_finite_differences(cam):
    t, h = np.array([0.4, 1.3, 2.5, 4.2, 5.6]), 1e-5
    for curve in (cam.profile, cam.offset_profile(3.0)):
        for k in range(3):
            fd = (curve.evaluate(t + h, k) - curve.evaluate(t - h, k)) / (2 * h)
            # central difference error ~h²·|P^(k+3)| ≲ 1e-7 mm/rad^k on these cams
            assert np.abs(fd - curve.evaluate(t, k + 1)).max() < 1e-5 * max(1.0, np.abs(fd).max())


def test_centred_translating_pressure_angle_closed_form(prog_mm):
    cam = DiscCam(TranslatingRoller(10.0, 0.0), prog_mm, 40.0)
    ref = np.arctan(prog_mm.lift(T, 1) / (50.0 + prog_mm.lift(T)))  # tan φ = s′/(R_p + s)
    assert np.abs(cam.pressure_angle(T).value - ref).max() < 1e-12  # same formula, float rounding only


def test_flat_face_radius_is_rb_plus_s_plus_s2(prog_mm):
    cam = DiscCam(TranslatingFlat(0.0), prog_mm, 40.0)
    ref = 40.0 + prog_mm.lift(T) + prog_mm.lift(T, 2)
    assert np.abs(1.0 / np.abs(curvature(cam.profile, T)) - ref).max() < 1e-9  # exact derivatives; rounding only
    assert np.abs(flat_radius(cam, T)[0] - ref).max() < 1e-9  # the signed form used by the analysis


def _independent(cam, n=72001):
    """Max |pressure angle| (deg) and min convex profile radius from a dense polyline alone."""
    t = np.linspace(0, 2 * math.pi, n)
    prof = cam.profile.evaluate(t)
    a, b, c = prof[:-2], prof[1:-1], prof[2:]
    cross = (b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0]
    la, lb, lc = np.hypot(*(b - a).T), np.hypot(*(c - b).T), np.hypot(*(c - a).T)
    radius = la * lb * lc / (2 * np.abs(cross) + 1e-300)
    convex = -cam.sigma * cross > 0
    rmin = radius[convex].min()
    if cam.pitch is None:
        return 0.0, rmin
    P = cam.pitch.evaluate(t)
    tang = np.gradient(P, t, axis=0)
    nrm = np.stack([-tang[:, 1], tang[:, 0]], 1)
    ang = cam.sigma * t  # back to the fixed frame: turn by +σθ
    c_, s_ = np.cos(ang), np.sin(ang)
    nf = np.stack([c_ * nrm[:, 0] - s_ * nrm[:, 1], s_ * nrm[:, 0] + c_ * nrm[:, 1]], 1)
    Pf = np.stack([c_ * P[:, 0] - s_ * P[:, 1], s_ * P[:, 0] + c_ * P[:, 1]], 1)
    if isinstance(cam.follower, TranslatingRoller):
        u = np.tile([0.0, 1.0], (n, 1))
    else:
        arm = Pf - [cam.follower.pivot_distance, 0.0]
        u = np.stack([arm[:, 1], -arm[:, 0]], 1)
    cosang = np.abs(np.einsum("ij,ij->i", nf, u)) / np.hypot(*nf.T) / np.hypot(*u.T)
    return math.degrees(np.arccos(np.clip(cosang, -1, 1)).max()), rmin


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
def test_report_figures_agree_with_dense_polyline(cam):
    an = analyse(cam)
    pa, rmin = _independent(cam)
    assert abs(an.max_pressure_angle_deg.value - pa) < 0.05  # the bound, degrees
    assert abs(an.profile.min_radius_mm - rmin) < 0.005 * rmin  # the bound, 0.5 %


def _sharp():
    c = make_law("cycloidal")
    return MotionProgram((Segment(c, 0, 45, 40.0, base=0.0), Segment(c, 45, 90, -40.0, base=40.0),
                          Segment(dwell(), 90, 360, 1.0, base=0.0)), 60)


def test_undercut_names_angle_and_fix():
    prog_mm = _sharp()
    cam = DiscCam(TranslatingRoller(20.0, 0.0), prog_mm, 5.0)
    with pytest.raises(GeometryError, match=r"undercut at cam angle [0-9.]+°: .* cam.base_radius >= ([0-9.]+) mm avoids it") as e:
        check_undercut(cam)
    fix = float(e.value.args[0].split(">= ")[1].split(" ")[0])
    check_undercut(DiscCam(TranslatingRoller(20.0, 0.0), prog_mm, fix))  # the named radius works
    with pytest.raises(GeometryError):
        check_undercut(DiscCam(TranslatingRoller(20.0, 0.0), prog_mm, fix - 0.02))  # and is the smallest to 0.01 mm


def test_flat_cusp_names_fix(prog_mm):
    fix_exact = -(prog_mm.lift(np.linspace(0, 2 * math.pi, 200001)) + prog_mm.lift(np.linspace(0, 2 * math.pi, 200001), 2)).min()
    with pytest.raises(GeometryError, match="cusp at cam angle") as e:
        check_undercut(DiscCam(TranslatingFlat(), prog_mm, 5.0))
    fix = float(e.value.args[0].split(">= ")[1].split(" ")[0])
    assert fix_exact <= fix <= fix_exact + 0.011  # rounded up to 0.01 mm; dense sample within 1e-4 mm of the min


def test_sizing_meets_limit(prog_mm, prog_deg):
    z = size_cam(DiscCam(TranslatingRoller(10.0, 0.0), prog_mm, 40.0))
    assert z.max_pressure_angle_deg == pytest.approx(30.0, abs=1e-6)  # brentq on the exact extreme
    z0 = size_cam(DiscCam(TranslatingRoller(10.0, 0.0), prog_mm, 40.0), optimise_offset=False)
    assert z.base_radius_mm <= z0.base_radius_mm + 1e-9  # the best offset never needs a larger cam
    zo = size_cam(DiscCam(OscillatingRoller(10.0, 110.0, 85.0), prog_deg, 40.0))
    assert zo.max_pressure_angle_deg == pytest.approx(35.0, abs=1e-6)  # default oscillating limit


def test_groove_flanks_and_offsets(prog_mm):
    g = GrooveCam(DiscCam(TranslatingRoller(10.0, 5.0), prog_mm, 40.0), 8.0)
    P = g.pitch.evaluate(T)
    inner, outer = (f.evaluate(T) for f in g.flanks)
    assert np.abs(np.hypot(*(inner - P).T) - 10).max() < 1e-9  # exact offsets: rounding only
    assert np.abs(np.hypot(*(outer - P).T) - 10).max() < 1e-9
    n = g.normal(T)
    assert np.allclose(g.offset_flank(1, 2.0).evaluate(T), P + 8.0 * n, atol=1e-9)  # into the groove
    assert np.allclose(g.offset_flank(0, 2.0).evaluate(T), P - 8.0 * n, atol=1e-9)


@settings(max_examples=15, deadline=None)
@given(
    rb=st.floats(30.0, 80.0),
    rr=st.floats(2.0, 15.0),
    e=st.floats(-10.0, 10.0),
    d=st.floats(-5.0, 5.0),
    rot=st.sampled_from(["ccw", "cw"]),
)
def test_property_offsets_are_exact(rb, rr, e, d, rot):
    cam = DiscCam(TranslatingRoller(rr, e), program("mm"), rb, rot)
    t = np.linspace(0, 2 * math.pi, 97)
    Q, O = cam.profile.evaluate(t), cam.offset_profile(d).evaluate(t)
    assert np.abs(np.hypot(*(O - Q).T) - abs(d)).max() < 1e-9  # exact offset, rounding only
    assert np.all(np.einsum("ij,ij->i", O - Q, cam.normal(t)) * d >= -1e-12)  # positive d = outside


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
def test_offset_jets_from_one_evaluation_are_the_separate_ones(cam):
    # The offset curve takes the point and the normal from one evaluation of the follower (the pitch curve
    # carried one order further for a roller); every row of a jet is independent of its order, so the result
    # is the point of order K plus d times the normal of order K evaluated apart, exactly
    t = np.linspace(0.0, 2 * math.pi, 203)
    for K in (0, 2, 3):
        for d in (0.0, 3.0, -2.5):
            if cam.is_roller:
                x, y = cam._pitch_jets(t, K)
                d_pitch = d - cam.roller_radius
            else:
                e = cam.element(t, K)
                x, y = cam._to_cam(t, e.x, e.y)
                d_pitch = d
            nx, ny = cam._normal_jets(t, K)
            ox, oy = cam.offset_profile(d).jets(t, K)
            assert np.array_equal(ox.d, (x + nx * d_pitch).d) and np.array_equal(oy.d, (y + ny * d_pitch).d)
