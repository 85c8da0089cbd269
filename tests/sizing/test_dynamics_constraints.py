"""`camcam size` with the dynamics constraints (issue 45): ``max_contact_stress_mpa`` and ``min_jump_rpm``.

The sweep's per-design contact stress (closed forms on the samples) and jump speed (exact) are checked
against the dynamics stage of `camcam run` (:func:`camcam.dynamics.cycle.analyse_dynamics`, the second
method), the accepted best design is run by `camcam run` itself, and tightening a limit only removes designs.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from camcam.dask_batch.engine import InProcess
from camcam.sizing.exact_check import exact_figures
from camcam.sizing.sweep import run_sweep
from camcam.spec import load_spec
from tests.sizing.helpers import cli

MOTION = """
[motion]
rpm = 400
segments = [
  { law = "modified-sine", from = 0, to = 120, rise = 20.0 },
  { law = "dwell", from = 120, to = 180 },
  { law = "cycloidal", from = 180, to = 300, rise = -20.0 },
  { law = "dwell", from = 300, to = 360 },
]
[cam]
kind = "disc"
base_radius = 40.0
thickness = 12.0
bore = 12.0
rotation = "ccw"
"""

KINDS = {
    "translating-roller": ("""
[follower]
kind = "translating-roller"
roller_radius = 10.0
offset = 5.0
[dynamics]
mass_kg = 0.8
spring_rate_n_per_mm = 1.5
preload_n = 60.0
damping_ratio = 0.05
external_load_n = [[0, 10.0], [120, 25.0], [180, 25.0], [300, 10.0]]
friction = 0.05
roller_width_mm = 12.0
""", """
base_radius = [20, 44, 4]
offset = [-8, 8, 4]
roller_radius = [6, 10]
law = [{ segment = 0, choices = ["cycloidal", "modified-sine"] }]
"""),
    "oscillating-roller": ("""
[follower]
kind = "oscillating-roller"
roller_radius = 10.0
pivot_distance = 110.0
arm_length = 85.0
[dynamics]
inertia_kgm2 = 0.004
spring_rate_n_per_mm = 2.0
preload_n = 40.0
damping_ratio = 0.05
roller_width_mm = 10.0
materials = { cam = "ductile-iron", follower = "steel" }
""", """
base_radius = [30, 50, 10]
pivot_distance = [100, 120, 10]
arm_length = [75, 95, 10]
roller_radius = [8, 10]
max_pressure_angle_deg = 45
"""),
    "translating-flat": ("""
[follower]
kind = "translating-flat"
offset = 0.0
[dynamics]
mass_kg = 1.2
spring_rate_n_per_mm = 3.0
preload_n = 80.0
damping_n_s_per_m = 15.0
materials = { cam = "cast-iron", follower = "steel" }
""", """
base_radius = [30, 60, 3]
law = [{ segment = 2, choices = ["cycloidal", "polynomial-345"] }]
"""),
}


def write_spec(tmp_path: Path, kind: str, limits: str = "", name: str = "dyn") -> Path:
    follower, axes = KINDS[kind]
    path = tmp_path / f"{name}.toml"
    path.write_text(f'name = "{name}"\n' + MOTION + follower + "\n[size]\n" + axes + limits + "samples = 1440\n")
    return path


def sweep(path: Path, **size_changes):
    spec = load_spec(path)
    if size_changes:
        spec = replace(spec, size=replace(spec.size, **size_changes))
    return run_sweep(spec, InProcess())


@pytest.mark.parametrize("kind", list(KINDS))
def test_sweep_figures_against_run_dynamics(kind, tmp_path):
    """Each design's sampled stress is at most the exact one and close to it; the jump speed is the exact one."""
    r = sweep(write_spec(tmp_path, kind, "max_contact_stress_mpa = 5000\nmin_jump_rpm = 1\n"))
    t = r.table
    spec = load_spec(write_spec(tmp_path, kind))
    from camcam.sizing.contact import SweepDynamics

    contact = SweepDynamics.of(spec)
    ok = np.flatnonzero(t["valid"] & ~t["undercut"] & (t["min_curvature_radius_mm"] > 0))
    assert ok.size >= 8
    for number in ok[:: max(1, ok.size // 12)]:
        params, _ = r.grid.design(int(number))
        combo = int(number) // r.grid.per_combo
        ex = exact_figures(kind, r.programs[combo], params, "ccw", (contact, spec.cam))
        assert not ex.dynamics_problem
        # a sampled maximum is never above the root-found one: float noise only (1e-9 relative)
        assert t["max_contact_stress_mpa"][number] <= ex.max_contact_stress_mpa * (1 + 1e-9)
        # 1440 samples a revolution: the samples' best is within h²·max|p″|/8 of the maximum (measured ≤ 4.2e-6
        # relative on these grids; 1e-4 leaves room for a sharper peak of another law)
        assert t["max_contact_stress_mpa"][number] == pytest.approx(ex.max_contact_stress_mpa, rel=1e-4)
        # the same function (program_jump_speed) as analyse_dynamics' jump_speed: equal to float noise
        assert t["jump_rpm"][number] == pytest.approx(ex.jump_rpm, rel=1e-12)


def test_accepted_design_meets_both_in_camcam_run(tmp_path):
    """The best design, written as a spec, run by `camcam run`: its report's dynamics meet both limits."""
    free = sweep(write_spec(tmp_path, "translating-roller", "max_contact_stress_mpa = 1e4\n", name="free"))
    assert free.best is not None
    stress = round(0.98 * free.best_exact.max_contact_stress_mpa, 1)  # a limit the unconstrained best misses
    path = write_spec(tmp_path, "translating-roller", f"max_contact_stress_mpa = {stress:.1f}\nmin_jump_rpm = 600\n")
    code, out, err = cli("size", str(path), "-o", str(tmp_path / "sized"), "--table", "csv")
    assert code == 0, err
    best = json.loads((tmp_path / "sized" / "dyn-best.json").read_text())["best"]
    assert "max contact stress" in out and best["design"] != free.best
    assert best["exact"]["max_contact_stress_mpa"] <= stress * (1 + 1e-9)  # the sweep's LIMIT_RTOL
    code, _, err = cli("run", str(tmp_path / "sized" / "dyn-best.toml"), "-o", str(tmp_path / "run"))
    assert code == 0, err
    dyn = json.loads((tmp_path / "run" / "dyn-best-report.json").read_text())["dynamics"]
    # `camcam run` computes the same figures as the exact check: equal to float noise (1e-12 relative)
    assert dyn["max_contact_stress_mpa"] == pytest.approx(best["exact"]["max_contact_stress_mpa"], rel=1e-12)
    assert dyn["jump_rpm"] == pytest.approx(best["exact"]["jump_rpm"], rel=1e-12)
    assert dyn["max_contact_stress_mpa"] <= stress * (1 + 1e-9)  # the limit, met within the sweep's LIMIT_RTOL
    assert dyn["jump_rpm"] >= 600 * (1 - 1e-9)  # the limit, met within the sweep's LIMIT_RTOL


@pytest.mark.parametrize("kind", ["translating-roller", "oscillating-roller"])
def test_tightening_a_limit_removes_designs(kind, tmp_path):
    """A lower stress limit or a higher jump speed keeps a subset of the feasible designs (nested sets)."""
    path = write_spec(tmp_path, kind, "max_contact_stress_mpa = 1e4\nmin_jump_rpm = 1\n")
    base = sweep(path)
    stress = base.table["max_contact_stress_mpa"][base.table["feasible"]]
    levels = np.quantile(stress, [1.0, 0.75, 0.5, 0.25])
    previous = None
    for level in levels:  # each a real sweep, not a re-filtering of one table
        kept = set(sweep(path, max_contact_stress_mpa=float(level)).ranked.tolist())
        if previous is not None:
            assert kept <= previous
        previous = kept
    assert len(previous) < int(base.table["feasible"].sum())
    jump = np.unique(base.table["jump_rpm"])
    previous = None
    for level in [1.0, *jump]:
        kept = set(sweep(path, min_jump_rpm=float(level)).ranked.tolist())
        if previous is not None:
            assert kept <= previous
        previous = kept


@pytest.mark.parametrize("limits, fragment", [
    ("max_contact_stress_mpa = -5\n", "size.max_contact_stress_mpa: expected a number > 0"),
    ("max_contact_stress_mpa = 0\n", "size.max_contact_stress_mpa: expected a number > 0"),
    ("min_jump_rpm = -100\n", "size.min_jump_rpm: expected a number > 0"),
    ('min_jump_rpm = "fast"\n', "size.min_jump_rpm: expected a number > 0"),
])
def test_bad_limits_one_line_exit_2(limits, fragment, tmp_path):
    code, _, err = cli("size", str(write_spec(tmp_path, "translating-roller", limits)), "-o", str(tmp_path / "o"))
    assert code == 2 and fragment in err and len(err.strip().splitlines()) == 1, err


def test_needs_dynamics_table(tmp_path):
    path = write_spec(tmp_path, "translating-roller", "min_jump_rpm = 500\n")
    path.write_text(path.read_text().split("[dynamics]")[0] + "[size]" + path.read_text().split("[size]")[1])
    code, _, err = cli("size", str(path), "-o", str(tmp_path / "o"))
    assert code == 2 and "size.min_jump_rpm: needs a [dynamics] table" in err and len(err.strip().splitlines()) == 1, err


def test_needs_a_given_spring(tmp_path):
    path = write_spec(tmp_path, "translating-roller", "max_contact_stress_mpa = 900\n")
    text = path.read_text().replace("spring_rate_n_per_mm = 1.5\npreload_n = 60.0\ndamping_ratio = 0.05\n",
                                    'spring = "size"\ndamping_n_s_per_m = 10.0\n')
    path.write_text(text)
    code, _, err = cli("size", str(path), "-o", str(tmp_path / "o"))
    assert code == 2 and "needs a given spring" in err and len(err.strip().splitlines()) == 1, err


def test_without_constraints_no_new_columns(tmp_path):
    """A [dynamics] table alone changes nothing in the sweep (the sample outputs stay as recorded)."""
    r = sweep(write_spec(tmp_path, "translating-flat"))
    assert "jump_rpm" not in r.table and "max_contact_stress_mpa" not in r.table
    assert math.isnan(r.best_exact.jump_rpm)
