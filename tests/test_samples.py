"""Every sample runs: `camcam run` on each run spec, `camcam optimize` on each optimisation
spec; the report renders in headless Chromium; the same spec gives the same bytes."""

from __future__ import annotations

import contextlib
import io
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from camcam.cli import main
from tests.report.test_html import CHROMIUM, screenshot

ROOT = Path(__file__).resolve().parents[1]
SPECS = sorted(p for p in (ROOT / "samples").rglob("*.toml"))
RUN_SPECS = [p for p in SPECS if "motion" in tomllib.loads(p.read_text())]
OPTIMIZE_SPECS = [p for p in SPECS if "optimize" in tomllib.loads(p.read_text())]


def cli(*args) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    return code, out.getvalue(), err.getvalue()


def test_every_sample_is_covered():
    assert set(RUN_SPECS) | set(OPTIMIZE_SPECS) == set(SPECS)
    assert len(RUN_SPECS) >= 18  # one per follower kind, cam kind, post, motion source


@pytest.mark.parametrize("spec", RUN_SPECS, ids=lambda p: str(p.relative_to(ROOT / "samples")))
def test_run_sample(spec, tmp_path):
    code, out, err = cli("run", str(spec), "-o", str(tmp_path), "--json")
    assert code == 0, err
    summary = json.loads(out)
    name = summary["name"]
    files = {Path(f).name for f in summary["files"]}
    assert {f"{name}-motion.csv", f"{name}-svaj.png"} <= files
    doc = tomllib.loads(spec.read_text())
    if "cam" in doc:
        assert {f"{name}.stl", f"{name}-report.html", f"{name}-report.json"} <= files
        report = json.loads((tmp_path / f"{name}-report.json").read_text())
        for key in ("max_pressure_angle_deg", "min_curvature_radius_mm"):
            assert np.isfinite(report[key])
    if "machining" in doc:
        report = json.loads((tmp_path / f"{name}-report.json").read_text())
        for key in ("tolerance_mm", "max_deviation_mm", "line_blocks", "arc_blocks"):
            assert key in report
        # the measured two-sided deviation of the printed program is within its tolerance, or the
        # verdict says FAIL and the sample accepts it (a sample that shows the FAIL verdict)
        verdict = report.get("verdict", {"status": "PASS", "accepted": False})
        within = report["max_deviation_mm"] <= report["tolerance_mm"]
        assert within == (verdict["status"] != "FAIL")  # WARN: an advisory design limit missed (issue 43)
        assert within or (verdict["accepted"] and "accept_out_of_tolerance = true" in spec.read_text())
        assert any(f.endswith(".dxf") for f in files)


@pytest.mark.parametrize("spec", OPTIMIZE_SPECS[:3], ids=lambda p: p.name)
def test_optimize_sample(spec, tmp_path):
    # exact method only here (the Complex method's budget belongs to the benchmark)
    text = spec.read_text().replace('method = "complex"', 'method = "exact"')
    local = tmp_path / spec.name
    local.write_text(text)
    code, out, err = cli("optimize", str(local), "--json")
    assert code == 0, err
    law = json.loads(out)
    assert law["Vm"] > 0 and law["Am"] > 0


def test_default_job_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = cli("run")
    assert code == 0, err
    assert (tmp_path / "camcam-out" / "disc-translating-roller-report.html").exists()


def test_same_spec_same_bytes(tmp_path):
    spec = ROOT / "samples" / "disc-groove.toml"
    for d in ("a", "b"):
        assert cli("run", str(spec), "-o", str(tmp_path / d))[0] == 0
    names = sorted(p.name for p in (tmp_path / "a").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "b").iterdir())
    for n in names:
        assert (tmp_path / "a" / n).read_bytes() == (tmp_path / "b" / n).read_bytes(), n


@pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (Debian package chromium); .ci/run installs it")
@pytest.mark.parametrize("sample", ["disc-translating-roller", "cylindrical-translating"])
def test_report_renders_in_chromium(sample, tmp_path):
    from PIL import Image

    assert cli("run", str(ROOT / "samples" / f"{sample}.toml"), "-o", str(tmp_path))[0] == 0
    shot = tmp_path / "shot.png"
    r = screenshot(tmp_path / f"{sample}-report.html", shot, tmp_path)
    assert shot.exists(), r.stderr[-2000:]
    img = np.asarray(Image.open(shot).convert("L"), dtype=float)
    # a rendered report: headings, tables and plots make many dark pixels on the first screen
    assert (img < 128).mean() > 0.005


def test_outputs_as_recorded():
    # every byte of every output of these samples as recorded in tests/data/sample_checksums.json, in a fresh
    # process (nothing this test process set up can leak in); tests/make_sample_checksums.py says when to re-record
    import os
    import subprocess
    import sys

    names = ["samples/disc-translating-roller.toml", "samples/disc-groove.toml", "samples/demo.toml"]
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    r = subprocess.run([sys.executable, str(ROOT / "tests" / "make_sample_checksums.py"), "--check", *names],
                       capture_output=True, text=True, env=env, cwd=ROOT)
    assert r.returncode == 0, r.stdout + r.stderr
