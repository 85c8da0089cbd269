"""[motion] lift_table in a spec, the rise-only segment law, and the `camcam fit` command."""

import json
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from camcam.errors import SpecError
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "lift"


def camcam(*args):
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    return subprocess.run([sys.executable, "-m", "camcam", *args], capture_output=True, text=True, env=env)


def write(tmp_path, text, name="s.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


def test_sample_spec_gives_a_closed_program():
    spec = load_spec(SAMPLE / "noisy-lift.toml")
    prog = spec.motion.program()
    assert prog.joins == ()  # periodic fit: V and A continuous through 360°/0°
    assert float(prog.lift(np.radians(150.0))) == pytest.approx(10.0, abs=0.003)  # dwell at 10 mm, within the 3 µm noise
    assert spec.motion.lift_table.fitted.bad.angles_deg == [47.0, 151.0, 233.0, 329.0]


@pytest.mark.parametrize(
    "motion, message",
    [
        ('lift_table = "t.csv"\nsegments = []', "motion.lift_table: give either segments or lift_table, not both"),
        ("", 'motion.segments: missing; expected an array of tables (or lift_table = "FILE.csv")'),
        ('lift_table = "none.csv"', "motion.lift_table: {d}/none.csv: no such file"),
        ('lift_table = "bad.csv"', "motion.lift_table: bad.csv row 3: angle 1 is not above the previous angle 1"),
        ('lift_table = "rise.csv"', "motion.lift_table: rise.csv covers 0–60°; [motion] lift_table must run 0–360° (a rise-only table is a segment law: law = \"lift-table\")"),
        ('lift_table = "t.csv"\nfit = "cubic"', 'motion.fit: expected one of "periodic", "clamped", "natural", "not-a-knot", "bspline", got "cubic"'),
        ('lift_table = "t.csv"\n[motion.fairing]\nmethod = "fancy"', 'motion.fairing.method: expected one of "mid-point", "smoothing", got "fancy"'),
        ('lift_table = "t.csv"\n[motion.fairing]\nxi = 0', "motion.fairing.xi: expected a number > 0 mm, got 0"),
        ('lift_table = "t.csv"\n[motion.fairing]\nksi = 1', "motion.fairing.ksi: unknown key; expected one of: bad_points, max_iterations, method, min_size, threshold, xi"),
    ],
)
def test_spec_errors(tmp_path, motion, message):
    ang = np.arange(0.0, 361.0, 10.0)
    (tmp_path / "t.csv").write_text("\n".join(f"{a:g} {2 - 2 * np.cos(np.radians(a)):.6f}" for a in ang) + "\n")
    (tmp_path / "bad.csv").write_text("0 0\n1 1\n1 2\n3 3\n4 4\n")
    (tmp_path / "rise.csv").write_text("\n".join(f"{a:g} {a / 10:g}" for a in range(0, 61, 10)) + "\n")
    p = write(tmp_path, f"[motion]\nrpm = 100\n{motion}\n")
    with pytest.raises(SpecError) as err:
        load_spec(p)
    assert str(err.value) == message.format(d=tmp_path)


def test_rise_only_table_as_a_segment_law(tmp_path):
    x = np.arange(0.0, 121.0, 2.0)
    T = x / 120
    (tmp_path / "rise.csv").write_text("\n".join(f"{a:g},{10 * (T_ - np.sin(2 * np.pi * T_) / (2 * np.pi)):.6f}" for a, T_ in zip(x, T)))
    p = write(tmp_path, """
        [motion]
        rpm = 60
        segments = [
          { law = "lift-table", table = "rise.csv", from = 0, to = 120 },
          { law = "dwell", from = 120, to = 180 },
          { law = "cycloidal", from = 180, to = 300, rise = -10.0 },
          { law = "dwell", from = 300, to = 360 },
        ]
    """)
    prog = load_spec(p).motion.program()
    assert float(prog.lift(np.radians(60.0))) == pytest.approx(5.0, abs=1e-5)  # cycloid midpoint, table printed to 1e-6
    assert prog.segments[0].scale == pytest.approx(10.0, abs=1e-6)  # rise defaults to the table's rise


def test_fit_command_on_the_sample(tmp_path):
    r = camcam("fit", str(SAMPLE / "noisy-lift.csv"), "-o", str(tmp_path), "--json", "--step", "1")
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    assert s["bad_points_deg"] == [47.0, 151.0, 233.0, 329.0]
    assert s["method"] == "smoothing" and s["iterations"] == 1
    assert s["roughness_after"] * 10 < s["roughness_before"]
    assert 0.03 < s["max_correction_mm"] < 0.06  # the largest spike (50 µm) is the largest correction
    rows = np.loadtxt(tmp_path / "faired.csv", delimiter=",", skiprows=1)
    assert rows.shape == (361, 5) and rows[0, 0] == 0 and rows[-1, 0] == 360
    assert (tmp_path / "faired.csv").read_text().startswith("angle_deg,lift_mm,velocity,acceleration,jerk\n")
    assert {p.name for p in tmp_path.iterdir()} == {"faired.csv", "curvature-comb.png", "roughness.png", "summary.json",
                                                 "camcam-manifest.json"}  # the manifest lists the other four


def test_fit_command_mid_point(tmp_path):
    r = camcam("fit", str(SAMPLE / "noisy-lift.csv"), "-o", str(tmp_path), "--json", "--method", "mid-point", "--xi", "1e-4")
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    assert s["converged"] and s["iterations"] == 12  # measured; deterministic for this table


def test_fit_command_bad_table_writes_nothing(tmp_path):
    bad = tmp_path / "lift.csv"
    bad.write_text("0 0\n1 1\n2 2\n3 3\n4 4\n5 5\n12 6\n12 7\n")
    out = tmp_path / "out"
    r = camcam("fit", str(bad), "-o", str(out))
    assert r.returncode == 2
    assert r.stderr.strip() == "camcam: error: lift.csv row 8: angle 12 is not above the previous angle 12"
    assert not out.exists()


def test_run_with_a_lift_table_spec(tmp_path):
    shutil.copy(SAMPLE / "noisy-lift.csv", tmp_path)
    shutil.copy(SAMPLE / "noisy-lift.toml", tmp_path)
    r = camcam("run", str(tmp_path / "noisy-lift.toml"), "-o", str(tmp_path / "out"), "--json")
    assert r.returncode == 0, r.stderr
    s = json.loads(r.stdout)
    vmax = s["motion"]["extremes"]["velocity"]["max"]
    assert vmax == pytest.approx(105.58, rel=0.01)  # modified-sine Vm 1.7596 × 10 mm / (2π/3 rad) × 4π rad/s
