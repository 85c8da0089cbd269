"""The command line as a user runs it: subprocess, exit status, files."""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "demo.toml"


def camcam(*args, cwd=None):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "camcam", *args], capture_output=True, text=True, cwd=cwd, env=env)


def test_laws_json_textbook_values():
    r = camcam("laws", "--json")
    assert r.returncode == 0, r.stderr
    table = json.loads(r.stdout)
    # 4 significant digits, as the issue asks
    assert f"{table['modified-sine']['Vm']:.4g}" == "1.76"
    assert f"{table['modified-sine']['Am']:.4g}" == "5.528"
    assert f"{table['modified-sine']['Jmax']:.4g}" == "69.47"
    assert f"{table['modified-sine']['Jmin']:.4g}" == "-23.16"
    assert f"{table['modified-trapezoid']['Am']:.4g}" == "4.888"
    assert f"{table['modified-trapezoid']['Jmax']:.4g}" == "61.43"
    assert f"{table['polynomial-345']['Am']:.4g}" == "5.774"
    assert f"{table['yu-lee']['Vm']:.4g}" == "1.911"
    assert f"{table['yu-lee']['Jmax']:.4g}" == "81"
    assert table["parabolic"]["Jmax"] == "inf"  # strict JSON has no Infinity token


def test_motion_writes_table_and_plot(tmp_path):
    r = camcam("motion", str(SAMPLE), "-o", str(tmp_path / "out"), "--json")
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout)
    assert summary["extremes"]["lift"]["max"] == pytest.approx(20.0, abs=1e-9)  # the rise, exact
    csv = (tmp_path / "out" / "demo-motion.csv").read_text().splitlines()
    assert csv[0].startswith("cam_angle_deg,lift_mm,velocity_mm_per_s")
    assert len(csv) == 1 + 721  # 0…360 at 0.5°
    png = (tmp_path / "out" / "demo-svaj.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert not [p for p in (tmp_path / "out").iterdir() if p.name.startswith(".")]  # no temp files left


def test_same_spec_same_bytes(tmp_path):
    for d in ("a", "b"):
        assert camcam("run", str(SAMPLE), "-o", str(tmp_path / d)).returncode == 0
    for name in ("demo-motion.csv", "demo-svaj.png"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()


def test_bad_spec_one_line_exit_2(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SAMPLE.read_text().replace("to = 300, rise", "to = 370, rise"))
    r = camcam("motion", str(bad), "-o", str(tmp_path / "out"))
    assert r.returncode == 2
    assert r.stderr.strip() == "camcam: error: motion.segments[2].to: 370 is past 360"
    assert "Traceback" not in r.stderr
    assert not (tmp_path / "out").exists()


def test_bad_argument_one_line():
    r = camcam("motion")
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1
