"""`camcam inspect` (issue 46): the samples' verdicts, the report's files and keys, and every bad input as
one stderr line with exit 2 and nothing written."""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import pytest

from camcam.cli import main
from camcam.inspect.measured import MAX_POINTS

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"
DISC = str(SAMPLES / "disc-translating-roller.toml")
BARREL = str(SAMPLES / "cylindrical-translating.toml")
PARTS = SAMPLES / "inspect"
KEYS = {"verdict", "max_deviation_mm", "min_deviation_mm", "worst_angle_deg", "rotation_deg", "translation_mm",
        "outliers", "max_acceleration_error"}


def cli(*args) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    return code, out.getvalue(), err.getvalue()


def _gap(a: float, b: float) -> float:
    return abs((a - b + 180.0) % 360.0 - 180.0)


def test_cmm_sample_fails_at_its_bump(tmp_path):
    out = tmp_path / "o"
    code, stdout, err = cli("inspect", DISC, str(PARTS / "disc-cmm.csv"), "--align", "rigid", "-o", str(out))
    assert code == 3
    assert err.count("\n") == 1 and "cam angle 200." in err and "tolerance ±0.01 mm" in err
    rep = json.loads((out / "report.json").read_text())
    assert KEYS <= set(rep)
    assert rep["verdict"] == "FAIL"
    # the sample's bump: +0.03 mm at 200° under σ 0.002 mm noise (4σ, and 3° of a 4°-wide bump, as the stage tests)
    assert rep["max_deviation_mm"] == pytest.approx(0.03, abs=0.008)
    assert _gap(rep["worst_angle_deg"], 200.0) <= 3.0
    assert rep["rotation_deg"] == pytest.approx(-0.7, abs=0.01)  # the datum turned 0.7°; measured within 0.006°
    assert rep["translation_mm"] == pytest.approx([-0.05, 0.0], abs=0.005)  # the centre shifted (0.05, 0)
    assert len(rep["outliers"]) == 3
    assert rep["max_acceleration_error"] > 0  # the reverse fit ran (its figures are the stage tests')
    assert len(rep["worst_points"]) == 10
    assert {"report.html", "report.json", "deviation.png", "polar.png", "motion.png", "deviation.csv"} <= {
        p.name for p in out.iterdir()}
    assert "FAIL" in (out / "report.html").read_text()


def test_clean_part_passes(tmp_path):
    code, stdout, err = cli("inspect", DISC, str(PARTS / "disc-cmm-clean.csv"), "--align", "rigid", "--no-motion",
                            "-o", str(tmp_path / "o"), "--json")
    assert code == 0, err
    assert err == ""
    rep = json.loads(stdout)
    assert rep["verdict"] == "PASS" and rep["max_acceleration_error"] is None  # --no-motion: no reverse fit


def test_bore_gives_the_centre(tmp_path):
    """With the bore's points the centre is the bore's: the rotation alone is fitted."""
    code, stdout, err = cli("inspect", DISC, str(PARTS / "disc-cmm.csv"), "--bore", str(PARTS / "disc-bore.csv"),
                            "--no-motion", "-o", str(tmp_path / "o"), "--json")
    assert code == 3
    rep = json.loads(stdout)
    assert rep["bore"]["centre_mm"] == pytest.approx([0.05, 0.0], abs=0.002)  # 36 points of σ 0.002 mm: ~0.0005
    assert rep["rotation_deg"] == pytest.approx(-0.7, abs=0.01)
    assert _gap(rep["worst_angle_deg"], 200.0) <= 3.0


def test_dial_sample(tmp_path):
    code, stdout, err = cli("inspect", DISC, str(PARTS / "disc-dial.csv"), "--probe-radius", "5", "--align", "rigid",
                            "--no-motion", "-o", str(tmp_path / "o"), "--json")
    assert code == 3 and err.count("\n") == 1
    rep = json.loads(stdout)
    assert rep["kind"] == "dial"
    assert rep["min_deviation_mm"] == pytest.approx(-0.02, abs=0.008)  # the sample's overcut bump, 4σ
    assert _gap(rep["worst_angle_deg"], 60.0) <= 3.0
    assert rep["reading_zero_mm"] == pytest.approx(0.25, abs=0.005)  # readings from a zero 0.25 mm low
    assert len(rep["outliers"]) == 3


def test_barrel_sample(tmp_path):
    code, stdout, err = cli("inspect", BARREL, str(PARTS / "barrel-walls.csv"), "--align", "rigid", "--no-motion",
                            "-o", str(tmp_path / "o"), "--json")
    assert code == 3 and "wall 1" in err
    rep = json.loads(stdout)
    assert rep["max_deviation_mm"] == pytest.approx(0.03, abs=0.008)
    assert _gap(rep["worst_angle_deg"], 90.0) <= 3.0
    assert rep["translation_mm"] == pytest.approx([-0.05, 0.0, 0.0], abs=0.005)
    assert rep["tolerance_mm"] == 0.02  # the spec's machining tolerance


def test_inspection_tolerance_from_the_spec(tmp_path):
    spec = tmp_path / "wide.toml"
    spec.write_text(Path(DISC).read_text() + "\n[inspection]\ntolerance = 0.05\n")
    code, stdout, err = cli("inspect", str(spec), str(PARTS / "disc-cmm.csv"), "--align", "rigid", "--no-motion",
                            "-o", str(tmp_path / "o"), "--json")
    assert code == 0, err
    assert json.loads(stdout)["tolerance_mm"] == 0.05


def test_an_existing_folder_needs_force(tmp_path):
    args = ("inspect", DISC, str(PARTS / "disc-cmm-clean.csv"), "--align", "rigid", "--no-motion", "-o", str(tmp_path / "o"))
    assert cli(*args)[0] == 0
    code, _, err = cli(*args[:-2], "-o", str(tmp_path))  # tmp_path holds "o": not empty, not an earlier set
    assert code == 2 and err.count("\n") == 1
    code, _, err = cli(*args, "--force")
    assert code == 0, err


def test_program_deviation_on_the_same_axes(tmp_path):
    code, stdout, err = cli("inspect", DISC, str(PARTS / "disc-cmm-clean.csv"), "--align", "rigid", "--no-motion",
                            "--program", "-o", str(tmp_path / "o"), "--json")
    assert code == 0, err
    dev = json.loads(stdout)["program_deviation_mm"]
    assert -0.01 <= dev["min"] <= dev["max"] <= 0.01  # the program is within its own tolerance, as `run` says


def _rows(n: int, dims: int = 2) -> str:
    return "x, y\n" + "\n".join(f"{40 + 0.001 * i}, {0.001 * i}" for i in range(n)) + "\n"


@pytest.mark.parametrize("name, text, extra, message", [
    ("few.csv", _rows(5), (), "few.csv: 5 points; inspection needs at least 20"),
    ("nan.csv", "x, y\n" + "40, 0\n" * 3 + "40, nan\n", (), "nan.csv row 5: y 'nan' is not a plain decimal number"),
    ("big.csv", _rows(MAX_POINTS + 1), (), f"more than {MAX_POINTS} points"),
    ("other.csv", "x, y\n" + "\n".join(f"{45 * __import__('math').cos(i / 10):.5f}, {45 * __import__('math').sin(i / 10):.5f}"
                                       for i in range(63)) + "\n", ("--align", "rigid"), "not from this cam"),
    ("dial.csv", "angle_deg, reading_mm\n" + "\n".join(f"{i * 10}, 1" for i in range(36)) + "\n", (), "--probe-radius"),
])
def test_bad_input_is_one_line(tmp_path, name, text, extra, message):
    f = tmp_path / name
    f.write_text(text)
    out = tmp_path / "o"
    code, stdout, err = cli("inspect", DISC, str(f), "--no-motion", "-o", str(out), *extra)
    assert code == 2
    assert err.count("\n") == 1 and message in err
    assert not out.exists()  # nothing written


def test_rotation_over_the_limit_is_refused(tmp_path):
    out = tmp_path / "o"
    code, _, err = cli("inspect", DISC, str(PARTS / "disc-cmm.csv"), "--align", "rigid", "--max-rotation", "0.5",
                       "--no-motion", "-o", str(out))
    assert code == 2 and err.count("\n") == 1 and "--max-rotation: the fitted rotation is -0.70" in err
    assert not out.exists()


@pytest.mark.parametrize("which", ["measured", "spec", "bore"])
def test_a_folder_where_a_file_was_expected(tmp_path, which):
    args = {"spec": DISC, "measured": str(PARTS / "disc-cmm.csv"), "bore": str(PARTS / "disc-bore.csv")}
    args[which] = str(tmp_path)
    code, _, err = cli("inspect", args["spec"], args["measured"], "--bore", args["bore"], "--no-motion",
                       "-o", str(tmp_path / "o"))
    assert code == 2 and err.count("\n") == 1 and "folder" in err
