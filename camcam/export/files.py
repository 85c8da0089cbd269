"""Writing output files all or nothing.

Every command collects its outputs in an :class:`OutputSet` and commits them
at the end: each file is written to a hidden temporary file in the target
directory and renamed into place only when all were written.  An error or
Ctrl-C before that leaves the directory as it was.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

from camcam.plots.concurrent import PendingPNG, resolve

__all__ = ["OutputSet", "atomic_write"]


def atomic_write(path: str | Path, data: bytes | str) -> Path:
    """Write ``data`` to ``path`` through a temporary file and a rename."""
    out = OutputSet(Path(path).parent)
    out.add(Path(path).name, data)
    return out.commit()[0]


class OutputSet:
    """Files to write into ``directory`` together.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> out = OutputSet(d)
    >>> out.add("a.txt", "hello\\n")
    >>> [p.name for p in out.commit()]
    ['a.txt']
    """

    def __init__(self, directory: str | Path) -> None:
        self.directory = Path(directory)
        self._files: dict[str, bytes] = {}

    def add(self, name: str, data: bytes | str | PendingPNG) -> None:
        """Add a file; a plot still being drawn (:class:`PendingPNG`) is collected at :meth:`commit`."""
        if "/" in name or name in ("", ".", ".."):
            raise ValueError(f"output name must be a plain file name, got {name!r}")
        self._files[name] = data.encode("utf-8") if isinstance(data, str) else data if isinstance(data, PendingPNG) else bytes(data)

    @property
    def names(self) -> list[str]:
        return list(self._files)

    def contents(self) -> dict[str, bytes]:
        """The files added so far as bytes, by name (plots still being drawn are collected first),
        e.g. to send them to another process to be written."""
        self._files = {name: resolve(data) for name, data in self._files.items()}
        return dict(self._files)

    def commit(self) -> list[Path]:
        """Write every file; on any failure remove what was written and re-raise."""
        self._files = {name: resolve(data) for name, data in self._files.items()}  # every plot drawn before a byte is written
        self.directory.mkdir(parents=True, exist_ok=True)
        temps: list[tuple[str, Path]] = []
        try:
            for name, data in self._files.items():
                fd, tmp = tempfile.mkstemp(prefix=f".{name}.", suffix=".tmp", dir=self.directory)
                temps.append((name, Path(tmp)))
                with os.fdopen(fd, "wb") as fh:
                    fh.write(data)
                os.chmod(tmp, 0o644)
            done = []
            for name, tmp in temps:
                final = self.directory / name
                os.replace(tmp, final)
                done.append(final)
            return done
        except BaseException:
            for _, tmp in temps:
                tmp.unlink(missing_ok=True)
            raise
