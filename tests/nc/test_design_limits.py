"""Issue 43, design limits in the verdict: the pressure angle and the radius of curvature are checks with a state
PASS, WARN or FAIL; ``[cam] design_limits = "fail"`` makes a miss exit 3 with one line whose advice works."""

from __future__ import annotations

import json
import re
from dataclasses import replace
from pathlib import Path

from camcam.geometry.build import build_cam
from camcam.nc.design_checks import design_checks
from camcam.spec import load_spec
from camcam.verdict import Check, Verdict
from tests.cli.test_exit_status import cli

ROOT = Path(__file__).resolve().parents[2]
DISC = ROOT / "samples" / "disc-translating-roller.toml"


def _disc_without_machining(tmp_path: Path, cam_keys: str, base_radius: float | None = None) -> Path:
    text = DISC.read_text().split("[stock]")[0]
    text = text.replace('rotation = "ccw"\n', 'rotation = "ccw"\n' + cam_keys)
    if base_radius is not None:
        text = text.replace("base_radius = 40.0", f"base_radius = {base_radius}")
    spec = tmp_path / f"limits-{len(list(tmp_path.iterdir()))}.toml"
    spec.write_text(text)
    return spec


def test_seed002_pressure_angle_is_a_warn_verdict_not_a_pass(tmp_path):
    code, out, err = cli("run", str(ROOT / "samples" / "reverse" / "seed002.toml"), "-o", str(tmp_path))
    assert code == 0 and err == ""
    verdict = [ln for ln in out.splitlines() if re.match(r"(PASS|WARN|FAIL): ", ln)]
    assert len(verdict) == 1 and verdict[0].startswith(
        "WARN: pressure angle 46.39 deg over the advisory limit 35 deg (program angle 325.57°")
    report = json.loads((tmp_path / "seed002-reverse-report.json").read_text())
    assert report["verdict"]["status"] == "WARN"
    assert {c["name"]: c["state"] for c in report["verdict"]["checks"]} == {
        "pressure angle": "WARN", "radius of curvature": "PASS"}
    html = (tmp_path / "seed002-reverse-report.html").read_text()
    assert html.index('<p class="verdict warn">WARN</p>') < html.index("pressure angle")  # the page opens with it


def test_design_limits_fail_exits_3_with_advice_that_works(tmp_path):
    # the sample's largest pressure angle is 22.26°: a 20° hard limit is missed
    spec = _disc_without_machining(tmp_path, 'max_pressure_angle_deg = 20.0\ndesign_limits = "fail"\n')
    code, out, err = cli("run", str(spec), "-o", str(tmp_path / "a"))
    assert code == 3
    assert len(err.splitlines()) == 1 and err.startswith("camcam: FAIL: pressure angle 22.26 deg over the limit 20 deg")
    assert 'design_limits = "warn"' in err  # the other way out: take it as advisory
    radius = float(re.search(r"cam\.base_radius >= ([0-9.]+) mm brings it within 20°", err).group(1))
    assert 40.0 < radius < 80.0
    # the advice followed: exit 0 with every check within its limit
    code, out, err = cli("run", str(_disc_without_machining(tmp_path, 'max_pressure_angle_deg = 20.0\n'
                                                            'design_limits = "fail"\n', radius)), "-o", str(tmp_path / "b"))
    assert code == 0 and err == "" and out.splitlines()[-1].startswith("PASS: ")
    # the other way out followed: the same miss is a WARN and the run exits 0
    code, out, err = cli("run", str(_disc_without_machining(tmp_path, 'max_pressure_angle_deg = 20.0\n'
                                                            'design_limits = "warn"\n')), "-o", str(tmp_path / "c"))
    assert code == 0 and err == "" and out.splitlines()[-1].startswith("WARN: pressure angle 22.26 deg")


def test_design_limits_is_validated(tmp_path):
    code, out, err = cli("run", str(_disc_without_machining(tmp_path, 'design_limits = "hard"\n')), "-o",
                         str(tmp_path / "a"))
    assert code == 2 and err == 'camcam: error: cam.design_limits: expected one of "warn", "fail", got "hard"\n'
    assert not (tmp_path / "a").exists()


def test_radius_of_curvature_is_a_check_with_a_least_limit_and_measured_advice():
    spec = load_spec(DISC)
    program = spec.motion.program(spec.unit)
    built = build_cam(spec.cam, spec.follower, program)
    checks = {c.name: c for c in design_checks(built)}
    rho = checks["radius of curvature"]
    # the default limit is half the roller radius (the pitch curve bends at least 1.5 roller radii)
    assert rho.ok and rho.limit == 5.0 and rho.value == built.analysis.profile.min_radius_mm
    tight = replace(spec.cam, min_curvature_radius_mm=40.0, design_limits="fail")  # the profile's is 38.29 mm
    rho = {c.name: c for c in design_checks(build_cam(tight, spec.follower, program))}["radius of curvature"]
    assert rho.state == "FAIL" and rho.describe().startswith("radius of curvature 38.29 mm below the limit 40 mm")
    radius = float(re.search(r"cam\.base_radius >= ([0-9.]+) mm brings it to 40 mm", rho.advice).group(1))
    again = build_cam(replace(tight, base_radius=radius), spec.follower, program)
    assert {c.name: c for c in design_checks(again)}["radius of curvature"].state == "PASS"


def test_verdict_states():
    ok = Check("NC deviation", 0.008, 0.01, "mm", ok=True)
    warn = Check("pressure angle", 46.39, 35.0, "deg", ok=False, severity="warn")
    fail = Check("3-D groove deviation", 0.08, 0.02, "mm", ok=False)
    assert [c.state for c in (ok, warn, fail)] == ["PASS", "WARN", "FAIL"]
    assert Verdict((ok,)).status == "PASS" and Verdict((ok, warn)).status == "WARN"
    assert Verdict((ok, warn, fail)).status == "FAIL"
    assert Verdict((ok, warn)).exit_status == 0 and Verdict((warn, fail)).exit_status == 3
    assert Verdict((ok, warn)).line().startswith("WARN: pressure angle 46.39 deg over the advisory limit 35 deg")
    assert Verdict((ok, warn)).line().endswith("; 1 other check within its limit")
