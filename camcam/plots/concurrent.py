"""Plots rendered in a forked child process while the run goes on.

Rendering a figure with matplotlib (layout, text, Agg rasterising, PNG
compression) costs about as much as the rest of a `camcam run` outside the NC
fitting, and nothing else waits for it until the files are written.
:func:`render_later` forks the process: the child, which shares every array the
parent has computed, calls the plot function and sends its PNG bytes back
through a pipe; the parent goes on at once and collects the bytes with
:meth:`PendingPNG.result` (the output set and the report page do, when they
are written).  The child runs the very same function on the very same data as
an in-process call would, so the bytes are the same.

Fork is what makes this cheap (no data is pickled, matplotlib is already
imported), so it is used where the platform has it (Linux, the BSDs, macOS);
elsewhere the plot is drawn at once, in process.  A failure in the child
raises :class:`PlotError` with the child's traceback when the result is
collected.
"""

from __future__ import annotations

import os
import sys
import traceback
from typing import Callable

__all__ = ["PendingPNG", "PlotError", "render_later", "resolve"]

_OK, _FAILED = b"K", b"E"


class PlotError(RuntimeError):
    """A plot failed in the child process that drew it (not a user's input error)."""


class PendingPNG:
    """The PNG bytes of a plot being drawn in a child process; :meth:`result` waits for them."""

    def __init__(self, pid: int, fd: int, what: str) -> None:
        self._pid, self._fd, self._what = pid, fd, what
        self._data: bytes | None = None

    def result(self) -> bytes:
        """The PNG bytes (waits for the child the first time)."""
        if self._data is None:
            chunks = []
            with os.fdopen(self._fd, "rb") as fh:
                while chunk := fh.read(1 << 20):
                    chunks.append(chunk)
            os.waitpid(self._pid, 0)
            raw = b"".join(chunks)
            if raw[:1] != _OK:
                detail = raw[1:].decode("utf-8", "replace").strip() or "the child process ended without a result"
                raise PlotError(f"{self._what} failed: {detail}")
            self._data = raw[1:]
        return self._data


def resolve(data):
    """``data`` itself, or the bytes of a :class:`PendingPNG`."""
    return data.result() if isinstance(data, PendingPNG) else data


def render_later(plot: Callable[..., bytes], *args, **kwargs) -> PendingPNG | bytes:
    """``plot(*args, **kwargs)`` (PNG bytes), drawn in a forked child; the bytes themselves without fork.

    Examples
    --------
    >>> from camcam.motion.program import MotionProgram, Segment
    >>> from camcam.motion.standard import dwell
    >>> from camcam.plots.svaj import svaj_png
    >>> program = MotionProgram((Segment(dwell(), 0, 360, 0.0),), 60)
    >>> png = resolve(render_later(svaj_png, program, title="t"))
    >>> png == svaj_png(program, title="t")
    True
    """
    if not hasattr(os, "fork"):
        return plot(*args, **kwargs)
    for stream in (sys.stdout, sys.stderr):  # nothing buffered may be written twice
        stream.flush()
    read_fd, write_fd = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child: draw, send, and leave without running the parent's exit handlers
        status = 1
        try:
            os.close(read_fd)
            try:
                payload = _OK + plot(*args, **kwargs)
            except BaseException:  # noqa: BLE001 - every failure goes back to the parent
                payload = _FAILED + traceback.format_exc().encode("utf-8", "replace")
            with os.fdopen(write_fd, "wb") as fh:
                fh.write(payload)
            status = 0
        finally:
            os._exit(status)
    os.close(write_fd)
    return PendingPNG(pid, read_fd, getattr(plot, "__name__", "plot"))
