"""Figures that can be absent print honestly (issue 50 item 4).

A dwell-only barrel cam has straight developed flanks: no smallest finite radius of curvature and
no cam angle where it occurs.  The report crashed formatting None (`report/job_page.py`, TypeError,
exit 1); now the radius is infinite everywhere it is shown: console, report HTML, report JSON
(``"inf"``, as an infinite jerk is), `camcam batch`'s rows.
"""

from __future__ import annotations

import csv
import json
import math
import re

from camcam.geometry.analysis import radius_text
from tests.hostile.harness import SAMPLES, run_inproc

BARREL = SAMPLES / "cylindrical-translating.toml"


def _barrel(tmp_path, name: str, segments: str):
    """samples/cylindrical-translating.toml with its motion replaced."""
    text = BARREL.read_text().replace('name = "cylindrical-translating"', f'name = "{name}"')
    text = re.sub(r"segments = \[.*?\n\]", f"segments = {segments}", text, flags=re.S)
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return path


DWELL = '[{law="dwell", from=0, to=360}]'


def test_dwell_only_barrel_reports_an_infinite_radius(tmp_path):
    spec = _barrel(tmp_path, "dwell-barrel", segments=DWELL)
    code, out, err = run_inproc(["run", spec, "-o", tmp_path / "out"])
    # 0 or 3: the 3-D groove verdict is issue 50 item 8's; the report itself must not fault (it was 1)
    assert code in (0, 3), err
    assert "internal error" not in err and "Traceback" not in err
    assert "min radius of curvature infinite (straight: no curvature)" in out
    report = json.loads((tmp_path / "out" / "dwell-barrel-report.json").read_text())
    assert report["min_curvature_radius_mm"] == "inf"
    assert report["min_curvature_radius_at_deg"] is None
    assert report["profile_curvature"]["min_radius_mm"] == "inf"
    assert report["profile_curvature"]["min_radius_at_deg"] is None
    html = (tmp_path / "out" / "dwell-barrel-report.html").read_text()
    assert "smallest convex radius of curvature</td><td>infinite (straight: no curvature)</td>" in html


def test_dwell_only_barrel_batch_row(tmp_path):
    spec = _barrel(tmp_path, "dwell-barrel", segments=DWELL)
    code, out, err = run_inproc(["batch", spec, "-o", tmp_path / "b", "--in-process"])
    assert code in (0, 3), err  # 3 when the row's verdict is FAIL (item 8's measurement), never an ERROR row
    rows = list(csv.DictReader((tmp_path / "b" / "summary.csv").open()))
    assert [r["verdict"] for r in rows] != ["ERROR"], rows
    assert rows[0]["min_curvature_radius_mm"] == "inf"  # was an empty cell ("not applicable")
    summary = json.loads((tmp_path / "b" / "summary.json").read_text())
    assert summary["specs"][0]["min_curvature_radius_mm"] == "inf"


def test_radius_text():
    assert radius_text(math.inf, 12.0) == "infinite (straight: no curvature)"
    assert radius_text(None, None) == "infinite (straight: no curvature)"
    assert radius_text(60545.38204, 37.49, 4) == "60545.3820 mm at 37.49°"
