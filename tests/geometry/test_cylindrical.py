"""Cylindrical cams: contact geometry checked against the envelope condition, closed forms."""

import math

import numpy as np
import pytest

from camcam.errors import GeometryError
from camcam.geometry.analysis import analyse_cylindrical
from camcam.geometry.cylindrical import BarrelOscillatingRoller, BarrelTranslatingRoller, CylindricalCam
from camcam.geometry.mesh import cylinder_mesh

from tests.geometry.cam_programs import program

T = np.linspace(0, 2 * math.pi, 721)


def cams():
    return [
        CylindricalCam(BarrelTranslatingRoller(8.0), program("mm"), 50.0, length=80.0, groove_depth=10.0, bore=20.0),
        CylindricalCam(BarrelTranslatingRoller(8.0), program("mm"), 50.0, length=80.0, groove_depth=10.0,
                       rotation="cw"),
        CylindricalCam(BarrelOscillatingRoller(15.0, 245.0, 170.0), program("deg", 15.0), 80.0, length=160.0,
                       groove_depth=10.0, bore=30.0),
    ]


def _cam_to_fixed(cam, t, p):
    a = cam.sigma * t
    c, s = np.cos(a), np.sin(a)
    return np.stack([p[:, 0], c * p[:, 1] - s * p[:, 2], s * p[:, 1] + c * p[:, 2]], 1)


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
@pytest.mark.parametrize("rho_frac", [0.0, 0.5, 1.0])
def test_flank_touches_roller_and_is_an_envelope(cam, rho_frac):
    rho = cam.bottom_radius + rho_frac * cam.groove_depth
    C = cam.centre(rho).evaluate(T)
    for i in (0, 1):
        F = cam.flank(i, rho)
        m = F.evaluate(T) - C  # contact offset from the roller axis point, cam frame
        assert np.abs(np.linalg.norm(m, axis=1) - cam.roller_radius).max() < 1e-9  # on the roller: rounding only
        # envelope: the cam-frame flank tangent is perpendicular to the contact normal
        assert np.abs(np.einsum("ij,ij->i", F.evaluate(T, 1), m)).max() < 1e-9 * cam.roller_radius * 1e3


def test_translating_pressure_angle_closed_form():
    cam = cams()[0]
    p = program("mm")
    ref = np.degrees(np.arctan(p.lift(T, 1) / cam.bottom_radius))  # tan φ = s′/ρ at the groove bottom
    assert np.abs(np.degrees(cam.pressure_angle(T).value) - ref).max() < 1e-10  # float rounding only
    an = analyse_cylindrical(cam)
    assert an.max_pressure_angle_deg.value == pytest.approx(np.abs(ref).max(), abs=1e-3)  # dense-grid reference


def test_seed002_eq17_pressure_angle():
    cam = cams()[2]
    s1 = np.radians(program("deg", 15.0).lift(T, 1))
    th = np.radians(program("deg", 15.0).lift(T) - 7.5)  # swing centred: s − (s_max + s_min)/2
    r = 245.0 - 70.0  # arm distance of the groove-bottom cross-section (radius 70)
    ref = np.arctan(r * s1 / (245.0 - r * np.cos(th)))  # seed 002 eqs. 16–17: tan φz = r ω_f / v_c
    assert np.abs(cam.pressure_angle(T).value - ref).max() < 1e-12  # float rounding only


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
def test_flank_on_surface_radius(cam):
    for i in (0, 1):
        q = cam.flank_on_surface(T, i)
        assert np.abs(np.hypot(q[:, 1], q[:, 2]) - cam.base_radius).max() < 1e-9  # solved to a few ulp, ~1e-14 mm


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
def test_flank_on_surface_is_the_bisection_root(cam):
    """The secant solve finds the cross-section a plain 60-step bisection finds (the method it replaced, issue 49):
    the same points to 1e-12 mm (both stop within a few ulp of the radius, 1e-14 mm at R 50-80 mm; a slope of
    the wall near 1 turns that into no more than a few times it along the wall)."""
    rho = 0.5 * (cam.bottom_radius + cam.base_radius)
    lift = cam.lift(T, 1, None)
    for i in (0, 1):
        lo, hi = np.full(T.shape, rho - 2 * cam.roller_radius), np.full(T.shape, rho + 2 * cam.roller_radius)
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            p = cam._contact(T, 0, None, mid, i, lift)
            out = np.hypot(p[1].value, p[2].value) > rho
            lo, hi = np.where(out, lo, mid), np.where(out, mid, hi)
        p = cam._to_cam(T, cam._contact(T, 0, None, 0.5 * (lo + hi), i, lift))
        ref = np.stack([j.value for j in p], axis=-1)
        assert np.abs(cam.flank_on_surface(T, i, rho) - ref).max() < 1e-12


def test_developed_centre_is_unrolled_lift():
    cam = cams()[0]
    d = cam.developed_centre(45.0).evaluate(T)
    assert np.allclose(d[:, 0], 45.0 * T, atol=1e-9)  # u = ρθ by definition
    assert np.allclose(d[:, 1] - 40.0, program("mm").lift(T) - 10.0, atol=1e-9)  # centred on the length


def test_mesh_watertight_and_volume():
    cam = cams()[0]
    m = cylinder_mesh(cam)
    assert m.is_watertight and m.is_winding_consistent
    solid = math.pi * (50.0**2 - 10.0**2) * 80.0
    # groove ≈ width 2r_r × depth × centre-line length at mid radius (a 2 % estimate)
    u = cam.developed_centre(45.0).polyline(400)
    groove = 16.0 * 10.0 * np.hypot(*np.diff(np.vstack([u, u[:1] + [2 * math.pi * 45, 0]]), axis=0).T).sum()
    assert m.volume == pytest.approx(solid - groove, rel=0.02)


def test_too_short_cylinder():
    with pytest.raises(GeometryError, match="cam.length 30 mm is too short"):
        CylindricalCam(BarrelTranslatingRoller(8.0), program("mm"), 50.0, length=30.0, groove_depth=10.0)


@pytest.mark.parametrize("cam", cams(), ids=lambda c: f"{c.kind}-{c.rotation}")
def test_wall_grid_is_the_wall_and_its_derivative_along_the_cam_angle(cam):
    t, radii = np.linspace(0.05, 6.2, 40), np.array([cam.bottom_radius - 3.0, cam.reference_radius, cam.base_radius + 2])
    for side in (0, 1):
        grid = cam.wall_grid(t, radii, side)
        for j, r in enumerate(radii):
            # the grid's column j is wall_point on the cross-section r (the same formula, so to rounding)
            assert np.allclose(grid[:, j], cam.wall_point(t, np.full(len(t), r), side), atol=1e-12)
        h = 1e-6
        fd = (cam.wall_grid(t + h, radii, side) - cam.wall_grid(t - h, radii, side)) / (2 * h)
        # central difference: error ~h² · |S'''| (≈1e-10 mm/rad here) plus rounding ~1e-16·|S|/h ≈ 1e-8
        assert np.allclose(cam.wall_grid(t, radii, side, 1), fd, atol=1e-6)
