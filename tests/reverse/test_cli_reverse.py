"""``camcam reverse``: outputs, errors against the design, motion.csv as a lift table, bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest

from camcam.cli import main
from camcam.lifttable.table import load_lift_table
from camcam.spec import load_spec

from .conftest import ROOT

SAMPLES = ROOT / "samples" / "reverse"


def test_seed002_sample(tmp_path, capsys):
    rc = main(["reverse", str(SAMPLES / "seed002-points.csv"), "--spec", str(SAMPLES / "seed002.toml"), "-o", str(tmp_path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert rc == 0 and out["points"] == 180 and out["output_points"] == 360
    # seed 002's reported largest errors (deg, deg/deg, deg/deg²): ours must be below them
    assert out["max_lift_error"] < 0.0023 and out["max_velocity_error"] < 0.001 and out["max_acceleration_error"] < 0.018
    assert sorted(p.split("/")[-1] for p in out["files"]) == ["motion.csv", "reverse.png", "summary.json"]
    table = load_lift_table(tmp_path / "motion.csv")
    assert len(table) == 361 and table.full_revolution
    # the recovered table as a spec's lift_table: the program reproduces it at its own rows
    spec_path = tmp_path / "again.toml"
    spec_path.write_text('[motion]\nrpm = 60\nlift_table = "motion.csv"\n')
    prog = load_spec(spec_path).motion.program("deg")
    assert np.abs(prog.lift(np.radians(table.x)) - table.y).max() < 1e-9  # interpolates its rows (float rounding)


def test_noisy_and_disc_samples(tmp_path, capsys):
    assert main(["reverse", str(SAMPLES / "seed002-noisy-points.csv"), "--spec", str(SAMPLES / "seed002.toml"), "-o", str(tmp_path / "n"), "--json"]) == 0
    noisy = json.loads(capsys.readouterr().out)
    # ±2 µm: measured 8.1e-4 deg, 6.6e-4 deg/deg, 8.7e-4 deg/deg²; bounds ~1.5x, still under the seed's figures
    assert noisy["max_lift_error"] < 1.2e-3 and noisy["max_velocity_error"] < 1e-3 and noisy["max_acceleration_error"] < 1.5e-3
    assert main(["reverse", str(SAMPLES / "disc-points.csv"), "--spec", str(SAMPLES / "disc.toml"), "-o", str(tmp_path / "d"), "--json"]) == 0
    disc = json.loads(capsys.readouterr().out)
    # 240 shuffled points, ±2 µm: measured 2.1e-3 mm, 1.1e-3 mm/deg, 9.5e-4 mm/deg²; bounds ~1.5x
    assert disc["max_lift_error"] < 3.2e-3 and disc["max_velocity_error"] < 1.7e-3 and disc["max_acceleration_error"] < 1.5e-3


@pytest.mark.parametrize("text,message", [
    ("x, y, z\n" + "1, 2, 3\n" * 5 + "1, 2\n", "p.csv row 7: expected 3 values (x, y, z), got '1, 2'"),
    ("x, y\n1, 2\n3, nan\n", "p.csv row 3: y 'nan' is not a plain decimal number (digits, point, exponent)"),
    ("x, y\n1, 2\n", "p.csv: 1 point(s); reverse design needs at least 20"),
])
def test_bad_points(tmp_path, capsys, text, message):
    (tmp_path / "p.csv").write_text(text)
    rc = main(["reverse", str(tmp_path / "p.csv"), "--spec", str(SAMPLES / "seed002.toml"), "-o", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and err == f"camcam: error: {message}" and not (tmp_path / "o").exists()


def test_spec_without_cam(tmp_path, capsys):
    (tmp_path / "s.toml").write_text('[motion]\nrpm = 60\nsegments = [{ law = "cycloidal", from = 0, to = 180, rise = 5 }, { law = "cycloidal", from = 180, to = 360, rise = -5 }]\n')
    rc = main(["reverse", str(SAMPLES / "disc-points.csv"), "--spec", str(tmp_path / "s.toml"), "-o", str(tmp_path / "o")])
    assert rc == 2 and "cam: missing; `camcam reverse` needs a [cam] table" in capsys.readouterr().err


def test_two_column_points_for_a_cylinder(tmp_path, capsys):
    rc = main(["reverse", str(SAMPLES / "disc-points.csv"), "--spec", str(SAMPLES / "seed002.toml"), "-o", str(tmp_path / "o")])
    assert rc == 2 and "a cylindrical cam needs x, y, z points" in capsys.readouterr().err
