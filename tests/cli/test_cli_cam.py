"""`camcam run` on the cam samples: STL, plot and report; undercut as one line, exit 2."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
import trimesh

ROOT = Path(__file__).resolve().parents[2]


def camcam(*args):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "camcam", *args], capture_output=True, text=True, env=env)


@pytest.mark.parametrize("name", ["disc-translating-roller", "disc-oscillating-flat", "cylindrical-oscillating"])
def test_run_writes_cam_outputs(name, tmp_path):
    r = camcam("run", str(ROOT / "samples" / f"{name}.toml"), "-o", str(tmp_path))
    assert r.returncode == 0, r.stderr
    report = json.loads((tmp_path / f"{name}-report.json").read_text())
    for key in ("max_pressure_angle_deg", "max_pressure_angle_at_deg", "min_curvature_radius_mm", "min_curvature_radius_at_deg"):
        assert isinstance(report[key], float)
    assert trimesh.load(tmp_path / f"{name}.stl").is_watertight
    assert (tmp_path / f"{name}-profile.png").read_bytes()[:4] == b"\x89PNG"


def test_undercut_spec_one_line(tmp_path):
    spec = (ROOT / "samples" / "disc-translating-roller.toml").read_text()
    spec = spec.replace("base_radius = 40.0", "base_radius = 3.0").replace("bore = 12.0", "bore = 2.0")
    spec = spec.replace("roller_radius = 10.0", "roller_radius = 30.0").replace("offset = 5.0", "offset = 0.0")
    spec = spec.replace("to = 120, rise = 20.0", "to = 40, rise = 40.0").replace('{ law = "dwell", from = 120', '{ law = "dwell", from = 40')
    spec = spec.replace("from = 180, to = 300, rise = -20.0", "from = 180, to = 220, rise = -40.0").replace("from = 300", "from = 220")
    bad = tmp_path / "bad.toml"
    bad.write_text(spec)
    r = camcam("run", str(bad), "-o", str(tmp_path / "out"))
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1
    assert r.stderr.startswith("camcam: error: undercut at cam angle ")
    assert "cam.base_radius >= " in r.stderr
    assert not (tmp_path / "out").exists()
