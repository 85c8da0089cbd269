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
