"""The options `camcam size` and `camcam batch` share: where their tasks run."""

from __future__ import annotations

import argparse
import sys

from camcam.cli.progress import Progress, add_progress_flag
from camcam.dask_batch.engine import WORKER_TIMEOUT_S, open_executor

__all__ = ["add_scale_arguments", "executor_from_args", "tell_scale_note"]


def _positive(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number of workers >= 1, got {text!r}") from None
    if n < 1:
        raise argparse.ArgumentTypeError(f"expected a whole number of workers >= 1, got {text!r}")
    return n


def _seconds(text: str) -> float:
    try:
        s = float(text)
    except ValueError:
        s = float("nan")
    if not s > 0 or s == float("inf"):
        raise argparse.ArgumentTypeError(f"expected a number of seconds > 0, got {text!r}")
    return s


def add_scale_arguments(p) -> None:
    g = p.add_argument_group("where the work runs (Dask, with `pip install 'camcam[scale]'`)")
    g.add_argument("--scheduler", metavar="ADDRESS", help="an existing Dask scheduler, e.g. tcp://10.0.0.5:8786")
    g.add_argument("--workers", type=_positive, metavar="N", help="worker processes of the local cluster (default: one per core)")
    g.add_argument("--in-process", action="store_true", help="run every task in this process, without Dask")
    g.add_argument("--timeout", type=_seconds, metavar="SECONDS", default=WORKER_TIMEOUT_S,
                   help=f"with --scheduler: how long to wait for a first worker (default {WORKER_TIMEOUT_S:g} s)")
    add_progress_flag(p)


def executor_from_args(args):
    """The executor context manager for the parsed options."""
    return open_executor(args.scheduler, args.workers, args.in_process, Progress.from_args(args).enabled,
                         args.timeout, _note if sys.stderr.isatty() else None)


def _note(text: str) -> None:
    print(f"camcam: note: {text}", file=sys.stderr, flush=True)


def tell_scale_note(executor) -> None:
    """The how-to-scale-out line, on stderr and only on a terminal."""
    if executor.note and sys.stderr.isatty():
        _note(executor.note)
