"""Classes 3 and 4: the output folder is published all or nothing; OS errors are one line, status 2."""

from __future__ import annotations

import errno
import fcntl
import json
import os
from pathlib import Path

import pytest

import camcam.export.files as files
from camcam.errors import OutputError
from camcam.export.files import MANIFEST, OutputSet
from tests.hostile.harness import SAMPLES, assert_clean_error, run_inproc, snapshot

DEMO = SAMPLES / "demo.toml"


def _set(target, names=("a.ngc", "a.dxf"), tag=b"new", force=False):
    out = OutputSet(target, force=force, command="test")
    for n in names:
        out.add(n, tag + b" " + n.encode())
    return out


def _earlier(target, names=("a.ngc", "a.dxf")):
    _set(target, names, b"old").commit()
    return snapshot(target.parent)


def test_manifest_lists_what_the_run_wrote(tmp_path):
    written = _set(tmp_path / "out").commit()
    doc = json.loads((tmp_path / "out" / MANIFEST).read_text())
    assert [f["name"] for f in doc["files"]] == sorted(p.name for p in written)
    assert sorted(os.listdir(tmp_path)) == ["out"]  # no temp folder, no lock file left


@pytest.mark.parametrize("state", ["earlier set", "foreign file", "earlier set + foreign file", "a file", "under a file",
                                   "unreadable manifest"])
@pytest.mark.parametrize("force", [False, True])
def test_targets_that_cannot_take_the_set_are_left_as_they_were(tmp_path, state, force):
    target = tmp_path / "out"
    if state.startswith("earlier set"):
        _earlier(target)
        if state.endswith("foreign file"):
            (target / "notes.txt").write_text("mine")
    elif state == "foreign file":
        target.mkdir()
        (target / "notes.txt").write_text("mine")
    elif state == "a file":
        target.write_text("x")
    elif state == "under a file":
        (tmp_path / "f").write_text("x")
        target = tmp_path / "f" / "out"
    elif state == "unreadable manifest":
        target.mkdir()
        (target / MANIFEST).write_text("{")
    before = snapshot(tmp_path)
    if state == "earlier set" and force:
        _set(target, ("a.nc",), force=True).commit()  # another post: the stale .ngc must go
        assert sorted(os.listdir(target)) == ["a.nc", MANIFEST]
        assert (target / "a.nc").read_bytes() == b"new a.nc"
        assert sorted(os.listdir(tmp_path)) == ["out"]
        return
    with pytest.raises(OutputError) as e:
        _set(target, force=force).commit()
    assert str(e.value).startswith(str(target) + ": ") and "\n" not in str(e.value)
    assert snapshot(tmp_path) == before


def test_cli_refuses_an_earlier_run_without_force_and_replaces_it_with(tmp_path):
    out = tmp_path / "out"
    assert run_inproc(["motion", DEMO, "-o", out])[0] == 0
    first = snapshot(out)
    code, _, err = run_inproc(["motion", DEMO, "-o", out])
    assert "add --force" in assert_clean_error(code, err)
    assert snapshot(out) == first
    code, _, err = run_inproc(["motion", DEMO, "-o", out, "--force"])
    assert code == 0, err
    assert snapshot(out) == first  # same spec, deterministic files: the same set, manifest included
    assert sorted(os.listdir(tmp_path)) == ["out"]


def test_a_held_lock_refuses_a_second_run(tmp_path):
    target = tmp_path / "out"
    fd = os.open(tmp_path / ".out.camcam-lock", os.O_RDWR | os.O_CREAT)
    fcntl.flock(fd, fcntl.LOCK_EX)
    try:
        with pytest.raises(OutputError, match="another camcam run is writing it"):
            _set(target).commit()
        assert not target.exists()
    finally:
        os.close(fd)
    _set(target).commit()  # released: the lock file is reused, then removed
    assert sorted(os.listdir(tmp_path)) == ["out"]


def test_orphans_of_a_killed_run_are_cleared(tmp_path):
    target = tmp_path / "out"
    _earlier(target)
    (tmp_path / ".out.camcam-new-0123456789ab").mkdir()
    (tmp_path / ".out.camcam-new-0123456789ab" / "a.ngc").write_text("half")
    (tmp_path / ".out.camcam-lock").write_text("")
    _set(target, force=True).commit()
    assert sorted(os.listdir(tmp_path)) == ["out"]


def test_a_killed_two_rename_publish_is_put_back(tmp_path):
    """Without RENAME_EXCHANGE a kill between the two renames leaves the earlier set aside: the next
    run puts it back before it decides anything."""
    target = tmp_path / "out"
    old = _earlier(target)
    os.rename(target, tmp_path / ".out.camcam-old-0123456789ab")
    with pytest.raises(OutputError, match="add --force"):
        _set(target).commit()  # the earlier set is back in place, so this run needs --force
    assert snapshot(tmp_path) == old


OS_FAULTS = [
    ("_write_file", errno.ENOSPC, "no space left on device"),
    ("_write_file", errno.EDQUOT, "quota exceeded"),
    ("mkdir", errno.EROFS, "read-only file system"),
    ("mkdir", errno.ENOSPC, "no space left on device"),  # out of inodes: mkdir fails with ENOSPC
    ("mkdir", errno.EACCES, "permission denied"),
    ("_fsync_dir", errno.EIO, "input/output error"),
]


@pytest.mark.parametrize("where,code,reason", OS_FAULTS, ids=[f"{w}-{errno.errorcode[c]}" for w, c, _ in OS_FAULTS])
def test_os_errors_while_publishing_are_one_line_and_leave_nothing(tmp_path, monkeypatch, where, code, reason):
    def fail(*a, **k):
        raise OSError(code, os.strerror(code), str(a[0]) if a else None)

    if where == "mkdir":
        real = os.mkdir
        monkeypatch.setattr(files.os, "mkdir", lambda p, *a: fail(p) if ".camcam-new-" in str(p) or str(p).endswith("deep")
                            else real(p, *a))
    else:
        monkeypatch.setattr(files, where, fail)
    before = snapshot(tmp_path)
    out = tmp_path / "deep" / "out"
    code_, _, err = run_inproc(["motion", DEMO, "-o", out])
    line = assert_clean_error(code_, err)
    assert line.startswith(f"camcam: error: {out}: ") and line.endswith(reason), line
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("target", ["/dev/null", "/dev/null/x", "/proc/self/cwd/../../..", "."])
def test_impossible_output_folders(tmp_path, monkeypatch, target):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "keep").write_text("x")
    before = snapshot(tmp_path)
    code, _, err = run_inproc(["motion", DEMO, "-o", target])
    assert_clean_error(code, err)
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("target", ["folder", "/dev/null/x", "under-file/x.json"])
def test_optimize_output_errors(tmp_path, target):
    (tmp_path / "folder").mkdir()
    (tmp_path / "under-file").write_text("x")
    t = target if target.startswith("/") else tmp_path / target
    before = snapshot(tmp_path)
    code, _, err = run_inproc(["optimize", SAMPLES / "optimize" / "table1.toml", "-o", t])
    assert assert_clean_error(code, err).startswith(f"camcam: error: {t}: ")
    assert snapshot(tmp_path) == before


@pytest.mark.parametrize("arg", ["spec", "table", "points", "post"])
@pytest.mark.parametrize("path", ["/dev/zero", "a folder", "missing", "not utf-8"])
def test_os_errors_on_input_are_one_line(tmp_path, arg, path):
    p = {"a folder": tmp_path, "missing": tmp_path / "nope.toml", "/dev/zero": Path("/dev/zero")}.get(path)
    if path == "not utf-8":
        p = tmp_path / "bad.toml"
        p.write_bytes(b"name = \"\xff\xfe\"\n")
    if arg == "spec":
        args = ["run", p, "-o", tmp_path / "out"]
    elif arg == "table":
        args = ["fit", p, "-o", tmp_path / "out"]
    elif arg == "points":
        args = ["reverse", p, "--spec", SAMPLES / "reverse" / "disc.toml", "-o", tmp_path / "out"]
    else:
        spec = tmp_path / "s.toml"
        spec.write_text((SAMPLES / "disc-translating-roller.toml").read_text().replace(
            'post = "linuxcnc"', f'post = "{p}"' if str(p).endswith(".toml") else f'post = "{p}/x.toml"'
            if path == "a folder" else f'post = "{p}"'))
        args = ["run", spec, "-o", tmp_path / "out"]
    before = snapshot(tmp_path)
    code, _, err = run_inproc(args)
    assert_clean_error(code, err)
    assert snapshot(tmp_path) == before
