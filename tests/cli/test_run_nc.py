"""``camcam run`` with [machining]: program, DXF and report figures, same bytes on a second run."""

import json
from pathlib import Path

from camcam.cli import main

ROOT = Path(__file__).resolve().parents[2]


def test_run_writes_program_dxf_and_report(tmp_path):
    spec = ROOT / "samples" / "disc-groove.toml"
    assert main(["run", str(spec), "-o", str(tmp_path / "a")]) == 0
    assert main(["run", str(spec), "-o", str(tmp_path / "b")]) == 0
    for name in ("disc-groove.ngc", "disc-groove.dxf"):
        assert (tmp_path / "a" / name).read_bytes() == (tmp_path / "b" / name).read_bytes()
    report = json.loads((tmp_path / "a" / "disc-groove-report.json").read_text())
    assert report["tolerance_mm"] == 0.01
    assert 0 < report["max_deviation_mm"] <= 0.01
    assert report["arc_blocks"] > 0 and report["lower_bound_blocks"] > 0
    segs = report["machining"]["contours"][0]["segments"]
    assert sum(s["blocks"] for s in segs) == report["arc_blocks"] + report["line_blocks"]
    assert (tmp_path / "a" / "disc-groove.ngc").read_text().rstrip().endswith("M2")


def test_run_tool_too_wide_is_one_line(tmp_path, capsys):
    text = (ROOT / "samples" / "disc-groove.toml").read_text().replace("tool_diameter = 20.0", "tool_diameter = 24.0")
    spec = tmp_path / "wide.toml"
    spec.write_text(text)
    assert main(["run", str(spec), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert "wider than the groove" in err and len(err.splitlines()) == 1
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())
