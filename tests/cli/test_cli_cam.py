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
