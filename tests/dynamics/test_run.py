"""[dynamics] through `camcam run` (issue 45): report.json, the motion table, the report section, the verdict."""

from __future__ import annotations

import contextlib
import io
import json
from pathlib import Path

import pytest

from camcam.cli import main
from camcam.flow import run_job

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples" / "dynamics"


def cli(*args) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    return code, out.getvalue(), err.getvalue()


def cam_only(tmp_path, sample: str, **dynamics) -> Path:
    """The sample without its [machining] and [stock] (the dynamics need neither), [dynamics] keys replaced."""
    text = (SAMPLES / f"{sample}.toml").read_text()
    head, dyn = text.split("[dynamics]")
    for table in ("[machining]", "[stock]"):
        if table in head:
            start = head.index(table)
            end = min([head.index(t, start + 1) for t in ("\n[", ) if t in head[start + 1:]] + [len(head)])
            head = head[:start] + head[end:]
    lines = [ln for ln in dyn.strip().splitlines() if ln.split("=")[0].strip() not in dynamics]
    lines += [f"{k} = {json.dumps(v)}" for k, v in dynamics.items()]
    p = tmp_path / f"{sample}.toml"
    p.write_text(head + "[dynamics]\n" + "\n".join(lines) + "\n")
    return p


KEYS = ("max_contact_force_n", "min_contact_force_n", "jump_rpm", "jump_angle_deg", "max_torque_nm", "rms_torque_nm",
        "max_contact_stress_mpa", "max_contact_stress_angle_deg", "spring_rate_n_per_mm", "preload_n")


def test_report_table_and_page(tmp_path):
    job = run_job(cam_only(tmp_path, "translating-roller"))
    name = job.name
    report = json.loads(job.files[f"{name}-report.json"])
    assert set(KEYS) <= set(report["dynamics"])
    assert report["dynamics"]["jump_rpm"] > 1.25 * 400
    header = job.files[f"{name}-motion.csv"].decode().splitlines()[0].split(",")
    assert header[-4:] == ["follower_force_n", "contact_force_n", "camshaft_torque_nm", "contact_stress_mpa"]
    html = job.files[f"{name}-report.html"].decode()
    assert "<h2>Dynamics</h2>" in html and "jump speed" in html
    assert job.files[f"{name}-dynamics.png"][:8] == b"\x89PNG\r\n\x1a\n"
    names = [c.name for c in job.verdict.checks]
    assert {"contact stress", "jump speed", "contact force"} <= set(names)


def test_sized_spring_and_groove(tmp_path):
    job = run_job(cam_only(tmp_path, "translating-flat"))
    dyn = json.loads(job.files[f"{job.name}-report.json"])["dynamics"]
    assert dyn["spring_sized"] and dyn["spring_rate_n_per_mm"] > 0 and "linear program" in dyn["spring_rule"]
    assert dyn["jump_rpm"] >= 1.3 * 400
    groove = run_job(cam_only(tmp_path, "groove"))
    dyn = json.loads(groove.files[f"{groove.name}-report.json"])["dynamics"]
    assert dyn["positive_drive"] and dyn["jump_rpm"] is None and dyn["spring_rate_n_per_mm"] is None
    assert dyn["max_lift_flank_force_n"] > 0 and dyn["max_return_flank_force_n"] > 0
    header = groove.files[f"{groove.name}-motion.csv"].decode().splitlines()[0]
    assert "lift_flank_force_n,return_flank_force_n" in header
    assert "jump speed" not in [c.name for c in groove.verdict.checks]


@pytest.mark.parametrize("limits, status, code", [("warn", "WARN", 0), ("fail", "FAIL", 3)])
def test_limits_missed_warn_or_fail(tmp_path, limits, status, code):
    spec = cam_only(tmp_path, "translating-roller", allowable_contact_stress_mpa=50.0, preload_n=5.0,
                    spring_rate_n_per_mm=0.2)
    spec.write_text(spec.read_text().replace("[cam]\n", f'[cam]\ndesign_limits = "{limits}"\n'))
    rc, out, err = cli("run", str(spec), "-o", str(tmp_path / "out"), "--json")
    assert rc == code, err
    verdict = json.loads(out)["cam"]["verdict"]
    assert verdict["status"] == status
    missed = {c["name"] for c in verdict["checks"] if not c["ok"]}
    assert {"contact stress", "jump speed"} <= missed


def test_a_spring_that_cannot_hold_at_rest_is_one_line_exit_2(tmp_path):
    spec = cam_only(tmp_path, "translating-roller", external_load_n=-80.0)
    out = tmp_path / "out"
    rc, _, err = cli("run", str(spec), "-o", str(out))
    assert rc == 2
    assert err.count("\n") == 1 and err.startswith("camcam: error: dynamics.preload_n: 60 N: the spring cannot hold")
    assert not out.exists()
