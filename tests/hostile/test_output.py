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


# --- issue 50, data loss: --force removes exactly an earlier run's own files, nothing else ----------------------

def _force_over(target, before_root):
    """A forced run over ``target`` must be refused with one line naming the folder, and leave every byte."""
    before = snapshot(before_root)
    with pytest.raises(OutputError) as e:
        _set(target, force=True).commit()
    assert str(e.value).startswith(f"{target}: ") and "\n" not in str(e.value)
    assert snapshot(before_root) == before
    return str(e.value)


def test_force_keeps_a_folder_put_where_a_listed_file_was(tmp_path):
    """Issue 50 item 1: `a.ngc` replaced by a folder holding the user's `mine.txt` was removed by --force."""
    target = tmp_path / "out"
    _earlier(target)
    (target / "a.ngc").unlink()
    (target / "a.ngc").mkdir()
    (target / "a.ngc" / "mine.txt").write_text("mine")
    assert "a.ngc is now a folder" in _force_over(target, tmp_path)


def test_force_keeps_a_listed_file_edited_since(tmp_path):
    """Issue 50 item 2: a listed file whose SHA-256 no longer matches the manifest is the user's now."""
    target = tmp_path / "out"
    _earlier(target)
    (target / "a.dxf").write_bytes(b"old a.dxf, edited in CAD")
    msg = _force_over(target, tmp_path)
    assert "a.dxf was changed after camcam wrote it" in msg
    (target / "a.dxf").write_bytes(b"old a.dxX")  # same size, other bytes: the hash decides, not the size
    assert "a.dxf was changed" in _force_over(target, tmp_path)


@pytest.mark.parametrize("what", ["listed file is a link", "folder link", "manifest is a link", "extra folder"])
def test_force_keeps_links_and_folders_it_did_not_write(tmp_path, what):
    """A link in place of a listed file (to the user's own file, same bytes) or an extra folder is not camcam's."""
    target = tmp_path / "out"
    _earlier(target)
    mine = tmp_path / "mine"
    mine.mkdir()
    if what == "listed file is a link":
        (mine / "a.ngc").write_bytes(b"old a.ngc")
        (target / "a.ngc").unlink()
        (target / "a.ngc").symlink_to(mine / "a.ngc")
    elif what == "folder link":
        (target / "linked").symlink_to(mine)
    elif what == "manifest is a link":
        os.replace(target / MANIFEST, mine / MANIFEST)
        (target / MANIFEST).symlink_to(mine / MANIFEST)
    else:
        (target / "sub").mkdir()
    _force_over(target, tmp_path)


@pytest.mark.parametrize("manifest", [b"{", b'{"files": 3}', b'{"files": [{"name": "../x", "bytes": 1, "sha256": "0"}]}',
                                      b"\xff\xfe"])
def test_an_unreadable_manifest_is_named_as_such(tmp_path, manifest):
    """Issue 50 item 14: a corrupt or tampered manifest is refused, and the line says the manifest is unreadable
    (it used to say camcam 'did not write' its own files)."""
    target = tmp_path / "out"
    _earlier(target)
    (target / MANIFEST).write_bytes(manifest)
    msg = _force_over(target, tmp_path)
    assert f"its {MANIFEST} is unreadable" in msg and "did not write" not in msg


def test_force_replaces_an_earlier_set_with_sub_folders(tmp_path):
    """Issue 50 item 11: a batch's set (`spec/file` names) is an earlier run's set that --force replaces."""
    target = tmp_path / "out"
    _earlier(target, ("s1/a.ngc", "s2/a.ngc", "summary.csv"))
    with pytest.raises(OutputError, match="add --force"):
        _set(target, ("s1/a.ngc",)).commit()
    _set(target, ("s1/a.ngc",), force=True).commit()
    assert snapshot(target)["s1/a.ngc"] == b"new s1/a.ngc" and "s2" not in os.listdir(target)
    (target / "s1" / "mine.txt").write_text("mine")
    assert "s1/mine.txt" in _force_over(target, tmp_path)


def test_cli_force_keeps_a_folder_in_place_of_the_program(tmp_path):
    """Issue 50 item 1 as reported, through the command line."""
    out = tmp_path / "m5"
    assert run_inproc(["motion", DEMO, "-o", out])[0] == 0
    victim = sorted(p for p in os.listdir(out) if p != MANIFEST)[0]
    os.remove(out / victim)
    (out / victim).mkdir()
    (out / victim / "mine.txt").write_text("mine")
    before = snapshot(tmp_path)
    code, _, err = run_inproc(["motion", DEMO, "-o", out, "--force"])
    assert f"{victim} is now a folder" in assert_clean_error(code, err)
    assert snapshot(tmp_path) == before
