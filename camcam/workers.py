"""Worker processes: work done in forked children while the run goes on (the plot workers among them).

A `camcam run` has three kinds of work that nothing else waits for until the
files are written: drawing the plots (matplotlib: importing it alone costs
about as much as the NC fitting), writing the DXF and STL (ezdxf, trimesh), and
the material-removal check of the printed program.  On a machine with two or
more cores they can run beside the NC work:

* :func:`later` forks the process; the child, which shares every array the
  parent has computed (nothing is pickled on the way in), calls the function
  and sends its result back pickled through a pipe; the parent goes on at once
  and collects the result with :meth:`Pending.result`.
* :func:`parallel_map` shares a list's items between processes;
  :class:`ChildGroup` stops a group of children together.
* Children that stay and take jobs over pipes: :class:`Server` (the plot
  worker) and :class:`Prepared` (the drawing's child), below ("Children that
  stay").

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
from dataclasses import dataclass
from typing import Any, Callable

from camcam.interrupts import SIGNALS, Interrupted

__all__ = ["ChildError", "Pending", "later", "resolve", "ChildGroup", "parallel_map", "call_target", "preload",
           "freeze_start_up", "ProcessMap", "Server", "Prepared", "Gate"]

PAYLOAD_OK, PAYLOAD_FAILED = b"K", b"E"


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
    if not hasattr(os, "fork"):
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
    if workers == 1 or not hasattr(os, "fork"):
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


# -- Children that stay --------------------------------------------------------------------------------
# Forked children that stay and take jobs over pipes: the plot server and the drawing's prepared child.
#
# * :class:`Server` forks one child that runs a first batch of jobs on the
#   memory it inherited, then serves later jobs sent to it (pickled), one at a
#   time, importing the modules they name itself.  So the parent never imports
#   matplotlib: the server imports it once, on the other core.  `camcam run`
#   starts its plot server before anything but numpy's import, which the server
#   inherits (matplotlib's import then runs beside the run's own imports); the
#   cam and the plots' data go to it pickled.
# * :class:`Prepared` forks one child that imports modules at once and runs one
#   job sent to it later, which, unlike a server's, may fork children of its
#   own.  `camcam run` starts one before the NC step: it imports ezdxf and
#   scipy (the DXF's splines, the material check's k-d trees) beside the NC
#   work, then takes the printed program and writes the drawing while the
#   material check runs in its children, which inherit those modules.
#
# Requests and replies travel as frames: an 8-byte length, then the pickled
# body (an empty frame ends a child's jobs).  The children run their jobs as
# :mod:`camcam.workers` runs a :func:`~camcam.workers.later` job (the same
# payload, failures and interrupts); without ``os.fork`` every job runs at once,
# in process.



_FRAME = struct.Struct("<Q")  # the length of one frame's body


def _frame(body: bytes) -> bytes:
    """``body`` as one frame: its length, then itself."""
    return _FRAME.pack(len(body)) + body


def _read_exactly(fd: int, n: int) -> bytes:
    """``n`` bytes from ``fd``, fewer only at end of file."""
    parts, got = [], 0
    while got < n:
        chunk = os.read(fd, min(n - got, 1 << 20))
        if not chunk:
            break
        parts.append(chunk)
        got += len(chunk)
    return b"".join(parts)


def _read_frame(fd: int) -> bytes:
    """One frame's body from ``fd`` (b"" for an empty frame or end of file)."""
    head = _read_exactly(fd, _FRAME.size)
    if len(head) < _FRAME.size:
        return b""
    return _read_exactly(fd, _FRAME.unpack(head)[0])


class _ServerPipes:
    """The server child's two pipe ends, each served by a thread of its own.

    A reader thread takes every request frame off the request pipe as soon as
    it arrives, so the parent's (blocking) write of a request returns at once,
    whatever job the child is busy with: a pickled cam is larger than a pipe
    holds, and the parent, busy with the NC step, must not wait for the child's
    current job to end.  A writer thread writes the replies in order, blocking
    while the reply pipe is full, so the next job starts while the parent has
    not yet read the last reply (a plot's PNG alone fills a pipe).  A parent
    that is gone (a broken pipe) ends the writing; the jobs then end with the
    request pipe.  The threads live only in the server child, whose jobs do not fork.
    """

    def __init__(self, requests: int, replies: int) -> None:
        import queue
        import threading

        self._requests, self._replies = requests, replies  # the two pipe ends (file descriptors)
        self.jobs: queue.SimpleQueue = queue.SimpleQueue()  # request bodies; None at the end
        self._out: queue.SimpleQueue = queue.SimpleQueue()  # reply bodies; None at the end
        self._reader = threading.Thread(target=self._read, name="camcam-server-requests", daemon=True)
        self._writer = threading.Thread(target=self._write, name="camcam-server-replies", daemon=True)

    def _read(self) -> None:
        try:
            while body := _read_frame(self._requests):  # an empty frame (or the pipe closed): done
                self.jobs.put(body)
        finally:
            self.jobs.put(None)

    def _write(self) -> None:
        broken = False
        while (data := self._out.get()) is not None:
            if broken:
                continue
            try:
                write_all(self._replies, _frame(data))
            except OSError:  # the parent closed its end: nobody reads any more replies
                broken = True

    def reply(self, data: bytes) -> None:
        """Queue one reply (written in order by the writer thread)."""
        self._out.put(data)

    def __enter__(self) -> "_ServerPipes":
        self._reader.start()
        self._writer.start()
        return self

    def __exit__(self, *exc) -> bool:
        self._out.put(None)
        self._writer.join()  # every reply written (the reader ends with the request pipe)
        return False


def _reap(pid: int, *fds: int | None) -> None:
    """Close the parent's pipe ends ``fds`` (None: closed already) and wait for child ``pid``."""
    for fd in fds:
        if fd is not None:
            os.close(fd)
    os.waitpid(pid, 0)


def _pipes() -> tuple[tuple[int, int], tuple[int, int]]:
    """A request pipe and a reply pipe, ((read, write), (read, write)), each widened (:func:`_widen`)."""
    req, rep = os.pipe(), os.pipe()
    _widen(req[1])
    _widen(rep[1])
    return req, rep


def _widen(fd: int) -> None:
    """Let a pipe hold 1 MiB where the platform allows it (Linux): fewer wake-ups for a large message."""
    try:
        import fcntl

        fcntl.fcntl(fd, fcntl.F_SETPIPE_SZ, 1 << 20)
    except (ImportError, AttributeError, OSError):
        pass  # only an optimisation: the pipe's own size works, in more steps


class Gate:
    """A signal to one waiting process from whichever of the others gives it first: a pipe.

    A :class:`Server` given a gate waits at it before its first submitted job
    (:meth:`wait`); :meth:`open` lets it go on, from any process that holds
    the gate (one forked after it was made), once: the first byte written ends
    the wait.  The wait also ends when every process that could open it has
    let go of its end (ended, or opened it), so a process that fails cannot
    leave the waiter waiting (:meth:`close` lets go without opening).  Each
    method closes this process's ends it no longer needs, and may be called
    again.  Without fork nothing waits.

    Examples
    --------
    >>> g = Gate()
    >>> s = Server([("operator:add", (1, 2), {})], gate=g)
    >>> job = s.submit("operator:mul", 3, 4)  # taken off the pipe, run once the gate is open
    >>> g.open()
    >>> from camcam.workers import resolve
    >>> resolve(s.first[0]), resolve(job)
    (3, 12)
    >>> s.close()
    """

    def __init__(self) -> None:
        self._read, self._write = os.pipe() if hasattr(os, "fork") else (None, None)

    def open(self) -> None:
        """Let the waiter go on (it may have gone on already, or be gone) and let go of both ends here."""
        if self._write is not None:
            try:
                os.write(self._write, b"o")
            except BrokenPipeError:
                pass  # nobody reads any more: the waiter went on (or ended) already
        self.close()

    def close(self) -> None:
        """Let go of this process's ends without opening the gate (the waiter goes on once all have)."""
        self._close_write()
        self._close_read()

    def wait(self) -> None:
        """Block until some process opens the gate or every other end is let go; then let go of ours."""
        self._close_write()  # this process never opens it: its own end must not keep the pipe alive
        if self._read is not None:
            os.read(self._read, 1)  # a byte, or b"" once no process holds the write end
            self._close_read()

    def _close_write(self) -> None:
        if self._write is not None:
            os.close(self._write)
            self._write = None

    def _close_read(self) -> None:
        if self._read is not None:
            os.close(self._read)
            self._read = None


class Server:
    """One forked child that runs jobs for the parent, in the order they are given.

    ``Server(first)`` forks at once; the child runs each ``(target, args,
    kwargs)`` of ``first`` on the memory it inherited (nothing pickled), then
    the :meth:`submit` jobs, whose arguments are pickled to it.  A target is
    ``"package.module:function"``, imported in the child (:func:`call_target`);
    :func:`preload` as a first job imports modules ahead of the jobs that need
    them.  :meth:`submit` returns at once (the child takes requests off the
    pipe while it works, see :class:`_ServerPipes`); :meth:`close` ends the
    child once every reply was read.  With a ``gate`` (:class:`Gate`) the
    child runs ``first`` at once and the submitted jobs only once the gate is
    open.  Without fork every job runs at once, in
    process.  Jobs must not fork (the child runs two threads for its pipes).

    Examples
    --------
    >>> from camcam.workers import resolve
    >>> s = Server([("operator:add", (1, 2), {})])
    >>> first = s.first[0]
    >>> later_job = s.submit("operator:mul", 3, 4)
    >>> resolve(first), resolve(later_job)
    (3, 12)
    >>> s.close()
    """

    def __init__(self, first=(), gate: Gate | None = None) -> None:
        first = [(t, tuple(a), dict(k)) for t, a, k in first]
        self._replies: dict[int, bytes] = {}
        self._names: list[str] = []
        self._next_reply = 0
        self._pid: int | None = None
        if not hasattr(os, "fork"):
            self.first = tuple(call_target(t, *a, **k) for t, a, k in first)
            return
        (req_r, req_w), (rep_r, rep_w) = _pipes()

        def child():
            os.close(req_w), os.close(rep_r)
            with _ServerPipes(req_r, rep_w) as pipes:
                for t, a, k in first:
                    pipes.reply(child_payload(call_target, (t, *a), k))
                if gate is not None:
                    gate.wait()  # the submitted jobs' requests are taken off the pipe meanwhile
                while (raw := pipes.jobs.get()) is not None:
                    t, a, k = pickle.loads(raw)
                    pipes.reply(child_payload(call_target, (t, *a), k))

        self._pid = fork_child(child)
        os.close(req_r), os.close(rep_w)
        self._req_fd, self._rep_fd = req_w, rep_r
        self.first = tuple(self._pending(t) for t, _, _ in first)

    def _pending(self, target: str) -> Pending:
        index = len(self._names)
        self._names.append(target)
        return Pending(lambda: self._reply(index))

    def _read_reply(self) -> None:
        """Read the next reply frame off the pipe (the parent waits for the one it needs)."""
        body = _read_frame(self._rep_fd)
        if not body:  # a reply is never empty: the pipe ended
            what = self._names[self._next_reply] if self._next_reply < len(self._names) else "the plot server"
            raise ChildError(f"{what} failed: the server process ended without a reply")
        self._replies[self._next_reply] = body
        self._next_reply += 1

    def _reply(self, index: int):
        if self._pid is None and index >= self._next_reply:
            raise ChildError(f"{self._names[index]} failed: the server was stopped before it replied")
        self._pump(until=index)
        return decode_payload(self._replies.pop(index), self._names[index])

    def _pump(self, until: int) -> None:
        """Read replies until reply ``until`` is in."""
        while until >= self._next_reply:
            self._read_reply()

    def _send(self, frame: bytes) -> None:
        """Write a whole request frame (the child's reader thread takes it off the pipe as it comes)."""
        try:
            write_all(self._req_fd, frame)
        except BrokenPipeError:
            raise ChildError("the server process ended before it took its jobs") from None

    def submit(self, target: str, *args, **kwargs) -> Pending | Any:
        """Run ``target(*args, **kwargs)`` in the server (arguments and result must pickle); returns at once."""
        if self._pid is None:
            return call_target(target, *args, **kwargs)
        data = pickle.dumps((target, args, kwargs), protocol=pickle.HIGHEST_PROTOCOL)
        self._send(_frame(data))
        return self._pending(target)

    def kill(self) -> None:
        """End the child at once (a run that failed): replies not yet read are lost (idempotent)."""
        if self._pid is None:
            return
        os.kill(self._pid, signal.SIGKILL)
        _reap(self._pid, self._req_fd, self._rep_fd)
        self._pid = None

    def close(self) -> None:
        """Read every reply still due, end the child and wait for it (idempotent)."""
        if self._pid is None:
            return
        try:
            # an empty frame ends the child (not EOF: other children hold the pipe too)
            self._send(_frame(b""))
            if self._names:
                self._pump(until=len(self._names) - 1)
        except ChildError:
            pass  # the missing replies raise when their results are asked for
        _reap(self._pid, self._req_fd, self._rep_fd)
        self._pid = None


class Prepared:
    """One forked child that imports ``modules`` and runs ``first`` at once, and one job sent to it later.

    ``Prepared(modules, first)`` forks at once; the child imports the modules
    and runs each ``(function, args, kwargs)`` of ``first`` on the memory it
    inherited (nothing pickled), in its main thread, while a reader thread
    takes the job off the request pipe as soon as it comes, so :meth:`submit`
    returns at once whatever the size of the job's arguments (pickled).  The
    reader ends before the job runs, so, unlike a :class:`Server` job, the job
    may fork children of its own (a :func:`later` in it), and they inherit
    the modules imported.  Every reply (``first``'s, then the job's) is sent
    once the job has run, so the child never waits on a parent that is busy
    elsewhere: ``first``'s results can be had once :meth:`submit` or
    :meth:`close` was called.  The child leads a process group of its own:
    :meth:`kill` (a run that failed) ends it and every child it started, at
    once.  Without fork, ``first`` runs at once and the job when it is
    submitted, in process.  A failed import fails every job.  With ``opens``
    (a :class:`Gate`) the child opens it once the modules are loaded and
    ``first`` has run.

    Examples
    --------
    >>> from camcam.workers import resolve
    >>> p = Prepared(["fractions"], first=[(sum, ([1, 2],), {})])
    >>> job = p.submit("fractions:Fraction", 3, 6)
    >>> resolve(p.first[0]), resolve(job)
    (3, Fraction(1, 2))
    """

    def __init__(self, modules=(), first=(), opens: Gate | None = None) -> None:
        self._modules = tuple(modules)
        first = [(fn, tuple(a), dict(k)) for fn, a, k in first]
        self._pid: int | None = None
        self._sent = False  # the job, or an empty frame, was sent
        self._replies: list[bytes] = []
        if not hasattr(os, "fork"):
            preload(*self._modules)
            self.first = tuple(fn(*a, **k) for fn, a, k in first)
            return
        (req_r, req_w), (rep_r, rep_w) = _pipes()

        def child():
            import threading

            os.setpgid(0, 0)
            # a process group of its own is not the terminal's foreground one: with ``stty tostop`` a write to
            # the terminal (a library's warning) would stop it; ignoring SIGTTOU lets the write through
            if hasattr(signal, "SIGTTOU"):
                signal.signal(signal.SIGTTOU, signal.SIG_IGN)
            os.close(req_w), os.close(rep_r)
            box: list[bytes] = []
            reader = threading.Thread(target=lambda: box.append(_read_frame(req_r)), name="camcam-prepared-job",
                                      daemon=True)
            reader.start()
            loaded = child_payload(preload, self._modules, {})
            replies = [loaded if loaded[:1] != PAYLOAD_OK else child_payload(fn, a, k) for fn, a, k in first]
            if opens is not None:
                opens.open()  # the modules are loaded and ``first`` has run
            reader.join()  # one thread again: the job may fork
            os.close(req_r)
            if box and box[0]:
                target, args, kwargs = pickle.loads(box[0])
                replies.append(loaded if loaded[:1] != PAYLOAD_OK else child_payload(call_target, (target, *args), kwargs))
            try:
                for data in replies:
                    write_all(rep_w, _frame(data))
            except BrokenPipeError:
                pass  # the parent is gone or stopped waiting
            os.close(rep_w)

        self._pid = fork_child(child)
        try:
            os.setpgid(self._pid, self._pid)  # also here: a kill() before the child ran must reach its group
        except OSError:
            pass  # the child did it first (or has ended already)
        os.close(req_r), os.close(rep_w)
        self._req_fd, self._rep_fd = req_w, rep_r
        self._names = [getattr(fn, "__name__", "job") for fn, _, _ in first]
        self.first = tuple(Pending(lambda k=k: self._reply(k), self.kill) for k in range(len(first)))

    def _reply(self, index: int):
        """Reply ``index`` (``first``'s in order, then the job's), read off the pipe as far as needed."""
        if not self._sent:
            raise ChildError("a prepared child's results come after its job was submitted, or it was closed")
        what = self._names[index]
        while len(self._replies) <= index:
            if self._pid is None:
                raise ChildError(f"{what} failed: the prepared process was stopped before it replied")
            body = _read_frame(self._rep_fd)
            if not body:  # the child ended without it
                self._reap()
                raise ChildError(f"{what} failed: the prepared process ended without a result")
            self._replies.append(body)
            if len(self._replies) == len(self._names):
                self._reap()  # every reply is in
        return decode_payload(self._replies[index], what)

    def _send(self, frame: bytes, what: str) -> None:
        self._sent = True
        try:
            write_all(self._req_fd, frame)
        except BrokenPipeError:
            raise ChildError(f"{what} failed: the prepared process ended before it took its job") from None
        finally:
            os.close(self._req_fd)
            self._req_fd = None

    def submit(self, target: str, *args, **kwargs) -> Pending | Any:
        """Run ``target(*args, **kwargs)`` in the child (arguments and result must pickle); returns at once.
        One job per child."""
        if self._sent:
            raise RuntimeError("a prepared child runs one job")
        if not hasattr(os, "fork"):
            self._sent = True
            return call_target(target, *args, **kwargs)
        self._names.append(target)
        index = len(self._names) - 1
        data = pickle.dumps((target, args, kwargs), protocol=pickle.HIGHEST_PROTOCOL)
        self._send(_frame(data), target)
        return Pending(lambda: self._reply(index), self.kill)

    def _reap(self) -> None:
        _reap(self._pid, self._req_fd, self._rep_fd)
        self._pid = self._req_fd = None

    def kill(self) -> None:
        """End the child and every child it started at once, and reap it (idempotent)."""
        if self._pid is None:
            return
        try:
            os.killpg(self._pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self._reap()

    def close(self) -> None:
        """No job for the child (an empty frame): ``first``'s results then follow (idempotent)."""
        if self._sent or self._pid is None:
            return
        try:
            self._send(_frame(b""), "the prepared process")
        except ChildError:
            pass  # the missing replies raise when their results are asked for
        if not self._names:
            self._reap()
