"""Forked children that stay and take jobs over pipes: the plot server and the drawing's prepared child.

* :class:`Server` forks one child that runs a first batch of jobs on the
  memory it inherited, then serves later jobs sent to it (pickled), one at a
  time, importing the modules they name itself.  So the parent never imports
  matplotlib: the server imports it once, on the other core.  `camcam run`
  starts its plot server before anything but numpy's import, which the server
  inherits (matplotlib's import then runs beside the run's own imports); the
  cam and the plots' data go to it pickled.
* :class:`Prepared` forks one child that imports modules at once and runs one
  job sent to it later, which, unlike a server's, may fork children of its
  own.  `camcam run` starts one before the NC step: it imports ezdxf and
  scipy (the DXF's splines, the material check's k-d trees) beside the NC
  work, then takes the printed program and writes the drawing while the
  material check runs in its children, which inherit those modules.

Requests and replies travel as frames: an 8-byte length, then the pickled
body (an empty frame ends a child's jobs).  The children run their jobs as
:mod:`camcam.workers.children` runs a :func:`~camcam.workers.children.later` job (the same
payload, failures and interrupts); without ``os.fork``, or within
:func:`~camcam.workers.children.single_process`, every job runs at once, in process.
"""

from __future__ import annotations

import os
import pickle
import signal
import struct
from typing import Any

# the forked-child protocol of camcam.workers.children (a job's payload, its decoding, the fork itself), shared here
from camcam.workers.children import (PAYLOAD_OK, ChildError, Pending, call_target, child_payload, decode_payload,
                                     fork_child, forking, preload, write_all)

__all__ = ["Server", "Prepared", "Gate"]

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
        self._read, self._write = os.pipe() if forking() else (None, None)

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
        if not forking():
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
        self._forked = forking()  # its job goes where ``first`` went, whatever the caller's mode is by then
        if not self._forked:
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
        if not self._forked:
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
