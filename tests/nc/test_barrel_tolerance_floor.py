"""A barrel's tolerance too fine for its flank fits is refused naming machining.tolerance with a value that works
(issue 43, campaign cause 6: the spec check passed 0.0023 mm on a 3-decimal post, then the run said "flank 0: tolerance
0.00115 mm is too fine …; use at least 0.0018 mm", a value the user already had, under no key)."""

from __future__ import annotations

import re

from tests.hostile.harness import SAMPLES, assert_clean_error, run_inproc


def _spec(tmp_path, tolerance: float):
    text = (SAMPLES / "cylindrical-translating-small-tool.toml").read_text()
    text = text.replace('post = "linuxcnc"', 'post = "grbl"')  # 3 decimals: floor 0.0018 mm
    text = re.sub(r"(?m)^tolerance = .*$", f"tolerance = {tolerance}", text)
    p = tmp_path / f"s{tolerance}.toml"
    p.write_text(text)
    return p


def test_the_least_tolerance_named_is_the_least_that_runs(tmp_path):
    code, _, err = run_inproc(["run", _spec(tmp_path, 0.0023), "-o", tmp_path / "a"])
    line = assert_clean_error(code, err)
    assert line.startswith("camcam: error: machining.tolerance: 0.0023 mm leaves the groove passes' fits")
    need = float(re.search(r"expected at least ([0-9.]+) mm", line).group(1))
    assert need == 0.0036  # the flank fit is half the tolerance (a thinner tool): 2 x 0.0018 mm
    code, _, err = run_inproc(["run", _spec(tmp_path, need), "-o", tmp_path / "b"])
    assert code == 0 and "machining.tolerance" not in err, err  # followed: it runs (the sample accepts its FAIL)
    code, _, err = run_inproc(["run", _spec(tmp_path, round(need - 0.0001, 4)), "-o", tmp_path / "c"])
    assert "machining.tolerance" in assert_clean_error(code, err)  # 0.0001 mm less is still too fine


def test_the_smallest_groove_tool_advised_is_taken():
    """Campaign case 43:20: "expected at least 10.2 mm (up to the roller's 30.6 mm)", followed, was refused by the
    same check (3 × 5.1 = 15.299999999999999 < 15.3 in floats)."""
    import pytest

    from camcam.errors import GeometryError
    from camcam.nc.tools import groove_passes

    with pytest.raises(GeometryError, match=r"expected at least 10\.2 mm") as e:
        groove_passes(3.0, 15.3)
    least = float(re.search(r"expected at least ([0-9.]+) mm", str(e.value)).group(1))
    assert groove_passes(least / 2, 15.3) == "centre+flanks"
