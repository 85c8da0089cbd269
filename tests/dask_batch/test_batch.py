"""`camcam batch` in-process (no Dask): one folder per spec, a summary row for every spec, a failing
spec (bad input or an internal fault) reported without stopping the others."""

from __future__ import annotations

import csv
import json

import camcam.flow as flow
from camcam.dask_batch import engine
from tests.sizing.helpers import ROOT, cli


def test_batch_without_dask_reports_every_spec(tmp_path, monkeypatch):
    monkeypatch.setattr(engine, "dask_available", lambda: False)
    bad = tmp_path / "bad.toml"
    bad.write_text((ROOT / "samples" / "demo.toml").read_text().replace("rpm = ", "rpm = -"))
    specs = [str(ROOT / "samples" / "demo.toml"), str(bad), str(ROOT / "samples" / "demo.toml")]
    code, out, err = cli("batch", *specs, "-o", str(tmp_path / "out"), "--json")
    assert code == 3
    assert err.startswith("camcam: FAIL: 1 of 3 specs did not pass; first: ") and err.count("\n") == 1
    printed = json.loads(out)
    assert printed["note"] == engine.SCALE_HINT  # the scale-out hint rides in the printed summary only
    rows = list(csv.DictReader((tmp_path / "out" / "summary.csv").open()))
    assert [r["verdict"] for r in rows] == ["PASS", "ERROR", "PASS"]
    assert rows[1]["reason"].startswith("motion.rpm: expected a number > 0")
    # a repeated file stem gets its own folder
    assert [r["folder"] for r in rows] == ["demo", "bad", "demo-2"]
    assert (tmp_path / "out" / "demo" / "demo-svaj.png").read_bytes() == (tmp_path / "out" / "demo-2" / "demo-svaj.png").read_bytes()
    assert not (tmp_path / "out" / "bad").exists()
    index = (tmp_path / "out" / "index.html").read_text()
    assert "3 specs: 2 PASS, 1 not" in index and engine.SCALE_HINT not in index


def test_an_internal_fault_is_a_row_not_the_end(tmp_path, monkeypatch):
    real = flow.run_job

    def job(spec, **kw):
        if str(getattr(spec, "source", spec)).endswith("disc-translating-flat.toml"):  # the batch passes it loaded
            raise ZeroDivisionError("simulated fault")
        return real(spec, **kw)

    monkeypatch.setattr(flow, "run_job", job)
    code, _, err = cli("batch", str(ROOT / "samples" / "disc-translating-flat.toml"), str(ROOT / "samples" / "demo.toml"),
                       "-o", str(tmp_path / "out"), "--in-process")
    assert code == 3
    rows = list(csv.DictReader((tmp_path / "out" / "summary.csv").open()))
    assert rows[0]["verdict"] == "ERROR" and rows[0]["reason"] == "internal fault: ZeroDivisionError: simulated fault"
    assert rows[1]["verdict"] == "PASS" and (tmp_path / "out" / "demo" / "demo-motion.csv").exists()


def test_batch_force_replaces_an_earlier_batch_and_the_loser_of_a_race_is_told(tmp_path, monkeypatch):
    """Issue 50 item 11: `batch --force` said an earlier batch's folder 'holds files camcam did not write' (its
    manifest's `spec/file` names were not read), and so did the loser of two concurrent batches."""
    monkeypatch.setattr(engine, "dask_available", lambda: False)
    demo, out = str(ROOT / "samples" / "demo.toml"), tmp_path / "out"
    assert cli("batch", demo, "-o", str(out))[0] == 0
    code, _, err = cli("batch", demo, "-o", str(out))
    assert code == 2 and "add --force" in err and err.count("\n") == 1
    assert cli("batch", demo, "-o", str(out), "--force")[0] == 0
    # a race: another batch publishes into the folder while this one runs
    real = flow.run_job

    def job(spec, **kw):
        if not out.with_name("other").exists():
            out.with_name("other").mkdir()
            assert cli("batch", demo, "-o", str(tmp_path / "race"))[0] == 0
        return real(spec, **kw)

    monkeypatch.setattr(flow, "run_job", job)
    code, _, err = cli("batch", demo, "-o", str(tmp_path / "race"))
    assert code == 2 and "another camcam run published its files there while this one ran" in err, err


def test_a_job_without_forks_gives_the_same_row_and_bytes():
    """Issue 49: on a Dask worker a batch job runs in its worker alone (camcam.workers.single_process); a disc
    and a barrel cam (whose NC step and 3-D measurement share their work between processes when they fork)."""
    from camcam.cli.batch import batch_task

    for name in ("disc-translating-roller", "cylindrical-translating"):
        item = (str(ROOT / "samples" / f"{name}.toml"), name)
        forked_row, forked_files = batch_task(item, forks=True)
        alone_row, alone_files = batch_task(item, forks=False)
        assert forked_row["verdict"] in ("PASS", "WARN") and len(forked_files) > 5, forked_row  # WARN: a design limit
        assert alone_row == forked_row
        assert sorted(alone_files) == sorted(forked_files)
        assert [n for n in forked_files if alone_files[n] != forked_files[n]] == []


def test_jobs_fork_in_process_and_run_alone_on_a_cluster(tmp_path, monkeypatch):
    """`batch --in-process` forks as `camcam run` does; on a Dask cluster, whose workers fill the cores, it does not."""
    import contextlib

    import camcam.cli.batch as batch

    asked = []
    real = batch.batch_task
    monkeypatch.setattr(batch, "batch_task", lambda item, forks=True: asked.append(forks) or real(item, forks))

    class Cluster(engine.Executor):  # stands for a DaskExecutor: the tasks run here
        def map(self, fn, items, what="tasks", **shared):
            return [fn(item, **shared) for item in items]

    demo = str(ROOT / "samples" / "demo.toml")
    for executor in (engine.InProcess(), Cluster()):
        monkeypatch.setattr(batch, "executor_from_args", lambda args, e=executor: contextlib.nullcontext(e))
        assert cli("batch", demo, "-o", str(tmp_path / type(executor).__name__))[0] == 0
    assert asked == [True, False]


def test_an_in_process_batch_loads_its_jobs_child_libraries_once(tmp_path):
    """Issue 49: in one process, each job's children (plot server, drawing's child) would import matplotlib and
    ezdxf again, job after job; the batch loads them before each job (camcam.flow.load_child_modules), so every
    fork of the batch finds them loaded and the children inherit them.  In a fresh interpreter, two jobs."""
    import subprocess
    import sys

    specs = [str(ROOT / "samples" / f"{n}.toml") for n in ("disc-translating-roller", "disc-groove")]
    code = (
        "import json, os, sys\n"
        "at_fork = []\n"
        "os.register_at_fork(before=lambda: at_fork.append(all(m in sys.modules for m in ('matplotlib', 'ezdxf'))))\n"
        "from camcam.cli.batch import batch_task\n"
        f"rows = [batch_task((s, f'f{{i}}'), forks=True)[0]['verdict'] for i, s in enumerate({specs!r})]\n"
        "print(json.dumps({'rows': rows, 'at_fork': at_fork}))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    result = json.loads(r.stdout.strip().splitlines()[-1])
    assert result["rows"] == ["PASS", "PASS"]
    assert len(result["at_fork"]) >= 4 and all(result["at_fork"])  # a plot server and a drawing child a job, at least
