"""Classes 5 and 6: size caps (refused with the limit in the message) and CSV parsing."""

from __future__ import annotations

import pytest

import camcam.inputs as inputs
from camcam.errors import InputError
from camcam.lifttable.table import parse_lift_table
from camcam.reverse.points import parse_points
from tests.hostile.harness import SAMPLES, assert_clean_error, run_inproc, snapshot

TABLE = "".join(f"{a},{a / 100:.2f}\n" for a in range(0, 361, 45))  # 9 rows, no header, closes? no: a rise


@pytest.mark.parametrize("args,limit", [
    (["motion", SAMPLES / "demo.toml", "--step", "1e-6"], "0.01"),
    (["fit", SAMPLES / "lift" / "noisy-lift.csv", "--step", "1e-6"], "0.01"),
    (["reverse", SAMPLES / "reverse" / "disc-points.csv", "--spec", SAMPLES / "reverse" / "disc.toml", "--points", "10000000"],
     "36000"),
    (["run", "/dev/zero"], "1 MiB"),
    (["fit", "/dev/zero"], "64 MiB"),
])
def test_sizes_over_a_cap_are_refused_with_the_limit(tmp_path, args, limit):
    code, _, err = run_inproc(args + ["-o", tmp_path / "out"])
    assert limit in assert_clean_error(code, err)
    assert not (tmp_path / "out").exists()


def test_rows_over_the_cap_are_refused(monkeypatch):
    monkeypatch.setattr(inputs, "MAX_ROWS", 5)  # the cap itself (200 000) is exercised by benchmarks/hostile_sizes.py
    text = "".join(f"{a} {a}\n" for a in range(6))
    with pytest.raises(InputError, match="more than 5 data rows"):
        parse_lift_table(text, "t.csv")


def test_a_bom_is_not_a_header(tmp_path):
    rows = "0,0\n90,1\n180,2\n270,1\n360,0\n"
    (tmp_path / "t.csv").write_bytes(b"\xef\xbb\xbf" + rows.encode())
    t = inputs.read_text(tmp_path / "t.csv")
    assert len(parse_lift_table(t, "t.csv")) == 5  # the first data row is kept, not taken as a header
    (tmp_path / "h.csv").write_bytes(b"\xef\xbb\xbfangle_deg,lift_mm\n" + rows.encode())
    assert len(parse_lift_table(inputs.read_text(tmp_path / "h.csv"), "h.csv")) == 5


@pytest.mark.parametrize("value", ["1_00", "١٠", "１０", "inf", "nan", "-Infinity", "0x10", "1e5_0", "1.5e", "+-1", "1..2"])
def test_only_plain_decimal_numbers(value):
    with pytest.raises(InputError, match="row 3: lift"):
        parse_lift_table(f"angle,lift\n0 0\n10 {value}\n20 2\n30 3\n40 4\n", "t.csv")
    with pytest.raises(InputError, match="row 2: y"):
        parse_points(f"x y\n1 {value}\n" + "1 2\n" * 30, "p.csv")


@pytest.mark.parametrize("value,expected", [("1e2", 100.0), ("-.5", -0.5), ("+2.", 2.0), ("3.25E-1", 0.325)])
def test_plain_decimal_numbers_are_read(value, expected):
    t = parse_lift_table(f"0 0\n10 {value}\n20 2\n30 3\n40 4\n", "t.csv")
    assert t.lift[1] == expected  # exact: float() of the same decimal text


def test_fit_writes_nothing_for_a_bad_table(tmp_path):
    (tmp_path / "t.csv").write_text("0,0\n1,1_00\n2,2\n3,3\n4,4\n")
    before = snapshot(tmp_path)
    code, _, err = run_inproc(["fit", tmp_path / "t.csv", "-o", tmp_path / "out"])
    assert "plain decimal" in assert_clean_error(code, err)
    assert snapshot(tmp_path) == before
