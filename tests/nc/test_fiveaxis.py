"""5 axes for an oscillating roller's barrel cam, checked in 3-D on the printed and the interpreted program.

The measure is :mod:`tests.nc.swept` (brute force, written from the machine-frame contract with its own
rotation matrices, walls from the cam geometry); nothing here trusts the fit's own error model.
"""

from __future__ import annotations

import functools
import math
import re
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.errors import GeometryError, SpecError
from camcam.geometry.build import build_cam
from camcam.nc.fiveaxis import ToolPose, part_pose, tip_lengths
from camcam.verify import checked
from camcam.post.post import load_post
from camcam.spec import load_spec
from camcam.verify.rs274 import rs274_available, run_rs274, tcp_readable
from tests.nc.swept import parse_moves, part_poses, rapid_clearance, rx, ry, wall_deviation

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "cylindrical-oscillating.toml"
needs_rs274 = pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")
# the swept check samples A every 0.05°: the tool moves ≤ 0.05° · 80 mm = 0.07 mm along the groove between
# poses, so a distance minimum can hide by ≤ 0.07²/(2 · 15) = 1.7e-4 mm; it is added to the tolerance
SAMPLING_MM = 1.7e-4


@functools.lru_cache(maxsize=None)
def job(post: str = "linuxcnc", rotation: str = "ccw", a_axis: str = "right-hand", axes: int = 5):
    spec = load_spec(SAMPLE)
    cam_spec = replace(spec.cam, rotation=rotation)
    built = build_cam(cam_spec, spec.follower, spec.motion.program(spec.unit))
    m = replace(spec.machining, post=load_post(post), a_axis=a_axis, axes=axes)
    return built, m, checked(built, m, spec.name)


def groove_deviation(built, moves, a_axis="right-hand", n_theta=240, radii=3):
    """Largest overcut and largest material left (mm) over both walls at ``radii`` radii, bottom to top."""
    cam = built.cam
    tips, axes, _ = part_poses(moves, a_axis, max_da_deg=0.05, max_step_mm=0.1)
    th = np.linspace(0.0, 2 * math.pi, n_theta, endpoint=False) + 0.3 / n_theta
    over = left = 0.0
    for r in np.linspace(cam.bottom_radius, cam.base_radius, radii):
        for flank in (0, 1):
            d = wall_deviation(cam.flank_on_surface(th, flank, r), tips, axes, cam.roller_radius)
            over, left = max(over, -d.min()), max(left, d.max())
    return over, left


def test_sample_is_five_axis_by_default():
    spec = load_spec(SAMPLE)
    assert spec.machining.axes == 5  # oscillating roller on a cylindrical cam
    _, _, r = job()
    assert r.toolpath.five_axis
    assert " B" in r.program.text


def test_sample_groove_within_tolerance_in_3d():
    built, m, r = job()
    over, left = groove_deviation(built, parse_moves(r.program.text), n_theta=360, radii=5)
    # the whole groove, both walls, five radii from the bottom (70) to the top (80): within ±0.01
    assert over <= m.tolerance_mm + SAMPLING_MM
    assert left <= m.tolerance_mm + SAMPLING_MM
    # and not trivially: the cut touches the walls (a deviation near 0 both ways means it follows them)
    assert over > 0.1 * m.tolerance_mm


def test_rapids_stay_above_the_cam():
    built, m, r = job()
    clear = rapid_clearance(parse_moves(r.program.text), built.cam.base_radius, built.cam.roller_radius)
    assert clear >= m.clearance_z_mm - 1e-3  # the tool's low edge, rounded to the post's grid


def test_header_states_the_frame():
    _, _, r = job()
    head = "\n".join(r.program.text.splitlines()[:14])
    for words in ("cam axis = machine X", "Rx[A]*p", "[sin B, 0, cos B]", "right-hand rule about +Y",
                  "X Y Z = tool tip", "G93 inverse time"):
        assert words in head


def test_cw_cuts_the_mirrored_groove():
    built_ccw, _, ccw = job()
    built_cw, m, cw = job(rotation="cw")
    a = parse_moves(ccw.program.text)
    b = parse_moves(cw.program.text)
    # mirror about the X-Z plane: a part point (x, y, z) → (x, −y, z) is A → −A with X Z B kept
    assert len(a) == len(b)
    assert all(p[:3] == q[:3] and p[4] == q[4] and p[3] == -q[3] + 0.0 for (_, p), (_, q) in zip(a, b))
    over, left = groove_deviation(built_cw, b)
    assert max(over, left) <= m.tolerance_mm + SAMPLING_MM
    # the ccw program cuts a cw cam wrongly: the two grooves differ by far more than the tolerance
    wrong_over, wrong_left = groove_deviation(built_cw, a, n_theta=60, radii=1)
    assert max(wrong_over, wrong_left) > 1.0


def test_left_hand_a_axis_negates_a():
    built, m, left = job(a_axis="left-hand")
    _, _, right = job()
    a = parse_moves(right.program.text)
    b = parse_moves(left.program.text)
    assert all(p[:3] == q[:3] and p[3] == -q[3] + 0.0 for (_, p), (_, q) in zip(a, b))
    over, lft = groove_deviation(built, b, a_axis="left-hand")
    assert max(over, lft) <= m.tolerance_mm + SAMPLING_MM


@settings(max_examples=60, deadline=None)
@given(st.floats(-400, 400), st.floats(-60, 60), st.floats(-50, 50), st.floats(0, 90))
def test_part_pose_matches_rotation_matrices(a, b, x, z):
    # contract: p_machine = Rx(A)·p_part; tool axis = Ry(B)·e_z; independent 3×3 matrices
    tip, axis = part_pose(x, 0.0, z, a, b)
    R = rx(math.radians(a)).T
    assert np.allclose(tip[0], R @ np.array([x, 0.0, z]), atol=1e-9)  # float round-off only
    assert np.allclose(axis[0], R @ ry(math.radians(b)) @ np.array([0.0, 0.0, 1.0]), atol=1e-12)


def test_b_is_the_follower_angle_and_tip_on_the_roller_axis():
    built, _, r = job()
    cam = built.cam
    pose = ToolPose.of(cam, cam.roller_radius, "right-hand")
    th = np.linspace(0, 2 * math.pi, 37)
    xzb = pose.at(th)
    f = np.degrees(cam.lift(th, 0).value)
    assert np.allclose(xzb[:, 2], f, atol=1e-12)  # B = θf (deg)
    # the tip lies on the line from the pivot (length/2, 0, d) along −(sin B, 0, cos B)
    d = cam.follower.pivot_distance
    b = np.radians(xzb[:, 2])
    rel = np.column_stack([xzb[:, 0] - cam.length / 2, xzb[:, 1] - d])
    cross = rel[:, 0] * np.cos(b) - rel[:, 1] * np.sin(b)
    assert np.abs(cross).max() < 1e-9  # collinear up to round-off


def test_inverse_time_feed_is_the_tip_feed():
    _, m, r = job()
    lines = [ln for ln in r.program.text.splitlines() if ln.startswith("G1") and " A" in ln and " F" in ln]
    moves = parse_moves(r.program.text)
    feeds = [(k, p) for k, p in moves if k == "feed"]
    # first contour block of the first pass: rebuild its tip path in the part with the matrices
    idx = [i for i, (k, p) in enumerate(feeds) if i and p[3] != feeds[i - 1][1][3]][0]
    p0, p1 = np.array(feeds[idx - 1][1]), np.array(feeds[idx][1])
    pts = [rx(math.radians(q[3])).T @ np.array(q[:3]) for q in (p0 + (p1 - p0) * t for t in np.linspace(0, 1, 2001))]
    length = float(np.sum(np.linalg.norm(np.diff(pts, axis=0), axis=1)))
    f = float(re.search(r"F([\d.]+)", lines[0]).group(1))
    assert f * length == pytest.approx(m.feed_mm_min, rel=1e-3)  # F printed to 1e-4 of ~100 /min
    assert tip_lengths(np.array([[p0[0], p0[2], p0[3], p0[4]], [p1[0], p1[2], p1[3], p1[4]]]))[0] == \
        pytest.approx(length, rel=1e-6)  # Simpson vs a 2000-chord polyline


@pytest.mark.parametrize("post,on,off", [("fanuc", "G43.4 H1", "G49"), ("haas", "G234 H01", "G49"),
                                         ("sinumerik", "TRAORI", "TRAFOOF"), ("heidenhain", "M128", "M129")])
def test_posts_switch_tcp(post, on, off):
    _, _, r = job(post)
    lines = [re.sub(r"^N?\d+ ", "", ln) for ln in r.program.text.splitlines()]
    i_on, i_off = lines.index(on), len(lines) - 1 - lines[::-1].index(off)
    moves = [i for i, ln in enumerate(lines) if re.match(r"(G[01] |L )", ln) and " B" in ln]
    assert moves and i_on < moves[0] and moves[-1] < i_off
    if post != "heidenhain":
        assert lines.index("G93") > i_on and lines.index("G94") < i_off


def test_grbl_refuses_five_axis(tmp_path):
    spec = tmp_path / "c.toml"
    spec.write_text(SAMPLE.read_text().replace('post = "linuxcnc"', 'post = "grbl"'))
    with pytest.raises(SpecError, match="no 5-axis mode"):
        load_spec(spec)
    r = subprocess.run([sys.executable, "-m", "camcam", "run", str(spec), "-o", str(tmp_path / "out")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "grbl" in r.stderr
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_axes_4_still_possible():
    _, _, r = job(axes=4)
    assert not r.toolpath.five_axis
    assert re.search(r"\bB-?\d", r.program.text) is None


def test_smaller_tool_refused_with_five_axes():
    built, m, _ = job()
    with pytest.raises(GeometryError, match="roller's diameter"):
        checked(built, replace(m, tool_diameter_mm=20.0), "c")


def test_axes_5_refused_for_translating_roller(tmp_path):
    text = (ROOT / "samples" / "cylindrical-translating.toml").read_text()
    spec = tmp_path / "t.toml"
    spec.write_text(text.replace("[machining]", "[machining]\naxes = 5"))
    with pytest.raises(SpecError, match="machining.axes"):
        load_spec(spec)


@needs_rs274
@pytest.mark.parametrize("post", ["linuxcnc", "fanuc", "haas"])
def test_interpreted_program_within_tolerance_in_3d(tmp_path, post):
    built, m, r = job(post)
    tcp = tuple(line.format(tool=m.tool_number) for line in r.post.tcp_on)
    prog, ini = tcp_readable(r.program.text, tcp, tmp_path)
    canon = run_rs274(prog, ini=ini)
    assert any(mv.b != 0.0 for mv in canon)  # rs274 carries B
    moves = [("rapid" if mv.kind == "rapid" else "feed", (mv.x, mv.y, mv.z, mv.a, mv.b)) for mv in canon]
    # the interpreted positions are the printed ones (≤ 4 decimals: rs274 prints 4)
    printed = [p for k, p in parse_moves(r.program.text) if k == "feed"]
    interpreted = [p for k, p in moves if k == "feed"]
    assert len(interpreted) == len(printed)
    assert np.abs(np.array(interpreted) - np.array(printed)).max() < 1e-9  # ≤ 4 decimals: rs274 prints them exactly
    over, left = groove_deviation(built, moves)
    assert max(over, left) <= m.tolerance_mm + SAMPLING_MM


# -- issue 43: the design-space campaign's 5-axis FAILs at the seam (cam angle 0/360) ---------------------------
DATA = ROOT / "tests" / "nc" / "data"


def spec_job(path: Path):
    spec = load_spec(path)
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    return built, spec.machining, checked(built, spec.machining, spec.name)


def read_back(r, m, tmp_path) -> list:
    """The program's moves as rs274 interprets them (the printed words where rs274 is missing)."""
    if not rs274_available():
        return parse_moves(r.program.text)
    tcp = tuple(line.format(tool=m.tool_number) for line in r.post.tcp_on)
    prog, ini = tcp_readable(r.program.text, tcp, tmp_path)
    return [("rapid" if mv.kind == "rapid" else "feed", (mv.x, mv.y, mv.z, mv.a, mv.b)) for mv in run_rs274(prog, ini=ini)]


@pytest.mark.parametrize("key", ["43-404", "43-425"])
def test_return_to_machine_home_is_no_cut_at_the_seam(key, tmp_path):
    # campaign cases 43:404 (fanuc, footer "G91 G28 Z0.") and 43:425 (haas, "G53 G00 Z0."): the pose reader took
    # the return to machine Z home for a move to work Z0, on the cam axis, after B went back to 0 — a radial tool
    # plunged through the groove at cam angle 0/360: FAIL 2.116 mm of 0.0034 and 0.2125 of 0.002 (overcut on
    # flank 0 at cam angle 0), and "cut depth 74.5 mm, the tool reaches R0".  The program was right all along.
    built, m, r = spec_job(DATA / f"fiveaxis-seam-{key}.toml")
    footer = "G91 G28 Z0." if key == "43-404" else "G53 G00 Z0."
    assert any(line.endswith(footer) for line in r.program.text.splitlines())
    check = {c.name: c for c in r.checks}["3-D groove deviation"]
    assert check.ok and check.value <= m.tolerance_mm
    assert r.reach.deepest_radius_mm > built.cam.bottom_radius - 2 * built.cam.roller_radius  # not R0
    # the independent read-back: rs274's moves swept against the walls, five radii, 720 angles
    over, left = groove_deviation(built, read_back(r, m, tmp_path), a_axis=m.a_axis, n_theta=720, radii=5)
    assert max(over, left) <= m.tolerance_mm + SAMPLING_MM
    assert check.value == pytest.approx(max(over, left), abs=0.1 * m.tolerance_mm)  # the report agrees with it


@pytest.mark.parametrize("footer", ["G91 G28 Z0.", "G53 G00 Z0.", "G28 G91 Z0"])
def test_pose_reader_leaves_the_work_frame_at_a_return_home(footer):
    from camcam.post.readback import poses_from_program
    text = f"G90 G0 X5 Y0 Z90 A0 B0\nG1 Z60 F9\nG1 X8 A90 B-12\nG0 Z90\nG0 B0\nM5\n{footer}\nM30\n"
    p = poses_from_program(text)
    assert p.tip_mm[:, 2].min() == 60.0  # the retract goes up machine Z, never to work Z0
    assert p.tip_mm[-1].tolist() == [8.0, 0.0, 90.0] and p.b_deg[-1] == 0.0
    with pytest.raises(ValueError, match="reference point"):
        poses_from_program(text.replace("M30", "G90 G0 X0 Y0 Z50 A0"))


def test_short_flute_advice_names_the_flute_that_holds(tmp_path):
    # campaign case 43:404 with flute_length = 6 where the cut reaches 10.04 mm up the tool: the top of the walls
    # stays (10.48 mm); the advice said "check flute_length (the cut needs 10.04 mm from the tip) and depth, or
    # accept a tolerance of at least 10.4822 mm", no setting.  It names [machining] flute_length, and that holds
    from tests.designspace import parse_advice

    text = (DATA / "fiveaxis-seam-43-404.toml").read_text().replace("axes = 5", "axes = 5\nflute_length = 6")
    short = tmp_path / "short.toml"
    short.write_text(text)
    _, _, r = spec_job(short)
    check = {c.name: c for c in r.checks}["3-D groove deviation"]
    assert not check.ok and check.value > 1.0
    ((section, key, value),) = parse_advice(check.advice, strict=True)
    assert (section, key) == ("machining", "flute_length") and value >= r.reach.flute_needed_mm
    fixed = tmp_path / "fixed.toml"
    fixed.write_text(text.replace("flute_length = 6", f"flute_length = {value:g}"))
    built, m, r2 = spec_job(fixed)
    check2 = {c.name: c for c in r2.checks}["3-D groove deviation"]
    assert m.flute_length_mm == value and check2.ok
    assert r2.reach.flute_needed_mm <= value
    # independently: the moves rs274 reads, swept (the sweep does not limit the flute: the reach above holds it)
    over, left = groove_deviation(built, read_back(r2, m, tmp_path), a_axis=m.a_axis, n_theta=360, radii=5)
    assert max(over, left) <= m.tolerance_mm + SAMPLING_MM
