"""The Python face (issue 44): `camcam.flow.run_job(spec) -> Job` writes nothing and holds what `camcam run` writes,
byte for byte; `Job.write(folder)` publishes it like the command does."""

from __future__ import annotations

import os
import pickle

import pytest

from camcam.errors import OutputError, SpecError
from camcam.export.files import MANIFEST
from camcam.flow import Job, run_job
from tests.hostile.harness import SAMPLES, run_inproc, snapshot

SPEC = SAMPLES / "disc-translating-roller.toml"


@pytest.fixture(scope="module")
def job() -> Job:
    return run_job(SPEC)


def test_run_job_writes_nothing_and_holds_what_the_command_writes(job, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    before = snapshot(tmp_path)
    again = run_job(SPEC)
    assert snapshot(tmp_path) == before  # nothing on disk, not even a temporary file
    code, _, err = run_inproc(["run", SPEC, "-o", tmp_path / "out"])
    assert code == 0, err
    written = {p.name: p.read_bytes() for p in (tmp_path / "out").iterdir() if p.name != MANIFEST}
    assert written == dict(job.files) == dict(again.files)


def test_the_job_carries_its_stages_verdict_and_summary(job):
    assert job.verdict.status == "PASS" and job.verdict.exit_status == 0
    assert job.summary["cam"]["verdict"] == job.verdict.as_dict()
    assert job.machining is not None and job.machining.program.text.encode() == job.files[f"{job.name}.ngc"]
    assert job.cam.spec.kind == "disc"
    # the summary's figure is the stage's own: the largest printed-path deviation (no re-rounding on the way)
    assert job.summary["cam"]["max_deviation_mm"] == job.machining.figures()["max_deviation_mm"]


def test_a_job_is_a_value_that_pickles(job):
    """A Dask user returns Jobs from workers: the value must pickle whole."""
    back = pickle.loads(pickle.dumps(job))
    assert back.files == job.files and back.verdict == job.verdict


def test_write_publishes_all_or_nothing_and_needs_force_over_an_earlier_run(job, tmp_path):
    written = job.write(tmp_path / "out")
    assert sorted(p.name for p in written) == sorted(job.files)
    assert sorted(os.listdir(tmp_path / "out")) == sorted([*job.files, MANIFEST])
    with pytest.raises(OutputError, match="add --force"):
        job.write(tmp_path / "out")
    job.write(tmp_path / "out", force=True)


def test_bad_input_raises_the_users_error(tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text(SPEC.read_text().replace("rpm = 120", "rpm = -1"))
    with pytest.raises(SpecError, match="motion.rpm"):
        run_job(bad)


@pytest.mark.skipif(not hasattr(os, "fork"), reason="counts the forks of the material check")
def test_the_material_check_forks_only_with_cores_to_spare(job, monkeypatch):
    """On fewer than three cores the drawing's child runs the material check itself, with one worker and no fork
    (each costs system CPU, and the plot server has the other core: issue 49); on three or more, in a child of
    its own with two workers.  The same files, outline deviation and checks either way."""
    from camcam import flow
    from camcam.spec import load_spec

    real_fork, forks = os.fork, []
    monkeypatch.setattr(os, "fork", lambda: forks.append(1) or real_fork())
    args = (job.cam, job.machining, load_spec(SPEC).machining)
    out = {}
    for cores in (2, 4):
        monkeypatch.setattr(flow, "_cores", lambda n=cores: n)
        forks.clear()
        out[cores] = flow.drawing_and_check(*args), len(forks)
    assert out[2][1] == 0 and out[4][1] == 1  # none; the check's child (which forks its own, unseen here)
    assert out[2][0] == out[4][0] and out[2][0][2] is not None  # a material check, the same either way
