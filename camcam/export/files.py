"""Writing an output folder all or nothing, and a single file atomically.

A command collects its outputs in an :class:`OutputSet` and commits them at
the end.  :meth:`OutputSet.commit`

1. checks the target folder (:meth:`OutputSet.check`): it may be missing,
   empty, or hold exactly the files an earlier camcam run listed in its
   manifest — then only with ``force`` (``--force``), and those files are
   replaced.  Anything else (a file, files camcam did not write, the current
   folder) is refused with one line;
2. takes a lock, ``.<name>.camcam-lock`` beside the target (``flock``; the
   kernel releases it when the process dies, even by SIGKILL);
3. clears what a killed run left beside the target (``.<name>.camcam-new-*``
   folders; an ``.<name>.camcam-old-*`` folder is put back if the target is
   missing);
4. writes every file and the manifest ``camcam-manifest.json`` (name, size
   and SHA-256 of each file) into a fresh folder ``.<name>.camcam-new-<hex>``
   beside the target, and syncs them to disk;
5. publishes in one step: a rename onto the target when it is missing or
   empty, else an atomic exchange of the two folders (Linux ``renameat2``
   with ``RENAME_EXCHANGE``) after which the earlier set, now in the temporary
   folder, is removed.  Where the exchange is not supported the target is
   first renamed to ``.<name>.camcam-old-<hex>`` (the next run puts it back
   if the process dies between the two renames).

Ctrl-C and termination signals are held back over step 5 and over every
removal of a temporary folder, so a run ends with the target either as it was
or complete.  Every OS error is one :class:`~camcam.errors.OutputError` line
naming the path and the reason.  :class:`DiskLog` records what is on disk for
the interrupt message.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import secrets
import shutil
from pathlib import Path

from camcam import __version__
from camcam.errors import OutputError
from camcam.inputs import os_reason
from camcam.interrupts import deferred
from camcam.workers import Pending, resolve

__all__ = ["OutputSet", "DiskLog", "atomic_write", "MANIFEST", "read_manifest"]

#: The manifest every output folder gets: what the run wrote.
MANIFEST = "camcam-manifest.json"

_NEW = ".camcam-new-"
_OLD = ".camcam-old-"
_LOCK = ".camcam-lock"


class DiskLog:
    """What a command has put on disk so far, for the one line an interrupt prints.

    Examples
    --------
    >>> DiskLog().describe()
    'nothing was written'
    """

    def __init__(self) -> None:
        self.target: str | None = None
        self.written: list[str] = []
        self.complete = False

    def describe(self) -> str:
        if self.complete:
            what = f"{len(self.written)} files, listed in its {MANIFEST}" if self.written and self.written[-1] == MANIFEST else \
                f"{len(self.written)} file(s)"
            return f"{self.target} holds this run's complete output ({what})"
        if self.target is not None:
            return f"nothing was written; {self.target} is as it was"
        return "nothing was written"


def _fail(shown: str, doing: str, err: OSError) -> OutputError:
    return OutputError(f"{shown}: {doing}: {os_reason(err)}")


def _plain_name(name: str) -> bool:
    return bool(name) and name not in (".", "..") and "/" not in name and "\0" not in name


def _output_name(name: str) -> bool:
    """A plain file name, or ``folder/file`` of two plain names (one level of sub-folders: a batch's specs)."""
    parts = name.split("/")
    return len(parts) <= 2 and all(_plain_name(p) for p in parts)


def read_manifest(folder: str | Path) -> dict[str, tuple[int, str]] | None:
    """What an earlier run's manifest in ``folder`` lists: ``{name: (bytes, sha256 hex)}``, or
    ``None`` when the folder has no manifest.

    Raises
    ------
    OutputError
        The manifest is there but camcam cannot read it (not JSON, not camcam's shape, a
        name that leaves the folder): the folder is refused, and the message says why.
    """
    path = Path(folder) / MANIFEST
    if not os.path.lexists(path):
        return None
    move = "camcam replaces a folder only when its manifest lists its files: move the folder away or choose another"
    if path.is_symlink() or not path.is_file():
        raise OutputError(f"{folder}: its {MANIFEST} is unreadable (it is not a regular file); {move}")
    try:
        doc = json.loads(path.read_bytes().decode("utf-8"))
        listed = {f["name"]: (int(f["bytes"]), str(f["sha256"])) for f in doc["files"]}
    except OSError as err:
        raise _fail(str(folder), f"cannot read its {MANIFEST}", err) from None
    except (ValueError, KeyError, TypeError):
        raise OutputError(f"{folder}: its {MANIFEST} is unreadable (it is not the JSON camcam writes); {move}") from None
    bad = [n for n in listed if not (isinstance(n, str) and _output_name(n) and n.split("/")[0] != MANIFEST)]
    if bad:
        raise OutputError(f"{folder}: its {MANIFEST} is unreadable (it lists {bad[0]!r}, not a file name camcam "
                          f"writes); {move}")
    return listed


def _sha256(path: Path) -> str:
    import hashlib  # here: only checking an earlier set needs it, and every command imports this module

    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _earlier_set_problem(target: Path, listed: dict[str, tuple[int, str]]) -> str | None:
    """Why ``target`` is not exactly the set its manifest lists (``None``: it is).

    Every entry is looked at without following links: a listed name must be a regular file
    with the size and SHA-256 the manifest records (a file edited since camcam wrote it is
    the user's now); a folder must be one that listed names sit in; nothing else may be
    there.  ``--force`` removes only what passes this check.
    """
    folders = {n.split("/")[0] for n in listed if "/" in n}
    foreign: list[str] = []
    for root, dirs, files in os.walk(target):
        rel = os.path.relpath(root, target)
        for d in sorted(dirs):
            name = d if rel == "." else f"{rel}/{d}"
            if name in listed:
                return f"{name} is now a folder, where camcam wrote a file; move it away or choose another folder"
            if os.path.islink(os.path.join(root, d)) or name not in folders:
                foreign.append(name)
        dirs[:] = [d for d in dirs if (d if rel == "." else f"{rel}/{d}") in folders
                   and not os.path.islink(os.path.join(root, d))]
        for f in sorted(files):
            name = f if rel == "." else f"{rel}/{f}"
            path = Path(root) / f
            if name == MANIFEST:
                continue
            if name not in listed or path.is_symlink() or not path.is_file():
                foreign.append(name)
                continue
            size, sha = listed[name]
            if path.stat().st_size != size or _sha256(path) != sha:
                return (f"{name} was changed after camcam wrote it (its SHA-256 no longer matches {MANIFEST}); "
                        "--force replaces only camcam's own files: move it away or choose another folder")
    if foreign:
        return (f"holds files its {MANIFEST} does not list ({_few(sorted(foreign))}); "
                "camcam replaces a folder only when it holds nothing but an earlier run's files")
    return None


def _few(names: list[str], k: int = 3) -> str:
    shown = ", ".join(names[:k])
    return shown + (f" and {len(names) - k} more" if len(names) > k else "")


def _nearest_existing(path: Path) -> Path:
    a = path
    while not os.path.lexists(a) and a != a.parent:
        a = a.parent
    return a


def _fsync_dir(path: Path) -> None:
    fd = os.open(path, os.O_RDONLY | os.O_DIRECTORY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _write_file(path: Path, data: bytes) -> None:
    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_CLOEXEC, 0o666)
    try:
        view = memoryview(data)
        while view:
            view = view[os.write(fd, view):]
        os.fsync(fd)
    finally:
        os.close(fd)


def _remove(path: Path) -> None:
    """Remove a temporary file or folder, signals held back (never half-removed by a Ctrl-C)."""
    with deferred():
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path, ignore_errors=True)
        else:
            try:
                path.unlink()
            except FileNotFoundError:
                pass


_RENAME_EXCHANGE = 2


def _swap(a: Path, b: Path) -> bool:
    """Swap folders ``a`` and ``b`` in one step (Linux ``renameat2(RENAME_EXCHANGE)``); False where
    the kernel or file system cannot."""
    import ctypes  # here: only a folder swap needs it, and every command imports this module

    try:
        renameat2 = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return False
    if renameat2(-100, os.fsencode(a), -100, os.fsencode(b), _RENAME_EXCHANGE) == 0:  # -100: AT_FDCWD
        return True
    code = ctypes.get_errno()
    if code in (errno.EINVAL, errno.ENOSYS, errno.EOPNOTSUPP, errno.ENOTSUP):
        return False
    raise OSError(code, os.strerror(code), str(b))


def _exchange(a: Path, b: Path, old: Path) -> None:
    """Swap folders ``a`` and ``b``: atomically, or else in two renames through ``old`` (a run
    killed between them leaves ``old``, which the next run puts back)."""
    if _swap(a, b):
        return
    os.rename(b, old)
    os.rename(a, b)
    os.rename(old, a)


class _Lock:
    """An exclusive, non-blocking ``flock`` on ``path`` (created, and removed when released)."""

    def __init__(self, path: Path, shown: str) -> None:
        self.path, self.shown, self.fd = path, shown, -1

    def __enter__(self) -> "_Lock":
        while True:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o666)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except BlockingIOError:
                os.close(fd)
                raise OutputError(f"{self.shown}: another camcam run is writing it (lock {self.path.name} is held); "
                                  "try again when that run has finished") from None
            try:
                same = os.fstat(fd).st_ino == os.stat(self.path).st_ino
            except FileNotFoundError:
                same = False
            if same:  # not a lock file its last holder removed while we waited to open it
                self.fd = fd
                return self
            os.close(fd)

    def __exit__(self, *exc) -> None:
        with deferred():
            try:
                self.path.unlink()
            except FileNotFoundError:
                pass
            os.close(self.fd)


class OutputSet:
    """Files to publish together as the folder ``directory``.

    Parameters
    ----------
    directory : path
        The target folder.
    force : bool
        Replace an earlier camcam run's files there (they are removed).
    log : DiskLog, optional
        Told what is on disk, for an interrupt's message.
    command : str
        Recorded in the manifest.
    checkpoint : callable, optional
        Called before anything is written (e.g. :meth:`camcam.interrupts.Watch.checkpoint`,
        which raises an interrupt a library swallowed).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp()) / "out"
    >>> out = OutputSet(d)
    >>> out.add("a.txt", "hello\\n")
    >>> [p.name for p in out.commit()], sorted(p.name for p in d.iterdir())
    (['a.txt'], ['a.txt', 'camcam-manifest.json'])
    """

    def __init__(self, directory: str | Path, *, force: bool = False, log: DiskLog | None = None,
                 command: str = "", checkpoint=None) -> None:
        self.directory = Path(directory)
        self.checkpoint = checkpoint
        self.force = force
        self.log = log if log is not None else DiskLog()
        self.command = command
        self._files: dict[str, bytes] = {}
        self._was_free = False  # the first check found no earlier set: one found later is another run's
        self.log.target = str(self.directory)

    def add(self, name: str, data: bytes | str | Pending) -> None:
        """Add a file; a plot still being drawn (:class:`Pending`) is collected at :meth:`commit`."""
        if not _output_name(name) or name.split("/")[0] == MANIFEST:
            raise ValueError(f"output name must be a plain file name (or folder/file) other than {MANIFEST}, "
                             f"got {name!r}")
        self._files[name] = data.encode("utf-8") if isinstance(data, str) else data if isinstance(data, Pending) \
            else bytes(data)

    @property
    def names(self) -> list[str]:
        return list(self._files)

    def contents(self) -> dict[str, bytes]:
        """The files added so far as bytes, by name (plots still being drawn are collected first),
        e.g. to send them to another process to be written."""
        self._files = {name: resolve(data) for name, data in self._files.items()}
        return dict(self._files)

    @property
    def _target(self) -> Path:
        return Path(os.path.realpath(os.path.abspath(self.directory)))

    def manifest(self) -> bytes:
        """The manifest's bytes (deterministic: no times, no ids)."""
        import hashlib  # here: only an output folder's manifest needs it, and every command imports this module

        files = [{"name": n, "bytes": len(d), "sha256": hashlib.sha256(d).hexdigest()} for n, d in sorted(self._files.items())]
        doc = {"camcam": __version__, "command": self.command, "files": files}
        return (json.dumps(doc, indent=2) + "\n").encode("utf-8")

    def check(self) -> list[str] | None:
        """Raise :class:`OutputError` if the target cannot take this set; return the earlier run's
        file names it holds (``[]``: an empty folder, ``None``: no folder yet)."""
        shown, target = str(self.directory), self._target
        try:
            if not os.path.lexists(target):
                anc = _nearest_existing(target.parent)
                if not anc.is_dir():
                    raise OutputError(f"{shown}: cannot create the folder: {anc} is not a folder")
                self._was_free = True
                return None
            if not target.is_dir():
                raise OutputError(f"{shown}: exists and is not a folder")
            cwd = Path(os.path.realpath(os.getcwd()))
            if target == cwd or target in cwd.parents:
                raise OutputError(f"{shown}: is the current folder or holds it; write into a new folder")
            entries = sorted(os.listdir(target))
        except OutputError:
            raise
        except OSError as err:
            raise _fail(shown, "cannot use it as the output folder", err) from None
        if not entries:
            self._was_free = True
            return []
        try:
            earlier = read_manifest(self.directory)
            if earlier is None:
                raise OutputError(f"{shown}: holds files camcam did not write ({_few(entries)}); "
                                  "choose a new or empty folder")
            problem = _earlier_set_problem(target, earlier)
        except OSError as err:
            if isinstance(err, OutputError):
                raise
            raise _fail(shown, "cannot read the earlier run's files", err) from None
        if problem is not None:
            raise OutputError(f"{shown}: {problem}")
        if self._was_free and not self.force:
            raise OutputError(f"{shown}: another camcam run published its files there while this one ran; "
                              "add --force to replace them, or choose another folder")
        if not self.force:
            raise OutputError(f"{shown}: holds the files of an earlier run (listed in its {MANIFEST}); "
                              "add --force to replace them, or choose another folder")
        return sorted(earlier)

    def commit(self) -> list[Path]:
        """Publish every file and the manifest as the target folder, all or nothing."""
        self._files = {name: resolve(data) for name, data in self._files.items()}  # every plot drawn before a byte is written
        if self.checkpoint is not None:
            self.checkpoint()
        shown, target = str(self.directory), self._target
        self.check()
        parent, name = target.parent, target.name
        created: list[Path] = []
        try:
            missing = []
            a = parent
            while not os.path.lexists(a):
                missing.append(a)
                a = a.parent
            for d in reversed(missing):
                os.mkdir(d)
                created.append(d)
        except OSError as err:
            self._undo_parents(created)
            raise _fail(shown, "cannot create the folder", err) from None
        try:
            with _Lock(parent / f".{name}{_LOCK}", shown):
                self._clear_orphans(parent, name, target)
                earlier = self.check()
                return self._publish(parent, name, target, earlier)
        except OSError as err:
            if isinstance(err, OutputError):
                raise
            raise _fail(shown, "cannot write the output folder", err) from None
        finally:
            if not self.log.complete:
                self._undo_parents(created)

    @staticmethod
    def _undo_parents(created: list[Path]) -> None:
        for d in reversed(created):
            try:
                os.rmdir(d)
            except OSError:
                break

    @staticmethod
    def _clear_orphans(parent: Path, name: str, target: Path) -> None:
        """Under the lock, a temporary folder of this target belongs to a run that was killed."""
        olds = []
        for entry in sorted(os.listdir(parent)):
            if entry.startswith(f".{name}{_NEW}"):
                _remove(parent / entry)
            elif entry.startswith(f".{name}{_OLD}"):
                olds.append(parent / entry)
        for old in olds:
            if not os.path.lexists(target):
                with deferred():
                    os.rename(old, target)  # killed between the two renames: the earlier set goes back
            else:
                _remove(old)

    def _publish(self, parent: Path, name: str, target: Path, earlier: list[str] | None) -> list[Path]:
        token = secrets.token_hex(6)
        tmp = parent / f".{name}{_NEW}{token}"
        os.mkdir(tmp, 0o777)
        try:
            if earlier is not None:
                os.chmod(tmp, os.stat(target).st_mode & 0o7777)
            for n, data in self._files.items():
                if "/" in n:
                    (tmp / n).parent.mkdir(exist_ok=True)
                _write_file(tmp / n, data)
            _write_file(tmp / MANIFEST, self.manifest())
            _fsync_dir(tmp)
            with deferred():
                if earlier is None or earlier == []:
                    os.rename(tmp, target)
                else:
                    _exchange(tmp, target, parent / f".{name}{_OLD}{token}")
                _fsync_dir(parent)
                self.log.written = list(self._files) + [MANIFEST]
                self.log.complete = True
        finally:
            _remove(tmp)
        return [target / n for n in self._files]


def atomic_write(path: str | Path, data: bytes | str, log: DiskLog | None = None) -> Path:
    """Write one file through a temporary file beside it and a rename (a file that
    exists is replaced in one step).  Errors are one :class:`OutputError` line."""
    path = Path(path)
    shown = str(path)
    data = data.encode("utf-8") if isinstance(data, str) else bytes(data)
    if log is not None:
        log.target = shown
    if os.path.isdir(path):
        raise OutputError(f"{shown}: is a folder; expected a file name")
    if os.path.lexists(path) and not os.path.isfile(path):
        raise OutputError(f"{shown}: exists and is not a regular file")
    parent = path.parent if str(path.parent) else Path(".")
    anc = _nearest_existing(parent)
    if not anc.is_dir():
        raise OutputError(f"{shown}: cannot create it: {anc} is not a folder")
    tmp = parent / f".{path.name}{_NEW}{secrets.token_hex(6)}"
    try:
        parent.mkdir(parents=True, exist_ok=True)
        for entry in os.listdir(parent):  # files a killed run left (SIGKILL cannot be caught)
            if entry.startswith(f".{path.name}{_NEW}"):
                _remove(parent / entry)
        try:
            _write_file(tmp, data)
            with deferred():
                os.replace(tmp, path)
                if log is not None:
                    log.written, log.complete = [path.name], True
        finally:
            _remove(tmp)
    except OSError as err:
        raise _fail(shown, "cannot write", err) from None
    return path
