"""The support function of the tool's and roller's sections on a cylinder (camcam.nc.flank), from its root."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.nc.flank import _support as support  # noqa: PLC2701  (the function under test)

_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


def _searched(r, rho, nu, nx):
    """h(K(r, ρ), n) as camcam.nc.flank computed it before the closed form (at 0e21d30): the maximum of
    nu·ρ·asin(r sin φ/ρ) + nx·r cos φ on a 97-point grid, refined by 40 golden-section steps.  The oracle."""
    phi = np.linspace(-math.pi, math.pi, 97)
    shape = np.broadcast(rho, nu, nx).shape
    rho, nu, nx = (np.broadcast_to(v, shape)[..., None] for v in (rho, nu, nx))

    def f(p):
        return nu[..., 0] * rho[..., 0] * np.arcsin(r * np.sin(p) / rho[..., 0]) + nx[..., 0] * r * np.cos(p)

    v = nu * rho * np.arcsin(r * np.sin(phi) / rho) + nx * r * np.cos(phi)
    j = np.argmax(v, axis=-1)
    step = phi[1] - phi[0]
    a, b = phi[j] - step, phi[j] + step
    c, d = b - _GOLDEN * (b - a), a + _GOLDEN * (b - a)
    fc, fd = f(c), f(d)
    for _ in range(40):
        left = fc >= fd
        b, a = np.where(left, d, b), np.where(left, a, c)
        cn, dn = b - _GOLDEN * (b - a), a + _GOLDEN * (b - a)
        c, d = np.where(left, cn, d), np.where(left, c, dn)
        fn = f(np.where(left, cn, dn))
        fc, fd = np.where(left, fn, fd), np.where(left, fc, fn)
    return np.maximum(np.maximum(fc, fd), v.max(axis=-1))


def test_closed_form_is_the_searched_maximum_on_random_normals():
    rng = np.random.default_rng(1)
    rho = rng.uniform(6.5, 80.0, 20000)
    ang = rng.uniform(-math.pi, math.pi, 20000)
    got = support(6.0, rho, np.cos(ang), np.sin(ang))
    want = _searched(6.0, rho, np.cos(ang), np.sin(ang))
    # the search ends within 0.13·0.618⁴⁰ rad of the maximum, where f is flat: the same figure to rounding
    # (40 mm × 1e-16 a step); a root that took the wrong sign would be off by up to the section's width
    assert np.abs(got - want).max() < 1e-12


@settings(max_examples=200, deadline=None)
@given(st.floats(0.5, 20.0), st.floats(1.02, 50.0), st.floats(-math.pi, math.pi))
def test_closed_form_is_the_maximum(r, ratio, ang):
    rho, nu, nx = r * ratio, math.cos(ang), math.sin(ang)
    h = float(support(r, np.array(rho), np.array(nu), np.array(nx)))
    phi = np.linspace(-math.pi, math.pi, 200001)
    f = nu * rho * np.arcsin(r * np.sin(phi) / rho) + nx * r * np.cos(phi)
    # no point of the section lies farther along n (1e-12 mm: rounding of a 1000 mm figure), and the densest
    # grid comes within its own spacing's error (f is flat at the maximum: r·(3e-5 rad)²·(1 + 1/(ρ/r − 1)))
    assert f.max() <= h + 1e-12
    assert h - f.max() <= r * (math.pi / 100000) ** 2 * (1 + 1 / (ratio - 1)) + 1e-12


def test_circle_and_axis_normals():
    # a huge cylinder (k → 0): the section is the disc of radius r, h = r·|n|; along x only: h = r
    assert abs(float(support(3.0, np.array(1e9), np.array(0.6), np.array(0.8))) - 3.0) < 1e-6
    assert float(support(3.0, np.array(10.0), np.array(0.0), np.array(1.0))) == 3.0
    # along u only: ρ·asin(r/ρ), the half width of the section on the developed cylinder
    assert abs(float(support(3.0, np.array(10.0), np.array(1.0), np.array(0.0))) - 10.0 * math.asin(0.3)) < 1e-12


def _small_tool_cam():
    from pathlib import Path

    from camcam.geometry.build import build_cam
    from camcam.spec import load_spec

    spec = load_spec(Path(__file__).resolve().parents[2] / "samples" / "cylindrical-translating-small-tool.toml")
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit)).cam


def test_flank_plan_is_the_balanced_displacement_between_its_stations():
    """q(θ) of a flank plan (numpy's Chebyshev series through the 49 stations of each motion segment, issue 49)
    against q balanced afresh at 600 angles a segment, and its slope against a 5-point difference of that.

    cylindrical-translating-small-tool, tool R6 in the R8 roller's groove: the cycloidal rise and the dwells are
    analytic (measured 1e-14 mm, 1e-11 mm/rad); the modified-sine return's jerk jumps inside its segment, where
    interpolation through 49 stations is what it is (measured 8.8e-7 mm and 4.7e-5 mm/rad; scipy's quintic
    splines through the same stations, which the series replaced, 6.8e-7 mm and 3.9e-5 mm/rad).  The bounds
    are 5x those: far below the 0.02 mm the flank passes are fitted to, and a plan that interpolated badly
    (a lower degree, the wrong scaling of a derivative) is far over them."""
    from camcam.nc.flank import _balance, _radii, _station_terms, plan_flank

    cam = _small_tool_cam()
    rho_d, r_t = cam.base_radius, 6.0
    plan = plan_flank(cam, r_t, rho_d)

    def balanced(theta):
        return _balance(*_station_terms(cam, theta, r_t, rho_d, _radii(cam)))[0]

    h = 2e-4  # rad: the 5-point difference's truncation (h⁴ q⁽⁵⁾) and rounding (1e-15 / h) both far below 1e-6
    for i, (lo, hi) in enumerate(zip(plan.breaks[:-1], plan.breaks[1:])):
        th = np.linspace(lo, hi, 600)[3:-3]
        q = plan.q(th, 1, i)
        slope = (balanced(th - 2 * h) - 8 * balanced(th - h) + 8 * balanced(th + h) - balanced(th + 2 * h)) / (12 * h)
        assert np.abs(q.d[0] - balanced(th)).max() < 5e-6
        assert np.abs(q.d[1] - slope).max() < 2.5e-4
