"""The sweep's closed forms against the full geometry (camcam.geometry.disc/analysis), point by point.

Reference: DiscCam.pressure_angle and analysis.convex_curvature / flat_radius evaluate the
same cam through jets of the fixed-frame follower element (no closed form shared with the
kernels), so agreement to 1e-9 at every sample of a sweep checks the closed forms.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.geometry.analysis import analyse, convex_curvature, flat_radius
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.motion.standard import dwell
from camcam.geometry.followers import OscillatingRoller, TranslatingFlat, TranslatingRoller, closedform
from camcam.sizing import kernels
from camcam.sizing.exact_check import design_cam, exact_figures, outer_radius
from camcam.sizing.samples import sample_program

SAMPLES = 720


def program(unit: str, rise: float, law: str = "modified-sine") -> MotionProgram:
    return MotionProgram((Segment(make_law(law), 0, 120, rise), Segment(dwell(), 120, 180, 0, base=rise),
                          Segment(make_law("cycloidal"), 180, 300, -rise, base=rise),
                          Segment(dwell(), 300, 360, 0, base=0)),
                         rpm=60, unit=unit)


def pieces(p: MotionProgram, ps) -> np.ndarray:
    """The segment of each sample (samples run segment by segment, ends included)."""
    n = [max(3, int(math.ceil((s.end_deg - s.start_deg) / 360.0 * SAMPLES)) + 1) for s in p.segments]
    assert sum(n) == ps.theta.size
    return np.repeat(np.arange(len(n)), n)


def spy(monkeypatch):
    seen = {}
    orig = closedform.roller_figures

    def capture(kc, ratio, *rest):
        seen["kc"], seen["ratio"] = kc, ratio
        return orig(kc, ratio, *rest)

    monkeypatch.setattr(closedform, "roller_figures", capture)
    return seen


def exact_pointwise(cam, p, ps):
    idx = pieces(p, ps)
    sg = cam.sigma
    pa = np.concatenate([cam.pressure_angle(ps.theta[idx == i], 0, i).d[0] for i in range(len(p.segments))])
    if cam.is_roller:
        kc = np.concatenate([convex_curvature(cam.pitch, sg, ps.theta[idx == i], i)[0] for i in range(len(p.segments))])
    else:
        kc = np.concatenate([flat_radius(cam, ps.theta[idx == i], i)[0] for i in range(len(p.segments))])
    return pa, kc


# a small sweep: every design, every sample
TRANSLATING = [(rb, e, rr, rot) for rb in (25.0, 40.0) for e in (-6.0, 0.0, 7.5) for rr in (5.0, 10.0) for rot in ("ccw", "cw")]


@pytest.mark.parametrize("rot", ["ccw", "cw"])
def test_translating_roller_matches_full_geometry_at_every_sample(rot, monkeypatch):
    seen = spy(monkeypatch)
    p = program("mm", 20.0)
    ps = sample_program(p, SAMPLES)
    designs = [d for d in TRANSLATING if d[3] == rot]
    rb, e, rr = (np.array([d[i] for d in designs]) for i in range(3))
    sg = 1 if rot == "ccw" else -1
    figs = TranslatingRoller.figures(ps, sg, rb, e, rr)
    for k, (b, off, r, _) in enumerate(designs):
        cam = design_cam("translating-roller", p, {"base_radius": b, "offset": off, "roller_radius": r}, rot)
        pa, kc = exact_pointwise(cam, p, ps)
        # 1e-9: both sides are double-precision evaluations of the same exact quantity (~1e-15 apart)
        assert np.abs(np.arctan(seen["ratio"][k]) - pa).max() < 1e-9
        assert np.abs(seen["kc"][k] - kc).max() < 1e-9
        # the closed-form outer radius (largest lift, root-found) against the profile's own maximum
        assert figs["outer_radius_mm"][k] == pytest.approx(outer_radius(cam), abs=1e-6)  # Brent to 1e-12 in angle


def test_oscillating_roller_matches_full_geometry_at_every_sample(monkeypatch):
    seen = spy(monkeypatch)
    p = program("deg", 18.0)
    ps = sample_program(p, SAMPLES)
    designs = [(rb, a, L, rr) for rb in (30.0, 45.0) for a in (100.0, 110.0) for L in (80.0, 95.0) for rr in (6.0,)]
    for rot, sg in (("ccw", 1), ("cw", -1)):
        arr = [np.array([d[i] for d in designs]) for i in range(4)]
        figs = OscillatingRoller.figures(ps, sg, *arr)
        for k, (b, a, L, r) in enumerate(designs):
            cam = design_cam("oscillating-roller", p, {"base_radius": b, "pivot_distance": a, "arm_length": L, "roller_radius": r}, rot)
            pa, kc = exact_pointwise(cam, p, ps)
            assert np.abs(np.arctan(seen["ratio"][k]) - pa).max() < 1e-9  # same quantity, double precision
            assert np.abs(seen["kc"][k] - kc).max() < 1e-9
            # the outer radius is a sampled maximum here: never above the exact one, within h²·R/8 of it
            exact = outer_radius(cam)
            assert exact - 1e-3 < figs["outer_radius_mm"][k] <= exact + 1e-9


def test_translating_flat_matches_full_geometry_at_every_sample():
    p = program("mm", 20.0)
    ps = sample_program(p, SAMPLES)
    for rot, sg in (("ccw", 1), ("cw", -1)):
        for rb in (20.0, 35.0):
            figs = TranslatingFlat.figures(ps, sg, np.array([rb]))
            cam = design_cam("translating-flat", p, {"base_radius": rb}, rot)
            _, rho = exact_pointwise(cam, p, ps)
            assert abs(figs["min_curvature_radius_mm"][0] - rho.min()) < 1e-9  # ρ = R_b + s + s″, same quantity


@settings(max_examples=25, deadline=None)
@given(rb=st.floats(15.0, 80.0), e=st.floats(-12.0, 12.0), rr=st.floats(3.0, 14.0), ccw=st.booleans(),
       law=st.sampled_from(["cycloidal", "polynomial-345", "modified-trapezoid", "harmonic"]))
def test_translating_roller_closed_form_any_design(rb, e, rr, ccw, law):
    """Hypothesis: the closed forms hold for any translating-roller design, not only the swept ones."""
    p = program("mm", 15.0, law)
    ps = sample_program(p, 90)
    captured = {}
    orig = closedform.roller_figures
    closedform.roller_figures = lambda kc, ratio, *rest: captured.update(kc=kc, ratio=ratio) or orig(kc, ratio, *rest)
    try:
        TranslatingRoller.figures(ps, 1 if ccw else -1, np.array([rb]), np.array([e]), np.array([rr]))
    finally:
        closedform.roller_figures = orig
    cam = design_cam("translating-roller", p, {"base_radius": rb, "offset": e, "roller_radius": rr}, "ccw" if ccw else "cw")
    th = ps.theta
    idx = np.repeat(np.arange(4), [max(3, int(math.ceil((s.end_deg - s.start_deg) / 4.0)) + 1) for s in p.segments])
    pa = np.concatenate([cam.pressure_angle(th[idx == i], 0, i).d[0] for i in range(4)])
    kc = np.concatenate([convex_curvature(cam.pitch, cam.sigma, th[idx == i], i)[0] for i in range(4)])
    assert np.abs(np.arctan(captured["ratio"][0]) - pa).max() < 1e-9  # same quantity in double precision
    assert np.abs(captured["kc"][0] - kc).max() < 1e-9


@pytest.mark.parametrize("kind,params,unit", [
    ("translating-roller", {"base_radius": 30.0, "offset": 4.0, "roller_radius": 8.0}, "mm"),
    ("oscillating-roller", {"base_radius": 35.0, "pivot_distance": 110.0, "arm_length": 90.0, "roller_radius": 7.0}, "deg"),
])
def test_sampled_extremes_within_the_stated_grid_bound(kind, params, unit):
    """A sampled maximum is below the root-found one, and by no more than the bound the table states."""
    p = program(unit, 20.0)
    ps = sample_program(p, 3600)
    arrays = {k: np.array([v]) for k, v in params.items()}
    figs = kernels.block_figures(kind, ps, 1, arrays)
    an = analyse(design_cam(kind, p, params, "ccw"))
    pa_grid, pa_exact = figs["max_pressure_angle_deg"][0], an.max_pressure_angle_deg.value
    assert pa_grid <= pa_exact + 1e-12  # samples of a maximum cannot exceed it (float noise only)
    assert pa_exact - pa_grid <= figs["pressure_angle_bound_deg"][0]
    rho_grid, rho_exact = figs["min_curvature_radius_mm"][0], an.profile.min_radius_mm
    assert rho_grid >= rho_exact - 1e-9  # samples of a minimum cannot go below it
    assert rho_grid - rho_exact <= figs["curvature_radius_bound_mm"][0]
    # the exact refinement reports the same figures as analyse()
    ex = exact_figures(kind, p, params, "ccw")
    assert ex.max_pressure_angle_deg == pa_exact and ex.min_curvature_radius_mm == rho_exact
