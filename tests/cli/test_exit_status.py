"""Honest exit statuses: 2 bad input (one line, nothing written), 3 written but FAIL, 1 internal fault
(one line, traceback in a file), and progress that never breaks the one-line promise on a busy machine."""

from __future__ import annotations

import contextlib
import io
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import camcam.flow as run_module
from camcam.cli import main
from camcam.errors import FitError
from camcam.verdict import Check, Verdict

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "disc-translating-roller.toml"


def cli(*args) -> tuple[int, str, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    return code, out.getvalue(), err.getvalue()


def _undercut_spec(tmp_path: Path) -> Path:
    spec = SAMPLE.read_text()
    spec = spec.replace("base_radius = 40.0", "base_radius = 3.0").replace("bore = 12.0", "bore = 2.0")
    spec = spec.replace("roller_radius = 10.0", "roller_radius = 30.0").replace("offset = 5.0", "offset = 0.0")
    spec = spec.replace("to = 120, rise = 20.0", "to = 40, rise = 40.0").replace('{ law = "dwell", from = 120', '{ law = "dwell", from = 40')
    spec = spec.replace("from = 180, to = 300, rise = -20.0", "from = 180, to = 220, rise = -40.0").replace("from = 300", "from = 220")
    bad = tmp_path / "bad.toml"
    bad.write_text(spec)
    return bad


def test_bad_input_is_one_line_on_a_busy_machine(tmp_path):
    # two busy loops hold both cores, so every step of the run is slow; stderr is a pipe (no terminal),
    # so no progress line may appear: exactly the one error line
    busy = [subprocess.Popen([sys.executable, "-c", "while True: pass"]) for _ in range(2)]
    try:
        env = {**os.environ, "PYTHONPATH": str(ROOT)}
        r = subprocess.run([sys.executable, "-m", "camcam", "run", str(_undercut_spec(tmp_path)), "-o",
                            str(tmp_path / "out")], capture_output=True, text=True, env=env)
    finally:
        for p in busy:
            p.kill()
            p.wait()
    assert r.returncode == 2
    assert r.stderr.count("\n") == 1 and r.stderr.startswith("camcam: error: undercut at cam angle "), r.stderr
    assert "cam.base_radius >= " in r.stderr  # names the key and the way out
    assert not (tmp_path / "out").exists()


def test_progress_only_when_asked(tmp_path, monkeypatch):
    # a step made slow on purpose: silent without --progress (stderr is no terminal here), announced with it
    import camcam.cli.progress as progress

    real = progress.Progress.step

    def slow_step(self, name, delay_s=1.0):
        return real(self, name, delay_s=0.0)

    monkeypatch.setattr(progress.Progress, "step", slow_step)
    code, _, err = cli("run", "samples/demo.toml", "-o", str(tmp_path / "a"))
    assert code == 0 and err == ""
    code, _, err = cli("run", "samples/demo.toml", "-o", str(tmp_path / "b"), "--progress")
    assert code == 0 and "camcam: motion table and plot" in err


def test_internal_fault_is_exit_1_with_details_in_a_file(tmp_path, monkeypatch):
    def broken(*args, **kw):
        raise FitError("profile: cannot fit the curve within 0.01 mm")

    monkeypatch.setattr("camcam.nc.machine_program", broken)  # the first NC step `camcam run` takes
    out = tmp_path / "job" / "out"
    out.parent.mkdir()  # the parent exists (the output folder does not yet): the details go there
    code, _, err = cli("run", str(SAMPLE), "-o", str(out))
    assert code == 1
    assert err.count("\n") == 1
    assert err.startswith("camcam: internal error: FitError: profile: cannot fit the curve within 0.01 mm; details in ")
    details = Path(err.strip().rsplit("details in ", 1)[1])
    assert details.parent == out.parent.resolve()  # beside the output folder, never inside it
    assert "Traceback" in details.read_text() and "FitError" in details.read_text()
    assert not out.exists()


def test_a_bug_is_not_dressed_up_as_bad_input(tmp_path, monkeypatch):
    def bug(*args, **kw):
        raise ZeroDivisionError("division by zero")

    monkeypatch.setattr(run_module, "nc_step", bug)
    code, _, err = cli("run", str(SAMPLE), "-o", str(tmp_path / "out"))
    assert code == 1 and "internal error: ZeroDivisionError" in err and "error: " not in err.split("internal")[0]


@pytest.mark.parametrize("accepted, status", [(False, 3), (True, 0)])
def test_fail_verdict_writes_everything_and_exits_3(tmp_path, monkeypatch, accepted, status):
    failing = Check("3-D groove deviation", 1.3, 0.02, "mm", ok=False, where="flank 0, r = 80.00 mm",
                    advice="use a tool of the roller's diameter")
    monkeypatch.setattr(run_module, "job_verdict", lambda m, s: Verdict((failing,), accepted))
    code, out, err = cli("run", str(SAMPLE), "-o", str(tmp_path), "--json")
    assert code == status
    assert err.count("\n") == 1 and err.startswith("camcam: FAIL: 3-D groove deviation 1.3 mm over the limit 0.02 mm")
    assert "use a tool of the roller's diameter" in err
    files = {Path(f).name for f in json.loads(out)["files"]}
    assert {"disc-translating-roller.ngc", "disc-translating-roller-report.html"} <= files
    report = json.loads((tmp_path / "disc-translating-roller-report.json").read_text())
    assert report["verdict"]["status"] == "FAIL" and report["verdict"]["accepted"] is accepted
    html = (tmp_path / "disc-translating-roller-report.html").read_text()
    # the verdict is the first thing on the page
    assert html.index('<p class="verdict fail">FAIL</p>') < html.index("<h2>Job</h2>")


def test_pass_verdict_in_report(tmp_path):
    code, out, err = cli("run", str(SAMPLE), "-o", str(tmp_path))
    assert code == 0 and err == ""
    report = json.loads((tmp_path / "disc-translating-roller-report.json").read_text())
    assert report["verdict"]["status"] == "PASS"
    check = report["verdict"]["checks"][0]
    assert check["name"] == "NC deviation (profile)" and check["value"] == report["max_deviation_mm"]
    # the deviation, the six material-removal checks (engagement, plunges, rapids, left, overcut, rough stock),
    # the DXF part outline and the four design checks (pressure angle, radius of curvature, cut depth, finish
    # allowance)
    assert out.splitlines()[-1] == "PASS: 12 checks within their limits"
