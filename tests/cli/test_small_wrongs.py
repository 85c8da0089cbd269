"""Issue 43, small wrongs: no -0 or e-15 noise in printed figures, a bore message that says what is possible, and a
small-tool advice that names each diameter once with one meaning."""

from __future__ import annotations

import json
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from camcam.export.figures import clean, fixed
from camcam.verify.groove_checks import groove_check
from camcam.report.inspection import InspectionTable
from tests.cli.test_exit_status import cli

ROOT = Path(__file__).resolve().parents[2]


def test_motion_extremes_print_zero_not_rounding_noise(tmp_path):
    # the Table 1 optimum's lift at 0° computes as -1.0842e-18 mm (it is 0: S(0) = 0)
    spec = ROOT / "samples" / "optimize" / "run-table1.toml"
    code, out, err = cli("motion", str(spec), "-o", str(tmp_path / "a"))
    assert code == 0
    lift = next(ln for ln in out.splitlines() if ln.startswith("lift"))
    assert re.match(r"lift +min +\+0 mm ", lift), lift
    assert not re.search(r"e-\d\d", out)
    code, out, err = cli("motion", str(spec), "-o", str(tmp_path / "b"), "--json")
    assert json.loads(out)["extremes"]["lift"]["min"] == 0.0


def test_figure_helpers():
    assert clean(-3.552713678800501e-15, scale=20.0) == 0.0 and str(clean(-0.0)) == "0.0"
    assert clean(-1e-4, scale=20.0) == -1e-4  # a real figure stays
    assert clean(float("inf")) == float("inf")
    assert [fixed(v, 4) for v in (-0.00001, -0.0, -0.00006, 0.00004)] == ["0.0000", "0.0000", "-0.0001", "0.0000"]


def test_inspection_table_has_no_negative_zero():
    table = InspectionTable(angle_deg=np.array([0.0, 10.0]), profile_xy=np.array([[-1e-9, 40.0], [-0.0004, -6.9456]]),
                            radius_mm=np.array([40.0, 7.0]),
                       normal_deg=np.array([-0.001, 90.0]), roller_centre_xy=None, lift=np.array([-2e-12, 1.25]),
                            lift_unit="mm", tolerance_mm=0.01)
    rows = table.rows()
    assert rows[0][1:5] == ("0.000", "40.000", "40.000", "0.00") and rows[0][7] == "0.0000 mm"
    assert rows[1][1] == "0.000" and rows[1][2] == "-6.946"  # a figure that is not zero keeps its sign
    csv = table.csv()
    assert not re.search(r"(^|,)-0\.0+(,|$)", csv, re.M) and csv.splitlines()[1].startswith("0.000000,0.000000,40.")


def test_bore_message_says_no_bore_fits_and_a_way_that_works(tmp_path):
    sample = (ROOT / "samples" / "disc-translating-roller.toml").read_text()  # roller 10 mm, bore 12 mm
    spec = tmp_path / "small.toml"
    spec.write_text(sample.replace("base_radius = 40.0", "base_radius = 8.0"))
    code, out, err = cli("run", str(spec), "-o", str(tmp_path / "a"))
    assert code == 2 and len(err.splitlines()) == 1
    assert err.startswith("camcam: error: cam.bore: Ø12 mm: no bore fits, the base circle minus the roller leaves "
                          "nothing (8 − 10 mm); expected cam.bore = 0 (no bore), or cam.base_radius >= 16 mm")
    assert "Ø-" not in err
    radius = re.search(r"cam\.base_radius >= ([0-9.]+) mm", err).group(1)
    spec.write_text(sample.replace("base_radius = 40.0", f"base_radius = {radius}"))  # the advice followed
    code, out, err = cli("run", str(spec), "-o", str(tmp_path / "b"))
    assert code == 0 and err == ""


def _groove(smallest_tool_mm):
    cam = SimpleNamespace(kind="translating-roller", roller_radius=8.0,
                          follower=SimpleNamespace(roller_axis_tilts=False))  # a translating roller's axis stays radial
    m = SimpleNamespace(tolerance_mm=0.02, tool_diameter_mm=12.0)
    groove = SimpleNamespace(max_deviation_mm=0.0816, where=lambda: "flank 0")
    return groove_check(cam, m, groove, smallest_tool_mm).advice


def test_small_tool_advice_names_each_diameter_once():
    advice = _groove(15.4512)
    # a spec's key and value first (what a user or a script applies), then what it means
    assert advice.startswith("[machining] tool_diameter = 15.46 (the thinnest tool whose flank error holds half of "
                             "0.02 mm; any up to the roller's diameter, 16 mm)")
    # where only the roller's own diameter holds it (the search ends at the roller), it is named once
    for smallest in (16.0, 15.999, None):
        advice = _groove(smallest)
        assert advice.startswith("[machining] tool_diameter = 16 (the roller's diameter: no thinner tool holds half "
                                 "of 0.02 mm)")
        assert advice.count("16") == 1 and "15." not in advice, advice


def test_the_bore_advice_followed_takes_the_bore(tmp_path):
    """Campaign case 43:57: "cam.base_radius >= 15.85 mm takes the Ø7.7 mm bore", followed, was refused again
    (15.85 − 12 = 3.8499999999999996 < 3.85 in floats)."""
    spec = tmp_path / "s.toml"
    text = (Path(__file__).with_name("data") / "bore-advice-43-57.toml").read_text()
    spec.write_text(text)
    code, _, err = cli("run", str(spec), "-o", str(tmp_path / "a"))
    assert code == 2 and "cam.base_radius >= 15.85 mm takes the Ø7.7 mm bore" in err, err
    spec.write_text(text.replace("base_radius = 15.1", "base_radius = 15.85"))  # the advice followed
    code, _, err = cli("run", str(spec), "-o", str(tmp_path / "b"))
    assert code == 0 and "cam.bore" not in err, err
