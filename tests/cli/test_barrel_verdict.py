"""A barrel cam cut out of tolerance: every file written, FAIL at the top of the report, one stderr line, exit 3."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from tests.cli.test_exit_status import cli

ROOT = Path(__file__).resolve().parents[2]
SMALL = ROOT / "samples" / "cylindrical-translating-small-tool.toml"


def test_small_tool_fails_with_advice_and_exit_3(tmp_path):
    import ezdxf

    spec = tmp_path / "small.toml"
    spec.write_text(SMALL.read_text().replace("accept_out_of_tolerance = true", "accept_out_of_tolerance = false"))
    out = tmp_path / "out"
    code, stdout, stderr = cli("run", str(spec), "-o", str(out))
    assert code == 3
    lines = stderr.strip().splitlines()
    fail = [line for line in lines if line.startswith("camcam: FAIL: ")]
    assert len(fail) == 1 and len(lines) == 1, stderr  # one line: the cause and the way out (notes are on stdout)
    assert "3-D groove deviation" in fail[0] and "[machining] tool_diameter = 15.46" in fail[0]
    # the tool is the way out: a tolerance it named (0.0817 mm) measured 0.1102 mm when accepted
    assert "accept a tolerance" not in fail[0]
    name = "cylindrical-translating-small-tool"
    report = json.loads((out / f"{name}-report.json").read_text())
    assert report["verdict"]["status"] == "FAIL" and not report["verdict"]["accepted"]
    walls = report["machining"]["flank_deviation"]
    assert [w["wall"] for w in walls] == [0, 1]
    g = report["machining"]["groove_3d"]
    # the figure held to the tolerance is the walls' largest plus the motion-sampling bound h² / (8 · 6) mm, h the
    # step whose bound is the 2 % the plans leave the measurement (0.1386 mm at 0.02 mm), exactly as summed in float
    assert g["measured_mm"] == max(max(w["overcut_mm"], w["material_left_mm"]) for w in walls)
    assert report["max_deviation_mm"] == g["measured_mm"] + g["sampling_bound_mm"]
    assert g["sampling_bound_mm"] == pytest.approx(g["pose_step_mm"] ** 2 / (8 * 6.0), rel=1e-12)  # float rounding
    assert g["sampling_bound_mm"] == pytest.approx(0.02 * 0.02, rel=1e-12)  # only
    assert report["max_deviation_mm"] > report["tolerance_mm"]
    for w in walls:
        assert 40.0 <= w["overcut_radius_mm"] <= 50.0 and 0.0 <= w["overcut_cam_angle_deg"] < 360.0
    html = (out / f"{name}-report.html").read_text()
    assert html.index("FAIL") < html.index("Motion (design)")  # the verdict opens the page
    assert (out / f"{name}.ngc").exists() and (out / f"{name}.stl").exists()
    # the DXF title block carries the 3-D figure, not a figure the 3-D check does not confirm
    doc = ezdxf.readfile(out / f"{name}.dxf")
    title = " ".join(e.dxf.text for e in doc.modelspace().query("TEXT[layer=='TITLE-BLOCK']"))
    assert f"3-D groove deviation {report['max_deviation_mm']:.4f} mm (OUT OF TOLERANCE)" in title
    assert "3-D groove deviation" in stdout
