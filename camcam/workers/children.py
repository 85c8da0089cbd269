"""One-off worker processes: work done in forked children while the run goes on.

A `camcam run` has three kinds of work that nothing else waits for until the
files are written: drawing the plots (matplotlib: importing it alone costs
about as much as the NC fitting), writing the DXF and STL (ezdxf; the STL numpy), and
the material-removal check of the printed program.  On a machine with two or
more cores they can run beside the NC work:

* :func:`later` forks the process; the child, which shares every array the
  parent has computed (nothing is pickled on the way in), calls the function
  and sends its result back pickled through a pipe; the parent goes on at once
  and collects the result with :meth:`Pending.result`.
* :func:`parallel_map` shares a list's items between processes;
  :class:`ChildGroup` stops a group of children together.
* Children that stay and take jobs over pipes, :class:`~camcam.workers.servers.Server`
  (the plot worker) and :class:`~camcam.workers.servers.Prepared` (the drawing's
  child), are in :mod:`camcam.workers.servers`.

The child runs the very same function on the very same data as an in-process
call would, so the results are the same.  Fork is what makes this cheap, so it
is used where the platform has it (Linux, the BSDs, macOS); elsewhere every job
runs at once, in process.  A failure in a child raises :class:`ChildError`
with the child's traceback when the result is collected.

The cyclic garbage collector.  A child starts with every object its parent
had, and Python's collector would walk them all again in each of its full
collections (writing to their pages, which fork then copies).  So a child
freezes them at once (:func:`gc.freeze`, as the ``gc`` documentation
advises for fork without exec): they stay alive and are freed by their
reference counts as ever, but the collector walks only what the child makes
itself.  :func:`preload` imports with the collector paused and freezes what
it loaded, and the run's own process freezes its start-up objects once
(:func:`freeze_start_up`).  Measured with ``benchmarks/timeline.py``'s GC
column (2026-12-06, the four disc samples at 0.001 mm): 0.16–0.24 → 0.03–0.05
CPU s of collection over all of a run's processes, the same files (nothing is
computed differently, only collected less often).
"""

from __future__ import annotations

import gc
import importlib
import os
import pickle
import signal
import struct
import sys
import traceback
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any, Callable

from camcam.interrupts import SIGNALS, Interrupted

__all__ = ["ChildError", "Pending", "later", "resolve", "ChildGroup", "parallel_map", "ProcessMap", "call_target",
           "preload", "freeze_start_up", "single_process", "forking",
           # the child protocol camcam.workers.servers shares: a job's payload, its decoding, the fork, whole writes
           "child_payload", "decode_payload", "fork_child", "write_all", "PAYLOAD_OK", "PAYLOAD_FAILED"]

PAYLOAD_OK, PAYLOAD_FAILED = b"K", b"E"

#: False inside :func:`single_process` (per thread and task: a context variable).
_FORKING: ContextVar[bool] = ContextVar("camcam_forking", default=True)


def forking() -> bool:
    """Whether jobs go to forked children here: the platform has ``os.fork`` and no :func:`single_process` is on."""
    return _FORKING.get() and hasattr(os, "fork")


@contextmanager
def single_process():
    """Within the block every job of this module and :mod:`camcam.workers.servers` runs at once, in this process,
    as without ``os.fork``: the same calls on the same data, so the same results.

    For a process that is itself one of a pool's workers (a `camcam batch` task on a Dask worker): the pool
    already fills the cores, and a job's forked children would only share them with the other workers and
    import their modules (matplotlib, ezdxf, scipy) again for every job, where the worker imports them once.

    Examples
    --------
    >>> with single_process():
    ...     job = later(os.getpid)
    >>> job == os.getpid()
    True
    """
    token = _FORKING.set(False)
    try:
        yield
    finally:
        _FORKING.reset(token)


class ChildError(RuntimeError):
    """A job failed in the child process that ran it (not a user's input error)."""


def call_target(target: str, *args, **kwargs):
    """Call the function named ``"package.module:function"`` (imported here, in whichever process runs it)."""
    module, _, name = target.partition(":")
    return getattr(importlib.import_module(module), name)(*args, **kwargs)


def preload(*modules: str) -> None:
    """Import ``modules`` (a server child's first job: its later jobs then find them loaded).

    The collector is paused while they load (an import makes many objects and no garbage: the drawing's
    child spent 0.11 s in two full collections during its imports, which freed nothing) and what they
    loaded is frozen (see the module notes); it runs again afterwards if it ran before.
    """
    running = gc.isenabled()
    gc.disable()
    try:
        for name in modules:
            importlib.import_module(name)
    finally:
        gc.freeze()
        if running:
            gc.enable()


def freeze_start_up() -> None:
    """Freeze the objects of a process's start-up (its modules and settings) out of the collector's walks, once.

    A process that froze any already (a child: see the module notes) is left as it is, and so is a second
    call: objects made after the first (a batch's earlier specs) are collected as ever.
    """
    if gc.get_freeze_count() == 0:
        gc.freeze()


def child_payload(fn: Callable, args, kwargs) -> bytes:
    """PAYLOAD_OK + the pickled result, or PAYLOAD_FAILED + the pickled (exception or None, traceback text): every
    failure goes back to the parent, the exception itself when it pickles (a user's error stays one).

    A SIGINT, SIGTERM or SIGHUP the child receives is an :class:`~camcam.interrupts.Interrupted`
    for the parent, also when the job swallowed it (trimesh imports its optional parts under
    ``except BaseException``): the parent then stops as if it had been interrupted itself."""
    came: list[int] = []

    def handler(signum, frame):
        came.append(int(signum))
        raise Interrupted(signum)

    try:
        for s in SIGNALS:
            try:
                signal.signal(s, handler)
            except ValueError:  # not the main thread (a process that forks from a worker thread)
                break
        value = fn(*args, **kwargs)
        if came:
            raise Interrupted(came[0])
        return PAYLOAD_OK + pickle.dumps(value, protocol=pickle.HIGHEST_PROTOCOL)
    except BaseException as err:  # noqa: BLE001
        text = traceback.format_exc()
        try:
            data = pickle.dumps(err, protocol=pickle.HIGHEST_PROTOCOL)
            pickle.loads(data)  # an exception whose arguments do not rebuild it travels as text only
        except Exception:  # noqa: BLE001
            data = None
        return PAYLOAD_FAILED + pickle.dumps((data, text), protocol=pickle.HIGHEST_PROTOCOL)


def decode_payload(raw: bytes, what: str):
    """The child's result, or its failure raised here: the child's own exception (chained to a
    :class:`ChildError` with its traceback) when it pickled, else a :class:`ChildError`."""
    if raw[:1] == PAYLOAD_OK:
        return pickle.loads(raw[1:])
    if raw[:1] != PAYLOAD_FAILED:
        raise ChildError(f"{what} failed: the child process ended without a result")
    data, text = pickle.loads(raw[1:])
    where = ChildError(f"{what} failed: {text.strip()}")
    if data is not None:
        raise pickle.loads(data) from where
    raise where


def fork_child(child: Callable[[], None]) -> int:
    """Fork; the child runs ``child()`` and leaves without running the parent's exit handlers."""
    for stream in (sys.stdout, sys.stderr):  # nothing buffered may be written twice
        stream.flush()
    pid = os.fork()
    if pid == 0:
        gc.freeze()  # the parent's objects: alive, but never walked by this process's collector
        status = 1
        try:
            child()
            status = 0
        finally:
            os._exit(status)
    return pid


class Pending:
    """The result of a job running in a child process; :meth:`result` waits for it."""

    def __init__(self, fetch: Callable[[], Any], cancel: Callable[[], None] | None = None) -> None:
        self._fetch, self._cancel = fetch, cancel
        self._done = False
        self._value: Any = None
        self._error: BaseException | None = None

    def result(self):
        """The job's value (waits for the child the first time; raises :class:`ChildError` if it failed,
        or the child's own exception, every time it is asked)."""
        if not self._done:
            if self._fetch is None:
                raise ChildError("the job was cancelled")
            fetch, self._fetch, self._cancel = self._fetch, None, None  # the fetch reaps the child
            try:
                self._value = fetch()
            except BaseException as err:
                self._error = err
            self._done = True
        if self._error is not None:
            raise self._error
        return self._value

    def cancel(self) -> None:
        """Stop a job whose result is no longer wanted (a run that failed): its child is killed and
        reaped, so it neither lingers nor holds memory.  Nothing happens to a collected result."""
        if not self._done and self._cancel is not None:
            self._cancel()
        self._fetch = self._cancel = None


def resolve(data):
    """``data`` itself, or the result of a :class:`Pending`."""
    return data.result() if isinstance(data, Pending) else data


def later(fn: Callable, *args, **kwargs) -> Pending | Any:
    """``fn(*args, **kwargs)`` in a forked child (its result must pickle); the value itself without fork.

    Examples
    --------
    >>> resolve(later(sum, [2, 3]))
    5
    """
    if not forking():
        return fn(*args, **kwargs)
    read_fd, write_fd = os.pipe()

    def child():
        os.close(read_fd)
        with os.fdopen(write_fd, "wb") as fh:
            fh.write(child_payload(fn, args, kwargs))

    pid = fork_child(child)
    os.close(write_fd)

    def fetch():
        with os.fdopen(read_fd, "rb") as fh:
            raw = fh.read()
        os.waitpid(pid, 0)
        return decode_payload(raw, getattr(fn, "__name__", "job"))

    def cancel():
        os.kill(pid, signal.SIGKILL)
        os.close(read_fd)
        os.waitpid(pid, 0)

    return Pending(fetch, cancel)


class ChildGroup:
    """Jobs started in child processes that stop together: used as a ``with`` block, an exception
    leaving it kills and reaps every child of the group whose result was not collected.

    Examples
    --------
    >>> with ChildGroup() as group:
    ...     job = group.later(sum, [1, 2, 3])
    ...     resolve(job)
    6
    """

    def __init__(self) -> None:
        self._jobs: list[Pending] = []

    def later(self, fn: Callable, *args, **kwargs) -> Pending | Any:
        """:func:`later`, in this group."""
        job = later(fn, *args, **kwargs)
        if isinstance(job, Pending):
            self._jobs.append(job)
        return job

    def cancel(self) -> None:
        """Kill and reap every child of the group whose result was not collected."""
        for job in self._jobs:
            job.cancel()

    def __enter__(self) -> "ChildGroup":
        return self

    def __exit__(self, kind, err, tb) -> bool:
        if kind is not None:
            self.cancel()
        return False


_TICKET = struct.Struct("<I")  # one item's index on a parallel_map's ticket pipe
#: The most items a ticket pipe holds without a reader (64 KiB, a pipe's least size, of 4-byte tickets).
_MAX_TICKETS = 65536 // _TICKET.size


def _take(fn: Callable, items: list, tickets: int) -> dict:
    """{index: fn(items[index])} for every ticket this process takes off the pipe ``tickets`` until it is empty.

    The tickets were all written before any process reads, in 4-byte reads of a pipe that holds a multiple
    of 4 bytes, so each read takes one whole ticket, and each ticket goes to exactly one process."""
    done = {}
    while len(ticket := os.read(tickets, _TICKET.size)) == _TICKET.size:
        i = _TICKET.unpack(ticket)[0]
        done[i] = fn(items[i])
    return done


def parallel_map(fn: Callable, items, workers: int = 1) -> list:
    """``[fn(x) for x in items]``, the items shared by ``workers`` processes as each becomes free.

    The calling process and ``workers − 1`` forked children (which read ``fn``
    and the items from the memory they inherited; only their results are
    pickled back) take the items' indices in order off one pipe, the next as
    each finishes its last: items of unequal cost keep both busy (a barrel
    cam's passes took 0.81 and 1.10 s dealt round-robin, its radii 0.71 and
    0.49 s).  Each ``fn(x)`` is the same call as in a plain loop, whichever
    process makes it, so the results are the same, in the items' order;
    with ``workers`` ≤ 1, one item, or no fork, it is a plain loop.

    Examples
    --------
    >>> parallel_map(lambda x: x * x, range(5), workers=2)
    [0, 1, 4, 9, 16]
    """
    items = list(items)
    workers = max(1, min(int(workers), len(items)))
    if workers == 1 or not forking():
        return [fn(x) for x in items]
    if len(items) > _MAX_TICKETS:
        raise ValueError(f"parallel_map takes at most {_MAX_TICKETS} items, got {len(items)}")
    read_fd, write_fd = os.pipe()
    try:
        write_all(write_fd, b"".join(_TICKET.pack(i) for i in range(len(items))))
        os.close(write_fd)  # every ticket is in: an empty pipe is the end of the work
        write_fd = None
        with ChildGroup() as group:
            children = [group.later(_take, fn, items, read_fd) for _ in range(1, workers)]
            done = _take(fn, items, read_fd)
            for child in children:
                done.update(resolve(child))
    finally:
        os.close(read_fd)
        if write_fd is not None:
            os.close(write_fd)
    return [done[i] for i in range(len(items))]


@dataclass(frozen=True)
class ProcessMap:
    """:func:`parallel_map` as a mapper (:class:`camcam.toolpath.mapper.Mapper`): ``width`` processes, the
    calling one among them, share the items; what the NC stage hands the fitter.

    Examples
    --------
    >>> ProcessMap(2)(lambda x: x + 1, [1, 2, 3])
    [2, 3, 4]
    """

    width: int = 1

    def __call__(self, fn: Callable, items) -> list:
        return parallel_map(fn, items, self.width)


def write_all(fd: int, data: bytes) -> None:
    """Write all of ``data`` to ``fd`` (a pipe takes it in as many steps as it needs)."""
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view):]
