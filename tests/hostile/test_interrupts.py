"""Class 3 (interrupts): Ctrl-C or a termination signal at any moment gives one line and 128+n, and the
line says what is on disk; a SIGKILL at any point leaves the target as it was or complete, and the next
run clears what the killed one left."""

from __future__ import annotations

import os
import signal

import pytest

import camcam.export.files as files
from camcam.export.files import MANIFEST, OutputSet
from tests.hostile.harness import SAMPLES, assert_clean_error, run_inproc, run_sub, snapshot

DEMO = SAMPLES / "demo.toml"


def _signal_at(monkeypatch, name, k, signum, obj=files):
    """Send ``signum`` to this process at the k-th call of ``obj.name`` (before it runs)."""
    real = getattr(obj, name)
    calls = [0]

    def wrapper(*a, **kw):
        calls[0] += 1
        if calls[0] == k:
            os.kill(os.getpid(), signum)
        return real(*a, **kw)

    monkeypatch.setattr(obj, name, wrapper)


@pytest.mark.parametrize("signum,k", [(signal.SIGINT, 1), (signal.SIGTERM, 2), (signal.SIGHUP, 3)])  # 2 files + manifest
def test_signal_while_writing_leaves_the_target_as_it_was(tmp_path, monkeypatch, signum, k):
    out = tmp_path / "out"
    assert run_inproc(["motion", DEMO, "-o", out])[0] == 0
    before = snapshot(tmp_path)
    _signal_at(monkeypatch, "_write_file", k, signum)
    code, _, err = run_inproc(["motion", DEMO, "-o", out, "--force"])
    line = assert_clean_error(code, err, status=128 + signum, prefix="camcam: ")
    assert line.endswith(f"nothing was written; {out} is as it was"), line
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_signal_during_publishing_is_held_until_the_set_is_complete(tmp_path, monkeypatch, signum):
    out = tmp_path / "out"
    assert run_inproc(["motion", DEMO, "-o", out])[0] == 0
    _signal_at(monkeypatch, "_exchange", 1, signum)
    code, _, err = run_inproc(["motion", DEMO, "-o", out, "--force"])
    line = assert_clean_error(code, err, status=128 + signum, prefix="camcam: ")
    assert line.endswith(f"{out} holds this run's complete output (3 files, listed in its {MANIFEST})"), line
    assert sorted(os.listdir(tmp_path)) == ["out"] and (out / MANIFEST).exists()


def test_interrupt_before_anything_is_written(tmp_path, monkeypatch):
    import camcam.cli.motion as motion

    _signal_at(monkeypatch, "motion_outputs", 1, signal.SIGINT, obj=motion)
    code, _, err = run_inproc(["motion", DEMO, "-o", tmp_path / "out"])
    assert assert_clean_error(code, err, status=130, prefix="camcam: ") == \
        f"camcam: interrupted; nothing was written; {tmp_path / 'out'} is as it was"
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("command,module", [
    ("motion", "camcam.cli.motion"),   # the command's module, loaded while the parser is built
    ("motion", "camcam.spec.motion"),  # loaded inside the command
    ("motion", "matplotlib.figure"),   # loaded by the child process that draws the plot (camcam.workers)
    ("run", "shapely"),                # loaded inside the command, by the NC stage
    # in the drawing's prepared child (a run imported trimesh.path there, whose own ``except BaseException``
    # swallowed the signal, until issue 49 wrote the STL with numpy: no run imports trimesh now)
    ("run", "ezdxf"),
])
def test_ctrl_c_while_importing(tmp_path, command, module):
    """Ctrl-C while a module loads: one line, 130, nothing written — also when a library swallows it,
    and also when the process that gets it is one of the run's children (the signal goes to that one
    process only here; a terminal's Ctrl-C goes to the whole process group)."""
    spec = DEMO if command == "motion" else SAMPLES / "disc-groove.toml"
    r = run_sub([command, spec, "-o", tmp_path / "out"], inject=["sigint-on-import", module])
    line = assert_clean_error(r.returncode, r.stderr, status=130, prefix="camcam: ")
    assert line in ("camcam: interrupted while starting; nothing was written", "camcam: interrupted; nothing was written",
                    f"camcam: interrupted; nothing was written; {tmp_path / 'out'} is as it was"), line
    assert os.listdir(tmp_path) == []


# SIGKILL at every step of a publish that replaces an earlier set (--force): before and while each
# file is written, before the exchange, before the earlier set is removed, before the lock goes.
KILL_POINTS = [("_write_file", k) for k in (1, 2, 3)] + [("_fsync_dir", 1), ("_exchange", 1), ("_remove", 1),
                                                           ("_fsync_dir", 2)]


@pytest.mark.parametrize("exchange", [True, False], ids=["renameat2", "two-renames"])
@pytest.mark.parametrize("step,k", KILL_POINTS + [("rename", 1), ("rename", 2), ("rename", 3)])
def test_sigkill_at_any_point(tmp_path, step, k, exchange):
    if step == "rename" and exchange:
        pytest.skip("the two renames are the fallback's")
    out = tmp_path / "out"
    earlier = OutputSet(out)
    earlier.add("demo-motion.csv", "old")
    earlier.add("stale.ngc", "old post")
    earlier.commit()
    old = snapshot(out)
    inject = ([] if exchange else ["no-exchange"]) + ["kill-at", step, str(k), "publish"]
    r = run_sub([out], inject=inject)  # a bare publish: the property lives in OutputSet, no numpy to load
    assert r.returncode == -signal.SIGKILL, r.stderr  # the kill point was reached
    if not os.path.exists(out):
        # only between the fallback's two renames: the earlier set waits beside it, whole
        assert not exchange and step == "rename"
        [aside] = [p for p in os.listdir(tmp_path) if ".camcam-old-" in p]
        assert snapshot(tmp_path / aside) == old
    else:
        now = snapshot(out)
        assert now == old or (sorted(now) == ["camcam-manifest.json", "demo-motion.csv", "demo-svaj.png"]), sorted(now)
    # the next run clears whatever the killed one left and publishes a complete set
    again = OutputSet(out, force=True)
    again.add("demo-motion.csv", "again")
    again.commit()
    assert sorted(os.listdir(tmp_path)) == ["out"]
    assert sorted(os.listdir(out)) == ["camcam-manifest.json", "demo-motion.csv"]
