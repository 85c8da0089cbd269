"""Reading lift tables: formats accepted, and one line naming the row for each bad table."""

import pytest

from camcam.errors import InputError
from camcam.lifttable.table import load_lift_table, parse_lift_table

ROWS = "0 0\n90 1\n180 2\n270 1\n360 0\n"


def test_header_commas_whitespace_comments():
    t = parse_lift_table("# measured\nangle_deg , lift_mm\n0,0\n 90 ,1.25\n180\t2\n\n270   1\n360,0\n", "a.csv")
    assert t.angles_deg == (0.0, 90.0, 180.0, 270.0, 360.0)
    assert t.lift == (0.0, 1.25, 2.0, 1.0, 0.0)
    assert t.rows == (3, 4, 5, 7, 8)
    assert t.full_revolution
    assert t.resolution == 0.01  # lifts written with at most 2 decimals


def test_rise_only_table():
    t = parse_lift_table("10 0\n20 1\n30 3\n40 4\n50 4.5\n", "r.csv")
    assert not t.full_revolution and t.span_deg == 40.0


@pytest.mark.parametrize(
    "text, message",
    [
        ("0 0\n1 1\n2 2\n2 3\n4 4\n", "lift.csv row 4: angle 2 is not above the previous angle 2"),
        ("0 0\n1 1\n5 2\n3 3\n6 4\n", "lift.csv row 4: angle 3 is not above the previous angle 5"),
        ("0 0\n1 x\n2 2\n3 3\n4 4\n", "lift.csv row 2: lift 'x' is not a number"),
        ("0 0\n1 1\n2 nan\n3 3\n4 4\n", "lift.csv row 3: lift 'nan' is not a plain decimal number (digits, point, exponent)"),
        ("0 0\n1 1\n2 2\n3 inf\n4 4\n", "lift.csv row 4: lift 'inf' is not a plain decimal number (digits, point, exponent)"),
        ("0 0\n1 1 1\n2 2\n3 3\n4 4\n", "lift.csv row 2: expected 2 values (angle_deg, lift_mm), got '1 1 1'"),
        ("0 0\n1,\n2 2\n3 3\n4 4\n", "lift.csv row 2: expected 2 values (angle_deg, lift_mm), got '1,'"),
        ("0 0\n90 1\n180 2\n270 1\n360 0.01\n", "lift.csv row 5: lift 0.01 at 360° differs from lift 0 at 0° by +0.01; a full revolution must close"),
        ("0 0\n90 1\n180 2\n270 1\n361 0\n", "lift.csv row 5: angle 361 is more than 360° after the first angle 0"),
        ("angle\n0 0\n", "lift.csv row 1: a header needs 2 column names (angle_deg, lift_mm), got 1"),
        ("0 0\n1 1\n2 2\n", "lift.csv: 3 data row(s); a lift table needs at least 5"),
        ("a, b\n0 0\nx 1\n", "lift.csv row 3: angle 'x' is not a number"),
    ],
)
def test_bad_tables(text, message):
    with pytest.raises(InputError) as err:
        parse_lift_table(text, "lift.csv")
    assert str(err.value) == message


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="no such file"):
        load_lift_table(tmp_path / "nope.csv")


def test_full_revolution_closes_exactly():
    t = parse_lift_table(ROWS.replace("360 0", "360 0.0000001"), "a.csv")  # within CLOSE_ATOL
    assert t.with_lift(t.y).lift[-1] == t.lift[0]
