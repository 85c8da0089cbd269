"""As-machined follower motion against closed forms (eccentric circle cams)."""

import math

import numpy as np
import pytest

from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import TranslatingFlat, TranslatingRoller
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.report.fitted_motion import fitted_motion
from camcam.toolpath.arcfit import fit_contour
from camcam.toolpath.elements import Arc

E = 3.0  # eccentricity, mm
RB = 30.0  # base radius, mm
RT = 5.0  # tool radius, mm


def harmonic_program():
    # two harmonic segments of rise ±2E make s = E·(1 − cos θ): an eccentric circle under a flat face
    h = make_law("harmonic")
    return MotionProgram((Segment(h, 0, 180, 2 * E), Segment(h, 180, 360, -2 * E, base=2 * E)), rpm=60)


def circle_as_arcs(centre, radius, ccw):
    cx, cy = centre
    p0, p1 = (cx + radius, cy), (cx - radius, cy)
    return (Arc(p0, p1, centre, ccw), Arc(p1, p0, centre, ccw))


def exact_circle_of(curve):
    """Centre and radius of a curve that is a circle (three points, exact construction)."""
    p = curve.evaluate(np.array([0.3, 2.2, 4.4]), 0)
    (x1, y1), (x2, y2), (x3, y3) = p
    d = 2 * (x1 * (y2 - y3) + x2 * (y3 - y1) + x3 * (y1 - y2))
    ux = ((x1**2 + y1**2) * (y2 - y3) + (x2**2 + y2**2) * (y3 - y1) + (x3**2 + y3**2) * (y1 - y2)) / d
    uy = ((x1**2 + y1**2) * (x3 - x2) + (x2**2 + y2**2) * (x1 - x3) + (x3**2 + y3**2) * (x2 - x1)) / d
    return (ux, uy), math.dist((ux, uy), p[0])


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_flat_face_on_eccentric_circle_is_harmonic(rotation):
    cam = DiscCam(TranslatingFlat(), harmonic_program(), RB, rotation)
    tool = cam.offset_profile(RT)
    centre, radius = exact_circle_of(tool)
    assert radius == pytest.approx(RB + E + RT, abs=1e-9)  # the envelope of s = E(1−cos θ) is a circle
    ccw = rotation == "cw"  # a ccw cam's curves run clockwise (geometry convention)
    fm = fitted_motion(cam, circle_as_arcs(centre, radius, ccw), RT, np.arange(0.0, 360.0, 5.0))
    th = np.radians(fm.angles_deg)
    w = 2 * math.pi  # 60 rpm in rad/s
    assert np.allclose(fm.fitted[0], E * (1 - np.cos(th)), atol=1e-9)  # solved to 1e-12 mm
    # 5-point stencils at h = 2e-3 rad: truncation h⁴·|s⁽⁵⁾|/30 ≈ 5e-12 mm/rad, rounding ~1e-12/h
    assert np.allclose(fm.fitted[1], E * np.sin(th) * w, atol=1e-6)
    assert np.allclose(fm.fitted[2], E * np.cos(th) * w**2 / 1000, atol=1e-6)
    # jerk: rounding 1e-12/h³ ≈ 1.3e-4 mm/rad³ → ×ω³/1000 ≈ 3e-5 m/s³, truncation h²/4·E ≈ 3e-6
    assert np.allclose(fm.fitted[3], -E * np.sin(th) * w**3 / 1000, atol=1e-3)


def test_roller_on_eccentric_circle_closed_form():
    # the roller centre rides a circle of radius RB + E + r_r about the eccentric centre
    rr = 8.0
    cam = DiscCam(TranslatingRoller(rr), harmonic_program(), RB, "ccw")
    tool_centre, _ = exact_circle_of(cam.offset_profile(RT))  # any circle will do: we test the kinematics
    R = 35.0  # tool-centre path radius: roller-centre circle radius R + rr − RT
    fm = fitted_motion(cam, circle_as_arcs(tool_centre, R, False), RT, np.arange(0.0, 360.0, 7.5))
    th = np.radians(fm.angles_deg)
    cx, cy = tool_centre
    # fixed frame: centre rotated by +θ (ccw cam); roller on x = 0 above it
    X = cx * np.cos(th) - cy * np.sin(th)
    Y = cx * np.sin(th) + cy * np.cos(th)
    Rp = R + rr - RT
    y = Y + np.sqrt(Rp**2 - X**2)
    y0 = math.sqrt((RB + rr) ** 2)  # lift is measured from the base pitch circle
    assert np.allclose(fm.fitted[0], y - y0, atol=1e-9)  # solved to 1e-12 mm


def test_fitted_program_lift_error_within_tolerance(request):
    # a real fit: the lift error can not exceed the path deviation over cos(pressure angle)
    law = make_law("cycloidal")
    prog = MotionProgram((Segment(law, 0, 180, 10.0), Segment(law, 180, 360, -10.0, base=10.0)), rpm=100)
    cam = DiscCam(TranslatingRoller(8.0), prog, 30.0)
    fit = fit_contour(cam.offset_profile(RT), 0.01)
    fm = fitted_motion(cam, fit.elements, RT, np.arange(0.0, 360.0, 1.0))
    pa = np.radians(np.abs(cam.pressure_angle(np.radians(fm.angles_deg)).value))
    bound = fit.max_deviation_mm / np.cos(pa)
    assert np.all(np.abs(fm.fitted[0] - fm.design[0]) <= bound + 1e-9)  # 1e-9: solver residual
    assert fm.contact_changes >= len(fit.elements) - 1  # every join is passed once
