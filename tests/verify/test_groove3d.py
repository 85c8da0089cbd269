"""The 3-D groove measurement, checked three ways: brute-force point membership, the closed case, the issue's figures.

Reference data: tests/verify/data/legacy-*.ngc are the 4-axis programs camcam printed for the two
cylindrical samples at commit 6187917 (before issue 11), with A = cam angle and no Y word.
"""

import functools
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, example, given, settings
from hypothesis import strategies as st

from camcam.geometry.build import build_cam
from camcam.post.readback import poses_from_program
from camcam.toolpath.poses import CylinderTool, ToolPoses
from camcam.verify.groove3d import cut_walls, design_walls, measure_groove
from camcam.verify.groove_motion import follower_poses
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
DATA = Path(__file__).resolve().parent / "data"


@functools.lru_cache(maxsize=None)
def cam_of(sample: str, rotation: str = "ccw"):
    from dataclasses import replace

    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    return build_cam(replace(spec.cam, rotation=rotation), spec.follower, spec.motion.program(spec.unit)).cam


# -- independent brute force -------------------------------------------------------------------
def _rx(a):
    c, s = np.cos(a), np.sin(a)
    return c, s


def _inside_any(points_cam, X, Y, Z, a, B, r, L):
    """Is each cam-frame point (n, 3) inside the cylinder at any of the poses (m,)? Plain 3-D vector maths."""
    x, y, z = points_cam[:, 0:1], points_cam[:, 1:2], points_cam[:, 2:3]
    c, s = _rx(a[None, :])
    px, py, pz = x + 0 * c, c * y - s * z, s * y + c * z  # machine position Rx(a)·p
    d = np.stack([px - X, py - Y, pz - Z], axis=-1)
    w = np.stack([np.sin(B), 0 * B, np.cos(B)], axis=-1)[None]
    axial = np.sum(d * w, axis=-1)
    radial = np.linalg.norm(d - axial[..., None] * w, axis=-1)
    return np.any((axial >= 0) & (axial <= L) & (radial <= r), axis=1)


def _brute_wall(points_of_x, inside, xs, side):
    """The extreme x of the points inside on a fine x grid: the wall at grid resolution."""
    ins = inside(points_of_x(xs))
    if not ins.any():
        return np.nan
    return xs[ins].max() if side == 1 else xs[ins].min()


def _dense_program_poses(poses: ToolPoses, step_deg: float = 0.01, step_mm: float = 0.005):
    """Every move cut into pieces ≤ step (a much finer sampling than the measurement's, built independently)."""
    tip, A, B = poses.tip_mm, poses.a_deg, poses.b_deg
    out = []
    for k in range(len(A) - 1):
        n = int(max(1, np.ceil(max(abs(A[k + 1] - A[k]) / step_deg, np.abs(tip[k + 1] - tip[k]).max() / step_mm))))
        t = np.linspace(0, 1, n, endpoint=False)[:, None]
        row = np.column_stack([tip[k] * (1 - t) + tip[k + 1] * t, A[k] * (1 - t[:, 0]) + A[k + 1] * t[:, 0],
                               B[k] * (1 - t[:, 0]) + B[k + 1] * t[:, 0]])
        out.append(row)
    out = np.vstack(out)
    return out[:, 0], out[:, 1], out[:, 2], np.radians(out[:, 3]), np.radians(out[:, 4])


def _roller_poses(cam, theta):
    """The roller axis from the geometry module's own axis points at two cross-sections (not groove3d's)."""
    lo = np.array([j.value for j in cam._axis_point(theta, 0, None, cam.bottom_radius - 20.0)[0]])
    hi = np.array([j.value for j in cam._axis_point(theta, 0, None, cam.base_radius)[0]])
    w = (hi - lo) / np.linalg.norm(hi - lo, axis=0)
    tip = lo - 40.0 * w  # well below the groove bottom: the roller is unbounded for the design
    return tip[0], tip[1], tip[2], cam.sigma * theta, np.arctan2(w[0], w[2])


def _cam_point(rho, cam_angle_deg, sigma, xs):
    g = -sigma * math.radians(cam_angle_deg)  # part angle of the groove point under the follower at θc
    return np.column_stack([xs, np.full_like(xs, -rho * math.sin(g)), np.full_like(xs, rho * math.cos(g))])


def _near(rho, cam_angle_deg, sigma, a, Y, r):
    """Poses whose axis plane passes within r + 1 mm of the point (a prefilter: others cannot contain it)."""
    beta = -sigma * math.radians(cam_angle_deg) + a
    return (np.cos(beta) > 0) & (np.abs(rho * np.sin(beta) + Y) <= r + 1.0)


@pytest.mark.parametrize("sample,radius,angles", [
    ("cylindrical-translating", 45.0, (30.0, 75.0, 200.0)),
    ("cylindrical-oscillating", 75.0, (80.0, 120.0, 300.0)),
])
def test_walls_against_brute_force_membership(sample, radius, angles):
    cam = cam_of(sample)
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    r_t = spec.machining.tool_diameter_mm / 2
    poses = poses_from_program((DATA / f"legacy-{sample}.ngc").read_text(), assume={"Y": 0.0})
    tool = CylinderTool(r_t, 40.0)
    measured = cut_walls(cam, tool, poses, radius, np.array(angles))
    designed = design_walls(cam, radius, np.array(angles))
    cut = _dense_program_poses(poses)
    roller = _roller_poses(cam, np.radians(np.arange(0.0, 360.0, 0.01)))
    step = 0.002
    for j, ang in enumerate(angles):
        def pts(x):
            return _cam_point(radius, ang, cam.sigma, x)

        k = _near(radius, ang, cam.sigma, cut[3], cut[1], r_t)
        q = [v[k] for v in cut]
        kr = _near(radius, ang, cam.sigma, roller[3], roller[1], cam.roller_radius)
        qr = [v[kr] for v in roller]
        for side in (0, 1):
            xs = measured[j, side] + np.arange(-0.3, 0.3, step)
            wall = _brute_wall(pts, lambda p: _inside_any(p, *q, r_t, 40.0), xs, side)
            # the brute wall sits on the x grid (step); its poses are 0.01° / 0.005 mm apart, a scallop
            # below 1e-5 mm on a tool of radius ≥ 6 mm
            assert abs(wall - measured[j, side]) <= step + 1e-4, (ang, side)
            xs = designed[j, side] + np.arange(-0.3, 0.3, step)
            wall = _brute_wall(pts, lambda p: _inside_any(p, *qr, cam.roller_radius, 4 * cam.base_radius), xs, side)
            # roller poses 0.01° apart move its axis ≤ 0.02 mm at these radii: scallop < 1e-4 mm
            assert abs(wall - designed[j, side]) <= step + 1e-4, (ang, side)


@pytest.mark.parametrize("sample", ["cylindrical-translating", "cylindrical-oscillating"])
@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_design_walls_are_the_contact_geometry(sample, rotation):
    """The designed walls (envelope of the posed roller) against cylindrical.py's contact points on r = ρ."""
    cam = cam_of(sample, rotation)
    th = np.radians(np.linspace(0.0, 359.0, 37))
    for rho in (cam.bottom_radius, cam.reference_radius, cam.base_radius):
        for idx in (0, 1):
            p = cam.flank_on_surface(th, idx, rho)  # cam frame, solved per point by bisection
            part = np.arctan2(-p[:, 1], p[:, 2])  # part angle from +Z by the right-hand rule about +X
            walls = design_walls(cam, rho, np.degrees(-cam.sigma * part) % 360.0)
            # two exact constructions (closed-form envelope refined to 7e-5 of a 0.1 mm sample step,
            # bisection to 1e-15): they agree to rounding
            assert np.abs(walls[:, idx] - p[:, 0]).max() < 1e-9


def _closed_poses(cam, tip_radius_mm: float, step_deg: float) -> ToolPoses:
    """A roller-sized tool on the exact roller axis, its tip at height ``tip_radius_mm`` above the cam axis."""
    th = np.radians(np.arange(0.0, 360.0 + step_deg / 2, step_deg))
    X, Y, Z, a, B = follower_poses(cam, th)
    w = np.stack([np.sin(B), 0 * B, np.cos(B)], axis=-1)
    base = np.stack([X, Y, Z], axis=-1)  # a point of the axis on the cam's axis level
    tip = base + w * ((tip_radius_mm - Z) / np.cos(B))[:, None]
    return ToolPoses(tip, np.degrees(a), np.degrees(B))


@pytest.mark.parametrize("sample", ["cylindrical-translating", "cylindrical-oscillating"])
def test_closed_case_is_zero(sample):
    """A roller-sized tool posed exactly like the roller cuts the designed groove: 0 to the sampling bound.

    The poses are 0.05° apart and the controller moves linearly between them: the chord of the
    follower path then departs from it by ≤ s″·Δθ²/8 (s″ ≤ 37 mm/rad² translating, ≤ 0.08 rad/rad² × 230 mm
    oscillating: ≤ 1.4e-5 mm); the measurement's own bound is h²/8r ≤ 1.6e-4 mm.  The tip is 5 mm below
    the groove bottom (10 mm: a Ø30 end face tilted 15° rises 3.9 mm) so that the flat end never shapes a wall.
    """
    cam = cam_of(sample)
    poses = _closed_poses(cam, cam.bottom_radius - 10.0, 0.05)
    m = measure_groove(cam, CylinderTool(cam.roller_radius, 40.0), poses, radii=5, angle_step_deg=1.0)
    assert m.uncut_points == 0
    assert m.max_deviation_mm <= m.sampling_bound_mm + 2e-5


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
def test_closed_case_sees_the_wrong_sense(rotation):
    """The same exact poses measured against the cam turning the other way: far out (the check is not blind)."""
    cam = cam_of("cylindrical-translating", rotation)
    other = cam_of("cylindrical-translating", "cw" if rotation == "ccw" else "ccw")
    poses = _closed_poses(other, cam.bottom_radius - 5.0, 0.25)
    m = measure_groove(cam, CylinderTool(cam.roller_radius, 40.0), poses, radii=3, angle_step_deg=1.0)
    assert m.max_deviation_mm > 5.0  # a 40 mm rise mirrored: the walls miss by the lift itself


def _legacy(sample):
    return poses_from_program((DATA / f"legacy-{sample}.ngc").read_text(), assume={"Y": 0.0})


def test_legacy_oscillating_figures_of_the_issue():
    """Issue 11: 4 axes, Ø30 tool: about 2 mm left on one wall and 1 mm overcut on the other at the 15° swing, at R75."""
    cam = cam_of("cylindrical-oscillating")
    m = measure_groove(cam, CylinderTool(15.0, 40.0), _legacy("cylindrical-oscillating"), radii=np.array([75.0]),
                       angle_step_deg=0.5)
    j = int(np.argmin(np.abs(m.cam_angle_deg - 80.0)))  # the +15° swing (the dwell at −15° mirrors it)
    at = m.deviation_mm[:, 0, j]
    # the issue's figures come from the tilted roller's span (18.92–49.98) against the tool's (21.00–51.00)
    # at r = 75: 2.08 mm and 1.02 mm along X; normal to the wall (steep there) they are a little less
    assert -2.1 <= at[0] <= -1.9  # −X wall: material left
    assert 0.9 <= at[1] <= 1.1  # +X wall: overcut
    for w in m.walls:  # the extremes are these, at one or the other swing
        assert 1.9 <= w.material_left_mm <= 2.1 and 0.9 <= w.overcut_mm <= 1.1


def test_legacy_translating_figures_of_the_issue():
    """Issue 11: Ø12 tool in a Ø16 roller's groove: 0.029 mm at the reference radius R45, 0.07–0.10 at top/bottom."""
    cam = cam_of("cylindrical-translating")
    m = measure_groove(cam, CylinderTool(6.0, 40.0), _legacy("cylindrical-translating"),
                       radii=np.array([40.25, 45.0, 50.0]), angle_step_deg=0.5)
    worst = np.abs(m.deviation_mm).max(axis=(0, 2))
    assert abs(worst[1] - 0.029) <= 0.001  # the issue's 0.029 mm normal to the wall at R45
    # the issue's "0.07–0.10 at top and bottom" was a developed-plane estimate; in 3-D the top is 0.072 and
    # 0.25 mm above the bottom (clear of the band where the tool's flat end shapes the wall) 0.103
    assert 0.07 <= worst[2] <= 0.10 and 0.09 <= worst[0] <= 0.11
    assert m.deviation_mm[:, 2].max() > 0.07  # the top is overcut …
    assert m.deviation_mm[:, 0].min() < -0.07  # … and the bottom keeps material


@settings(max_examples=120, deadline=None)
@example(X=0.0, Y=0.0, Z=30.0, a=0.0, B=2.870757905050182e-127, r=2.0, L=5.0, rho=30.0, gamma=0.0)
@given(X=st.floats(-20, 20), Y=st.floats(-3, 3), Z=st.floats(20, 60), a=st.floats(-math.pi, math.pi),
       B=st.floats(-0.6, 0.6), r=st.floats(2, 20), L=st.floats(5, 60), rho=st.floats(30, 80),
       gamma=st.floats(-math.pi, math.pi))
def test_section_interval_is_the_membership_of_the_line(X, Y, Z, a, B, r, L, rho, gamma):
    """The closed-form x-interval of a posed cylinder on r = ρ against 3-D point membership along that line."""
    from camcam.verify.groove_motion import section_interval

    # not the degenerate pose where the line lies in the tip plane or the end plane (an untilted tool with
    # ζ = ρ cos(γ + a) − Z at 0 or L): every point of the section is then on the boundary, and membership
    # is decided by rounding (hypothesis found X=0, Y=0, Z=30, a=0, B=2.9e-127, r=2, L=5, ρ=30, γ=0)
    zeta = rho * math.cos(gamma + a) - Z
    assume(abs(math.sin(B)) > 1e-9 or min(abs(zeta), abs(zeta - L)) > 1e-9)
    lo, hi = (float(v) for v in section_interval(X, Y, Z, a, B, r, L, rho, gamma))

    def inside(x):
        p = _cam_point(rho, 0.0, 1, np.array([x]))
        c, s = math.cos(gamma), math.sin(gamma)  # the point at part angle γ: rotate (0, 0, ρ) by γ
        p[0, 1], p[0, 2] = -rho * s, rho * c
        return bool(_inside_any(p, np.array([X]), np.array([Y]), np.array([Z]), np.array([a]), np.array([B]),
                                r, L)[0])

    eps = 1e-7  # well above the rounding of a closed form evaluated in doubles at these sizes
    if math.isnan(lo):
        xs = np.linspace(X - r - L, X + r + L, 801)  # a miss: no point of the line is inside
        assert not any(inside(x) for x in xs)
        return
    assert inside(0.5 * (lo + hi))
    assert not inside(lo - eps) and not inside(hi + eps)
    if hi - lo > 2 * eps:
        assert inside(lo + eps) and inside(hi - eps)


def _section_interval_reference(X, Y, Z, a, B, r, L, rho, gamma):
    """section_interval as first written: one fresh array per operation (the in-place version must equal it)."""
    beta = gamma + a
    sb, cb = np.sin(B), np.cos(B)
    eta = rho * np.sin(beta) + Y
    zeta = rho * np.cos(beta) - Z
    q2 = r * r - eta * eta
    q = np.sqrt(np.maximum(q2, 0.0))
    lo = (zeta * sb - q) / cb
    hi = (zeta * sb + q) / cb
    tilted = np.abs(sb) > 1e-15
    safe = np.where(tilted, sb, 1.0)
    e0 = -zeta * cb / safe
    e1 = (L - zeta * cb) / safe
    alo = np.where(sb > 0, e0, e1)
    ahi = np.where(sb > 0, e1, e0)
    lo = np.where(tilted, np.maximum(lo, alo), lo)
    hi = np.where(tilted, np.minimum(hi, ahi), hi)
    ok = (q2 >= 0) & (lo <= hi) & (tilted | ((zeta >= 0) & (zeta <= L)))
    return np.where(ok, X + lo, np.nan), np.where(ok, X + hi, np.nan)


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 300), tilted=st.floats(0.0, 1.0),
       r=st.floats(1, 20), L=st.floats(2, 80), rho=st.floats(20, 80), scalar_gamma=st.booleans())
def test_section_interval_in_place_equals_the_plain_formula(seed, n, tilted, r, L, rho, scalar_gamma):
    """Bit for bit (the in-place arithmetic does the same operations in the same order), with and
    without a caller's sin/cos of B, on pairs inside and outside the β window."""
    from camcam.verify.groove_motion import section_interval

    rng = np.random.default_rng(seed)
    X, Y = rng.uniform(-50, 50, n), rng.uniform(-r, r, n)
    gamma = 0.7 if scalar_gamma else rng.uniform(-np.pi, np.pi, n)
    a = np.arcsin(np.clip((rng.uniform(-1.2 * r, 1.2 * r, n) - Y) / rho, -1, 1)) - gamma  # mostly in the window
    # the tip's depth ζ = ρ cos β − Z mostly along the tool: tilted sections are then often cut by the
    # tip plane or the end (the axial bounds' arithmetic is exercised)
    Z = rho * np.cos(gamma + a) - rng.uniform(-0.3 * L, 1.3 * L, n)
    B = np.where(rng.uniform(size=n) < tilted, rng.uniform(-0.7, 0.7, n), 0.0)
    want = _section_interval_reference(X, Y, Z, a, B, r, L, rho, gamma)
    for got in (section_interval(X, Y, Z, a, B, r, L, rho, gamma),
                section_interval(X, Y, Z, a, B, r, L, rho, gamma, (np.sin(B), np.cos(B)))):
        assert all(np.array_equal(g, w, equal_nan=True) for g, w in zip(got, want))


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, 300), tilted=st.floats(0.0, 1.0),
       r=st.floats(1, 20), L=st.floats(2, 80), rho=st.floats(20, 80))
def test_section_interval_from_angle_sums_is_the_plain_formula(seed, n, tilted, r, L, rho):
    """A regular-grid envelope passes sin and cos of β = γ + a made by the angle-addition formulas
    (groove_motion.sincos_sum) instead of the sine of the rounded sum: the same section to 1e-9 mm.

    Why 1e-9 mm: the two sines differ by a few units in the last place of 1 (≤ 1e-15), so η and ζ by
    ≤ ρ·1e-15 ≤ 1e-13 mm; the half width q = √(r² − η²) turns that into η/q times as much (≤ 20/1e-3 where
    q ≥ 1e-3 mm, the pairs compared) and 1/cos B (≤ 1.3 for |B| ≤ 0.7): ≤ 3e-9 in the worst product,
    1e-9 with the margins seen.  Pairs within 1e-9 mm of a decision (tangent, tip plane, end, empty
    interval) may fall either way and are not compared; every other pair hits or misses alike."""
    from camcam.verify.groove_motion import section_interval, sincos_sum

    rng = np.random.default_rng(seed)
    X, Y = rng.uniform(-50, 50, n), rng.uniform(-r, r, n)
    gamma = rng.uniform(-np.pi, 3 * np.pi, n)  # the envelope's grid angles run past 2π
    a = np.arcsin(np.clip((rng.uniform(-1.2 * r, 1.2 * r, n) - Y) / rho, -1, 1)) - gamma  # mostly in the window
    Z = rho * np.cos(gamma + a) - rng.uniform(-0.3 * L, 1.3 * L, n)
    B = np.where(rng.uniform(size=n) < tilted, rng.uniform(-0.7, 0.7, n), 0.0)
    want = _section_interval_reference(X, Y, Z, a, B, r, L, rho, gamma)
    beta = sincos_sum(np.sin(gamma), np.cos(gamma), np.sin(a), np.cos(a))
    got = section_interval(X, Y, Z, None, B, r, L, rho, None, (np.sin(B), np.cos(B)), beta)
    # the plain formula's decision margins
    eta = rho * np.sin(gamma + a) + Y
    zeta = rho * np.cos(gamma + a) - Z
    q2 = r * r - eta * eta
    q = np.sqrt(np.maximum(q2, 0.0))
    sb, cb = np.sin(B), np.cos(B)
    tilted_ = np.abs(sb) > 1e-15
    lo_raw, hi_raw = (zeta * sb - q) / cb, (zeta * sb + q) / cb
    safe = np.where(tilted_, sb, 1.0)
    e0, e1 = -zeta * cb / safe, (L - zeta * cb) / safe
    lo_a = np.where(tilted_, np.maximum(lo_raw, np.where(sb > 0, e0, e1)), lo_raw)
    hi_a = np.where(tilted_, np.minimum(hi_raw, np.where(sb > 0, e1, e0)), hi_raw)
    clear = ((q >= 1e-3) | (q2 < -1e-9)) & (np.abs(hi_a - lo_a) > 1e-6) & \
        (tilted_ | ((np.abs(zeta) > 1e-9) & (np.abs(zeta - L) > 1e-9)))
    for g, w in zip(got, want):
        assert np.array_equal(np.isnan(g[clear]), np.isnan(w[clear]))
        both = clear & ~np.isnan(w) & ~np.isnan(g)
        assert np.all(np.abs(g[both] - w[both]) <= 1e-9)


@pytest.mark.parametrize("sample", ["cylindrical-translating", "cylindrical-oscillating"])
def test_scattered_envelope_at_many_radii_is_each_alone_and_the_map(sample):
    """A scattered envelope of points each at its own radius (the refinement's radii in one call) against one
    call per point, and against the regular map at those angles."""
    from camcam.verify.groove_envelope import envelope as _envelope
    from camcam.verify.groove_motion import ProgramMotion, RollerMotion

    cam = cam_of(sample)
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    program = poses_from_program((DATA / f"legacy-{sample}.ngc").read_text(), assume={"Y": 0.0})
    tool = CylinderTool(spec.machining.tool_diameter_mm / 2, 40.0)
    grid = np.radians(np.arange(1440) * 0.25)
    at = np.array([40, 380, 720, 1000, 1439])
    for motion in (RollerMotion(cam), ProgramMotion(program, tool)):
        s = motion.samples(0.1, cam.base_radius)
        poses = motion.pose(s)
        rho = np.linspace(cam.bottom_radius, cam.base_radius, len(at))
        both = _envelope(motion, s, poses, rho, grid[at])
        for i in range(len(at)):
            alone = _envelope(motion, s, poses, float(rho[i]), grid[at[i]:at[i] + 1])
            mapped = _envelope(motion, s, poses, float(rho[i]), grid)
            for side in (0, 1):
                # exactly: each (point, sample) pair's section is the same arithmetic, element by element
                np.testing.assert_allclose(both[side].value[i], alone[side].value[0], rtol=0, atol=0)
                # the map takes sin(γ + a) by the angle-addition formulas: a few ulps of 50 mm apart
                np.testing.assert_allclose(both[side].value[i], mapped[side].value[at[i]], rtol=0, atol=1e-9)


def _every_pair_best(poses, r, L, rho, gamma):
    """The scattered envelope's best samples with every (angle, sample) pair tested (what it did before the
    sorted prefilter on the windows' centres): (best_v, best_j), each (2, k)."""
    from camcam.verify.groove_envelope import _windows
    from camcam.verify.groove_motion import section_interval, wall_extents

    X, Y, Z, a, B = poses
    best_v, best_j = np.full((2, len(gamma)), -np.inf), np.full((2, len(gamma)), -1)
    radii, row = np.unique(np.asarray(rho, float), return_inverse=True)
    reach, lo_s, hi_s = _windows(poses, r, radii)
    g, w = gamma[:, None], row
    d_lo = np.mod(g + a - lo_s[w] + math.pi, 2 * math.pi) - math.pi
    d_hi = np.mod(hi_s[w] - g - a + math.pi, 2 * math.pi) - math.pi
    ii, js = np.nonzero(reach[w] & (d_lo >= 0) & (d_hi >= 0))
    lo, hi = section_interval(X[js], Y[js], Z[js], a[js], B[js], r, L, radii[w[ii]], gamma[ii])
    for side, v in enumerate(wall_extents(lo, hi)):
        for i in np.unique(ii):
            m = np.flatnonzero(ii == i)
            k = m[int(np.argmax(v[m]))]
            if np.isfinite(v[k]):
                best_v[side, i], best_j[side, i] = v[k], js[k]
    return best_v, best_j


@pytest.mark.parametrize("sample", ["cylindrical-translating", "cylindrical-oscillating"])
@pytest.mark.parametrize("seed", [1, 2])
def test_scattered_prefilter_finds_what_every_pair_finds(sample, seed):
    """The scattered envelope tests only the pairs whose window centre is near the angle: the best sample and
    its extent at every angle are those of every pair tested, exactly (angles anywhere, radii from below
    the groove bottom to over the outer radius, both motions)."""
    from camcam.verify.groove_envelope import _scattered_best
    from camcam.verify.groove_motion import ProgramMotion, RollerMotion

    cam = cam_of(sample)
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    program = poses_from_program((DATA / f"legacy-{sample}.ngc").read_text(), assume={"Y": 0.0})
    tool = CylinderTool(spec.machining.tool_diameter_mm / 2, 40.0)
    rng = np.random.default_rng(seed)
    gamma = np.concatenate([rng.uniform(-2 * math.pi, 4 * math.pi, 60), [0.0, 2 * math.pi, -math.pi]])
    rho = rng.choice(np.linspace(cam.bottom_radius - 2.0, cam.base_radius + 2.0, 7), len(gamma))
    for motion in (RollerMotion(cam), ProgramMotion(program, tool)):
        poses = motion.pose(motion.samples(0.1, cam.base_radius))
        best_v, best_j = np.full((2, len(gamma)), -np.inf), np.full((2, len(gamma)), -1)
        _scattered_best(poses, motion.r, motion.L, rho, gamma, best_v, best_j)
        want_v, want_j = _every_pair_best(poses, motion.r, motion.L, rho, gamma)
        assert np.array_equal(best_j, want_j) and np.array_equal(best_v, want_v)
        assert (best_j >= 0).sum() > len(gamma)  # most angles reach a sample on both sides: not a vacuous check


@pytest.mark.parametrize("sample", ["cylindrical-translating", "cylindrical-oscillating"])
def test_extremes_refined_together_are_each_refined_alone(sample):
    """measure_groove refines its four extremes in one envelope a step (issue 49); each extreme's radius, angle
    and exact figure are those it has refined alone, to the bit (a scattered envelope's figure at an angle does
    not depend on the other angles of the call), on both walls and both signs."""
    from camcam.verify.groove3d import _refine, _Setup

    cam = cam_of(sample)
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    program = poses_from_program((DATA / f"legacy-{sample}.ngc").read_text(), assume={"Y": 0.0})
    setup = _Setup(cam, CylinderTool(spec.machining.tool_diameter_mm / 2, 40.0), program, 0.1)
    rb, R = cam.bottom_radius, cam.base_radius
    found = [(0, 1.0, R, 0.4), (0, -1.0, rb, 2.0), (1, 1.0, 0.5 * (rb + R), 3.5), (1, -1.0, R, 5.0)]
    together = _refine(setup, found, rb, R, 0.25 * (R - rb), math.radians(1.0))
    alone = [_refine(setup, [f], rb, R, 0.25 * (R - rb), math.radians(1.0))[0] for f in found]
    assert together == alone
    assert len({t[2] for t in together}) == 4  # four different figures: not one extreme four times
