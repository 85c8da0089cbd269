"""Where `camcam size` and `camcam batch` run their tasks: in this process, or on Dask.

With ``dask.distributed`` installed (``pip install 'camcam[scale]'``) the
default is a local cluster of one single-threaded worker process per core;
``--scheduler ADDRESS`` uses an existing cluster instead.  Without it the
tasks run here, one after the other, and :attr:`Executor.note` says how to
scale out.  Either way :meth:`Executor.map` returns the results in the order
of the tasks, so what is written never depends on where a task ran.
"""

from __future__ import annotations

import logging
from abc import ABC, abstractmethod
import os
import sys
from contextlib import contextmanager
from typing import Any, Callable, Iterator, Sequence, TextIO

from camcam.errors import SpecError

__all__ = ["Executor", "InProcess", "DaskExecutor", "open_executor", "dask_available", "SCALE_HINT", "WORKER_TIMEOUT_S",
           "NO_TRIM"]

SCALE_HINT = "ran in-process; pip install 'camcam[scale]' runs it on a Dask cluster (local by default, or --scheduler ADDRESS)"


def dask_available() -> bool:
    try:
        import distributed  # noqa: F401
    except ImportError:
        return False
    return True


class _Bar:
    """A progress bar on ``stream`` (stderr) when ``enabled``; nothing otherwise."""

    def __init__(self, what: str, total: int, enabled: bool, stream: TextIO | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.on = enabled and total > 1
        self.what, self.total, self.done = what, total, 0

    def step(self) -> None:
        self.done += 1
        if self.on:
            filled = int(30 * self.done / self.total)
            self.stream.write(f"\rcamcam: {self.what} [{'#' * filled}{'.' * (30 - filled)}] {self.done}/{self.total}")
            if self.done == self.total:
                self.stream.write("\n")
            self.stream.flush()


class Executor(ABC):
    """Runs ``fn(item, **shared)`` for every item and returns the results in item order."""

    label = "executor"
    workers = 1
    note = ""
    #: Draw a progress bar on stderr (the commands set it: a terminal, or ``--progress``).
    progress = False

    @abstractmethod
    def map(self, fn: Callable, items: Sequence, what: str = "tasks", **shared: Any) -> list:
        """``[fn(item, **shared) for item in items]``, in the order of ``items``."""


class InProcess(Executor):
    """Every task in this process, in order.

    Examples
    --------
    >>> InProcess().map(pow, [1, 2, 3], exp=2)
    [1, 4, 9]
    """

    label = "in-process"

    def __init__(self, note: str = "") -> None:
        self.note = note

    def map(self, fn, items, what="tasks", **shared):
        bar = _Bar(what, len(items), self.progress)
        out = []
        for item in items:
            out.append(fn(item, **shared))
            bar.step()
        return out


#: The Dask setting our local cluster's workers start without: Dask sets ``MALLOC_TRIM_THRESHOLD_=65536`` in a
#: worker's environment, which turns off glibc's sliding mmap threshold, so every numpy array over 128 KiB is
#: mapped and faulted in afresh and unmapped when freed.  A batch job allocates many (the barrel cam's 3-D
#: measurement most): `camcam batch` of the 9 run samples on 2 workers, the workers' own getrusage (2026-12-07,
#: a loaded machine): 10.6 system CPU s with it, 2.3 without; 48.5 → 34.9 CPU s in all.  A value the user's
#: environment sets is inherited as ever.
NO_TRIM = "distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_"

#: How long a command waits for a first worker on an existing scheduler (``--timeout``), seconds.
WORKER_TIMEOUT_S = 60.0


class DaskExecutor(Executor):
    """The tasks on a ``dask.distributed`` client; the shared arguments are sent to the workers once.

    ``wait_s``: on a scheduler with no worker, how long to wait for one before giving up with a
    :class:`~camcam.errors.SpecError` naming ``--timeout`` (``None``: a cluster of our own, whose
    workers are started with it).  The waiting is said on a terminal (``tell``), never silent there.
    """

    def __init__(self, client, label: str, wait_s: float | None = None, tell: Callable[[str], None] | None = None) -> None:
        self.client = client
        self.label = label
        self.wait_s = wait_s
        self.tell = tell

    @property
    def workers(self) -> int:
        return len(self.client.scheduler_info().get("workers", {}))

    def map(self, fn, items, what="tasks", **shared):
        from distributed import as_completed

        if not items:
            return []
        if self.wait_s is not None and not self.workers:
            self._wait_for_a_worker()
        # hash=False: a fresh key each call, so releasing an earlier call's copy cannot drop this one
        scattered = {k: self.client.scatter(v, broadcast=True, hash=False) for k, v in shared.items()}
        futures = self.client.map(fn, list(items), pure=False, **scattered)
        bar = _Bar(what, len(futures), self.progress)
        for _ in as_completed(futures):
            bar.step()
        return self.client.gather(futures)


    def _wait_for_a_worker(self) -> None:
        if self.tell is not None:
            self.tell(f"waiting for a worker to join the {self.label} (up to {self.wait_s:g} s, --timeout)")
        try:
            self.client.wait_for_workers(1, timeout=self.wait_s)
        except (TimeoutError, OSError):
            raise SpecError("--timeout", f"no worker joined the {self.label} within {self.wait_s:g} s; start one "
                            f"(dask worker ADDRESS) or wait longer with --timeout SECONDS") from None


@contextmanager
def open_executor(scheduler: str | None = None, workers: int | None = None, in_process: bool = False,
                  progress: bool = False, timeout_s: float = WORKER_TIMEOUT_S,
                  tell: Callable[[str], None] | None = None) -> Iterator[Executor]:
    """The executor a command runs on (see the module docstring); closes what it opened.

    ``timeout_s`` bounds the wait for a first worker on an existing scheduler; ``tell`` is told that
    the command is waiting (the commands pass a stderr note on a terminal)."""
    with _opened(scheduler, workers, in_process, timeout_s, tell) as executor:
        executor.progress = progress
        yield executor


@contextmanager
def _opened(scheduler, workers, in_process, timeout_s, tell) -> Iterator[Executor]:
    if in_process:
        yield InProcess()
        return
    if not dask_available():
        if scheduler is not None:
            raise SpecError("--scheduler", "needs dask.distributed: pip install 'camcam[scale]'")
        yield InProcess(SCALE_HINT)
        return
    from distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            client = Client(scheduler, timeout="10s")
        except (OSError, TimeoutError, ValueError) as err:
            raise SpecError("--scheduler", f"cannot reach a Dask scheduler at {scheduler}: {' '.join(str(err).split())}") from None
        try:
            yield DaskExecutor(client, f"Dask scheduler {scheduler}", timeout_s, tell)
        finally:
            client.close()
        return
    import dask

    n = workers if workers is not None else (os.cpu_count() or 1)
    with dask.config.set({NO_TRIM: None}):  # see NO_TRIM
        cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True, dashboard_address=":0",
                               silence_logs=logging.ERROR)
    client = Client(cluster)
    try:
        yield DaskExecutor(client, f"local Dask cluster, {n} worker{'s' if n != 1 else ''}")
    finally:
        client.close()
        cluster.close()
