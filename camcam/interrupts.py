"""Ctrl-C and termination signals: one line, a known exit status, nothing half-written.

:class:`Watch` is what ``camcam``'s ``main`` runs under: SIGINT, SIGTERM and
SIGHUP raise :class:`Interrupted` (a :class:`KeyboardInterrupt`) in the main
thread and are remembered, so an interrupt that a library swallows (trimesh
imports its optional parts under ``except BaseException``) is raised again at
the next :meth:`Watch.checkpoint` — before anything is published.
:func:`deferred` holds the signals back over a step that must not be cut in
half (publishing an output folder, removing a temporary one).
:func:`import_guard` covers the imports of the command line itself.

Only the main thread can install handlers; elsewhere these are no-ops.
"""

from __future__ import annotations

import signal
import sys
import threading
from contextlib import contextmanager
from typing import Iterator

__all__ = ["Interrupted", "Watch", "deferred", "import_guard", "signal_name", "exit_status"]

#: The signals that end a command cleanly (temporary files removed, one line, status 128 + n).
SIGNALS = tuple(s for s in (signal.SIGINT, getattr(signal, "SIGTERM", None), getattr(signal, "SIGHUP", None)) if s is not None)


def _main_thread() -> bool:
    return threading.current_thread() is threading.main_thread()


def signal_name(signum: int) -> str:
    """``"SIGTERM"`` for 15."""
    try:
        return signal.Signals(signum).name
    except ValueError:
        return f"signal {signum}"


def exit_status(signum: int) -> int:
    """The shell's status for a command ended by ``signum``: 128 + n (130 for Ctrl-C).

    >>> exit_status(signal.SIGINT)
    130
    """
    return 128 + int(signum)


class Interrupted(KeyboardInterrupt):
    """Ctrl-C or a termination signal, raised in the main thread."""

    def __init__(self, signum: int = signal.SIGINT) -> None:
        super().__init__(signal_name(signum))
        self.signum = int(signum)

    def __reduce__(self):
        # pickled as its signal: an interrupt in a child process (camcam.workers) is raised in the parent
        return (type(self), (self.signum,))


class Watch:
    """Turn SIGINT/SIGTERM/SIGHUP into :class:`Interrupted` and remember that one came.

    Examples
    --------
    >>> with Watch() as w:
    ...     w.checkpoint()          # nothing came: returns
    >>> w.signum is None
    True
    """

    def __init__(self) -> None:
        self.signum: int | None = None
        self._old: dict[int, object] = {}

    def _handler(self, signum, frame) -> None:
        if self.signum is None:
            self.signum = int(signum)
        raise Interrupted(signum)

    def __enter__(self) -> "Watch":
        if _main_thread():
            for s in SIGNALS:
                self._old[s] = signal.signal(s, self._handler)
        return self

    def __exit__(self, *exc) -> None:
        for s, old in self._old.items():
            signal.signal(s, old)
        self._old.clear()

    def checkpoint(self) -> None:
        """Raise :class:`Interrupted` again if a signal came and somebody swallowed it."""
        if self.signum is not None:
            raise Interrupted(self.signum)


@contextmanager
def deferred() -> Iterator[list[int]]:
    """Hold SIGINT/SIGTERM/SIGHUP back until the block ends, then deliver the first one.

    The block gets the list of the signals held so far: a long call into native code (a HiGHS
    solve, :mod:`camcam.optimize.lp`) polls it from its progress callback and stops early, so
    the signal is answered as soon as the call returns.

    Examples
    --------
    >>> with deferred() as came:
    ...     came
    []
    """
    if not _main_thread():
        yield []
        return
    came: list[int] = []

    def hold(signum, frame):
        came.append(int(signum))

    old = {s: signal.signal(s, hold) for s in SIGNALS}
    try:
        yield came
    finally:
        for s, h in old.items():
            signal.signal(s, h)
        if came:
            handler = old[came[0]]
            if callable(handler):
                handler(came[0], None)
            elif handler == signal.SIG_DFL:
                signal.raise_signal(came[0])


@contextmanager
def import_guard(stream=None) -> Iterator[None]:
    """Ctrl-C while the command line loads its modules: one line, exit status 130.

    Python's default would print a traceback, and a library that swallows the
    interrupt would let the command run on.  Inactive when SIGINT already has
    a handler of its own (camcam imported by another program).
    """
    if not _main_thread() or signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        yield
        return
    watch = Watch()
    old = signal.signal(signal.SIGINT, watch._handler)
    try:
        yield
    except KeyboardInterrupt:
        watch.signum = watch.signum or int(signal.SIGINT)
    finally:
        signal.signal(signal.SIGINT, old)
    if watch.signum is not None:
        print("camcam: interrupted while starting; nothing was written", file=stream or sys.stderr)
        raise SystemExit(exit_status(watch.signum))
