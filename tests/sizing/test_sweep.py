"""`camcam size` end to end: the best design against a brute-force loop over the full geometry,
and the sample's best design run by `camcam run` and re-checked by the full geometry."""

from __future__ import annotations

import itertools
import json
import math
import tomllib
from dataclasses import replace

import numpy as np
import pytest

from camcam.errors import GeometryError
from camcam.geometry.analysis import analyse, check_undercut
from camcam.geometry.build import build_cam
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import TranslatingRoller
from camcam.motion.catalog import make_law
from camcam.spec import load_spec
from tests.sizing.helpers import SAMPLE, cli


SMALL = """
name = "small"
[motion]
rpm = 60
segments = [
  { law = "modified-sine", from = 0, to = 120, rise = 20.0 },
  { law = "dwell", from = 120, to = 180 },
  { law = "cycloidal", from = 180, to = 300, rise = -20.0 },
  { law = "dwell", from = 300, to = 360 },
]
[cam]
kind = "disc"
base_radius = 30.0
thickness = 10.0
rotation = "ccw"
[follower]
kind = "translating-roller"
roller_radius = 10.0
[size]
base_radius = [11, 17, 3]
offset = [-4, 4, 4]
roller_radius = [10]
law = [{ segment = 0, choices = ["cycloidal", "modified-sine"] }]
max_pressure_angle_deg = 30
min_curvature_radius_mm = 12.0
samples = 1440
"""



def profile_outer_radius(cam: DiscCam) -> float:
    """Largest |profile| on 36,000 samples: within R·h²/8 ≈ 2e-7 mm of the true maximum."""
    p = cam.profile.evaluate(np.linspace(0.0, 2 * math.pi, 36001))
    return float(np.hypot(p[:, 0], p[:, 1]).max())


def test_brute_force_over_the_full_geometry_finds_the_same_best_design(tmp_path):
    spec_path = tmp_path / "small.toml"
    spec_path.write_text(SMALL)
    code, out, err = cli("size", str(spec_path), "-o", str(tmp_path / "out"), "--in-process", "--table", "csv", "--json")
    assert code == 0, err
    best = json.loads(out)["best"]
    spec = load_spec(spec_path)
    rows = []
    for rb, e, law in itertools.product((11.0, 14.0, 17.0), (-4.0, 0.0, 4.0), ("cycloidal", "modified-sine")):
        segs = list(spec.motion.segments)
        segs[0] = replace(segs[0], law_name=law, law=make_law(law))
        program = replace(spec.motion, segments=tuple(segs)).program("mm")
        cam = DiscCam(TranslatingRoller(10.0, e), program, rb, "ccw")
        try:
            check_undercut(cam)
        except GeometryError:
            rows.append((rb, e, law, False, math.inf, math.inf))
            continue
        an = analyse(cam)
        ok = an.max_pressure_angle_deg.value <= 30.0 and an.profile.min_radius_mm >= 12.0
        rows.append((rb, e, law, ok, profile_outer_radius(cam), an.max_pressure_angle_deg.value))
    feasible = [r for r in rows if r[3]]
    assert 0 < len(feasible) < len(rows)  # the constraints bite: the choice is not trivial
    # smallest outer radius, ties by pressure angle; 1e-6 mm merges the ±e mirror pairs' float noise
    brute = min(feasible, key=lambda r: (round(r[4], 6), round(r[5], 6)))
    assert (best["base_radius_mm"], best["offset_mm"], best["laws"]["segment 0"]) == (brute[0], brute[1], brute[2])
    assert best["exact"]["outer_radius_mm"] == pytest.approx(brute[4], abs=1e-6)  # dense samples: within 2e-7 mm
    assert best["exact"]["max_pressure_angle_deg"] == pytest.approx(brute[5], abs=1e-9)  # same analysis
    # the grid table agrees with the full geometry on feasibility for every design
    table = (tmp_path / "out" / "small-designs.csv").read_text().splitlines()
    head = table[0].split(",")
    grid_feasible = sum(line.split(",")[head.index("feasible")] == "true" for line in table[1:])
    assert grid_feasible == len(feasible)


def test_sample_best_design_runs_and_meets_every_constraint(tmp_path):
    code, out, err = cli("size", str(SAMPLE), "-o", str(tmp_path / "size"), "--in-process", "--json")
    assert code == 0, err
    summary = json.loads(out)
    best_spec = tmp_path / "size" / "size-translating-roller-best.toml"
    assert summary["best"]["spec"] == best_spec.name
    # the full geometry: build (undercut raises), analyse, hold to the sample's constraints
    spec = load_spec(best_spec)
    assert spec.size is None and tomllib.loads(best_spec.read_text())["name"] == "size-translating-roller-best"
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    an = built.analysis
    assert an.max_pressure_angle_deg.value <= 30.0
    assert an.profile.min_radius_mm >= 15.0
    concave = an.profile.min_concave_radius
    assert concave is None or concave.value >= spec.machining.tool_diameter_mm / 2
    assert summary["best"]["exact"]["max_pressure_angle_deg"] == pytest.approx(an.max_pressure_angle_deg.value, abs=1e-9)
    # `camcam run` takes the written spec as is
    code, out, err = cli("run", str(best_spec), "-o", str(tmp_path / "run"), "--json")
    assert code == 0, err
    report = json.loads(out)["cam"]
    assert report["max_deviation_mm"] <= report["tolerance_mm"]
    assert report["max_pressure_angle_deg"] == pytest.approx(an.max_pressure_angle_deg.value, abs=1e-9)
    # and it is a corner of the sweep where a constraint binds: one step smaller base radius fails
    assert summary["feasible"] < summary["designs"]


def test_csv_and_parquet_tables_hold_the_same_numbers(tmp_path):
    pa = pytest.importorskip("pyarrow.parquet")
    spec_path = tmp_path / "small.toml"
    spec_path.write_text(SMALL.replace("samples = 1440", "samples = 720"))
    for fmt in ("csv", "parquet"):
        code, _, err = cli("size", str(spec_path), "-o", str(tmp_path / fmt), "--in-process", "--table", fmt)
        assert code == 0, err
    table = pa.read_table(tmp_path / "parquet" / "small-designs.parquet").to_pydict()
    lines = (tmp_path / "csv" / "small-designs.csv").read_text().splitlines()
    head = lines[0].split(",")
    assert head == list(table)
    for i, line in enumerate(lines[1:]):
        cells = line.split(",")
        for name, cell in zip(head, cells):
            v = table[name][i]
            if isinstance(v, bool):
                assert cell == ("true" if v else "false")
            elif isinstance(v, float):
                assert float(cell) == v or (math.isnan(v) and cell == "nan")  # repr round-trips exactly
            else:
                assert cell == str(v)


OSCILLATING = """
name = "osc"
[motion]
rpm = 60
segments = [
  { law = "cycloidal", from = 0, to = 150, rise = 20.0 },
  { law = "dwell", from = 150, to = 200 },
  { law = "cycloidal", from = 200, to = 330, rise = -20.0 },
  { law = "dwell", from = 330, to = 360 },
]
[cam]
kind = "disc"
base_radius = 40.0
thickness = 10.0
rotation = "cw"
[follower]
kind = "{kind}"
{follower}
[size]
{size}
samples = 720
"""


@pytest.mark.parametrize("kind,follower,size,check", [
    ("oscillating-roller", "roller_radius = 8.0\npivot_distance = 110.0\narm_length = 90.0",
     "base_radius = [20, 50, 10]\npivot_distance = [100, 120, 10]\nmax_pressure_angle_deg = 35\nmin_curvature_radius_rollers = 1.0",
     lambda an, rr: an.max_pressure_angle_deg.value <= 35.0 and an.profile.min_radius_mm >= rr),
    ("translating-flat", "offset = 0.0",
     "base_radius = [5, 40, 5]\nmin_curvature_radius_mm = 10.0",
     lambda an, rr: an.profile.min_radius_mm >= 10.0),
])
def test_other_followers_best_design_meets_every_constraint_by_the_full_geometry(kind, follower, size, check, tmp_path):
    spec_path = tmp_path / "osc.toml"
    spec_path.write_text(OSCILLATING.replace("{kind}", kind).replace("{follower}", follower).replace("{size}", size))
    code, out, err = cli("size", str(spec_path), "-o", str(tmp_path / "out"), "--in-process", "--table", "csv", "--json")
    assert code == 0, err
    summary = json.loads(out)
    assert 0 < summary["feasible"] < summary["designs"]  # the constraints bite
    spec = load_spec(tmp_path / "out" / "osc-best.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))  # undercut/cusp would raise
    assert check(built.analysis, spec.follower.roller_radius)
    # the smallest feasible base radius on the grid: one step smaller fails by the full geometry
    rb = summary["best"]["base_radius_mm"]
    step = 10.0 if kind == "oscillating-roller" else 5.0
    if rb - step >= (20.0 if kind == "oscillating-roller" else 5.0):
        smaller = replace(spec.cam, base_radius=rb - step)
        try:
            worse = build_cam(smaller, spec.follower, spec.motion.program(spec.unit))
        except GeometryError:
            return
        assert not check(worse.analysis, spec.follower.roller_radius)
