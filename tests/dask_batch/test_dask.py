"""Dask: `camcam size` and `camcam batch` write the same bytes in-process, on a local cluster of
one worker, and on a two-worker LocalCluster reached by its address (as a user's cluster is)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

distributed = pytest.importorskip("distributed")

from tests.sizing.helpers import BASE, ROOT, cli  # noqa: E402




def tree(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def scheduler():
    import logging

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0",
                                  silence_logs=logging.ERROR) as cluster:
        yield cluster.scheduler_address


def test_size_same_bytes_in_process_one_worker_and_cluster(scheduler, tmp_path):
    spec = tmp_path / "s.toml"
    # 2 law combinations × 3 chunks each (1,353 designs a combination): the workers share the chunks
    spec.write_text(BASE + "[size]\nbase_radius = [10, 42, 0.5]\noffset = [-10, 10, 1]\n"
                    'law = [{ segment = 0, choices = ["cycloidal", "modified-sine"] }]\nsamples = 720\n')
    runs = {"in-process": ("--in-process",), "one worker": ("--workers", "1"), "cluster": ("--scheduler", scheduler)}
    trees = {}
    for label, flags in runs.items():
        code, out, err = cli("size", str(spec), "-o", str(tmp_path / label), "--json", *flags)
        assert code == 0, (label, err)
        trees[label] = tree(tmp_path / label)
        assert json.loads(out)["designs"] == 65 * 21 * 2
    assert len(trees["in-process"]) == 7  # six outputs and the manifest of the output folder
    assert trees["one worker"] == trees["in-process"]
    assert trees["cluster"] == trees["in-process"]


def test_batch_same_bytes_in_process_and_cluster(scheduler, tmp_path):
    specs = [str(ROOT / "samples" / "demo.toml"), str(ROOT / "samples" / "disc-translating-roller.toml"),
             str(tmp_path / "missing.toml")]
    results = {}
    for label, flags in {"in-process": ("--in-process",), "cluster": ("--scheduler", scheduler)}.items():
        code, out, err = cli("batch", *specs, "-o", str(tmp_path / label), *flags)
        # the missing spec is a row of the summary, not the end of the batch: exit 3, others written
        assert code == 3, err
        assert err.count("\n") == 1 and "1 of 3 specs did not pass" in err
        results[label] = tree(tmp_path / label)
    assert results["cluster"] == results["in-process"]
    summary = (tmp_path / "cluster" / "summary.csv").read_text().splitlines()
    assert [line.split(",")[3] for line in summary[1:]] == ["PASS", "PASS", "ERROR"]
    assert "disc-translating-roller/disc-translating-roller.ngc" in results["cluster"]
    assert not any(k.startswith("missing/") for k in results["cluster"])


def test_a_scheduler_without_workers_is_given_up_after_the_timeout(tmp_path):
    """Issue 50 item 12: `batch --scheduler ADDR` against a scheduler with no workers hung silently; now it waits
    --timeout seconds and ends with one line naming --timeout, nothing written."""
    import logging

    with distributed.LocalCluster(n_workers=0, processes=False, dashboard_address=":0",
                                  silence_logs=logging.ERROR) as empty:
        code, _, err = cli("batch", str(ROOT / "samples" / "demo.toml"), "-o", str(tmp_path / "out"),
                           "--scheduler", empty.scheduler_address, "--timeout", "1")
    assert code == 2 and err.count("\n") == 1, err
    assert err.startswith("camcam: error: --timeout: no worker joined the Dask scheduler") and "within 1 s" in err
    assert not (tmp_path / "out").exists()


def test_the_local_clusters_workers_keep_mallocs_sliding_mmap_threshold(monkeypatch):
    """Issue 49: Dask's MALLOC_TRIM_THRESHOLD_=65536 made every large numpy array a fresh mmap in the workers (4.6×
    the system time of a batch); our local cluster starts its workers without it, a user's own value still counts."""
    import os

    from camcam.dask_batch import engine

    monkeypatch.delenv("MALLOC_TRIM_THRESHOLD_", raising=False)
    with engine.open_executor(workers=1) as executor:
        assert list(executor.client.run(os.environ.get, "MALLOC_TRIM_THRESHOLD_").values()) == [None]
    monkeypatch.setenv("MALLOC_TRIM_THRESHOLD_", "131072")
    with engine.open_executor(workers=1) as executor:
        assert list(executor.client.run(os.environ.get, "MALLOC_TRIM_THRESHOLD_").values()) == ["131072"]
