"""The ``camcam`` command.

Each sub-command lives in its own module with ``register(subparsers)``
(:mod:`camcam.cli.commands` names them); only the module of the command that
runs is imported, so ``camcam --help`` and ``camcam laws`` do not load the
plotting, geometry and NC stages.  This module assembles them and maps what went wrong to an exit status:

=====  ==============================================================================
0      done
2      bad input: one line naming the key, row or argument; nothing written
3      files written, but the verdict is FAIL (out of tolerance); the report opens with it
1      internal fault: one line ``internal error: …; details in <file>``, the traceback in
       that file (beside the output folder, or in the temp folder)
130    interrupted (Ctrl-C)
=====  ==============================================================================

The command asks OpenBLAS (numpy's and scipy's) for one thread unless the
environment says otherwise (:func:`single_threaded_blas`): camcam's arrays are
far below the sizes BLAS threads pay off at, its work is spread over the cores
by forked processes (:mod:`camcam.workers`), and starting each library's idle
threads cost about 0.1 CPU s per import (numpy 0.23 → 0.12 CPU s, scipy.interpolate
0.74 → 0.62 CPU s on the 2-core benchmark machine).
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
import tempfile
import traceback
from pathlib import Path

from camcam import __version__
from camcam.cli.commands import COMMANDS
from camcam.errors import CamcamError
from camcam.export.files import DiskLog
from camcam.interrupts import Interrupted, Watch, exit_status, import_guard, signal_name

__all__ = ["main", "main_exit", "single_threaded_blas", "USAGE_ERROR", "INTERNAL_ERROR"]

#: Exit status for every user error (bad spec, table, points, arguments).
USAGE_ERROR = 2
#: Exit status for a fault of camcam's own (a bug, or a stage that failed on valid input).
INTERNAL_ERROR = 1


class _Parser(argparse.ArgumentParser):
    """argparse, but a bad argument gives one line, not the usage block."""

    def error(self, message: str):  # noqa: D401
        print(f"camcam: error: {message} (see `{self.prog} --help`)", file=sys.stderr)
        raise SystemExit(USAGE_ERROR)


def build_parser(argv: list[str] | None = None) -> argparse.ArgumentParser:
    """The parser for ``argv``: the full parser of the command it names (every command's
    when ``argv`` is None), a bare entry with its help for each other command."""
    parser = _Parser(prog="camcam", description="Cam design to verified NC programs.")
    parser.add_argument("--version", action="version", version=f"camcam {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    # the top-level options take no value, so the first word that names a command is the command
    chosen = set(COMMANDS) if argv is None else next(({a} for a in argv if a in COMMANDS), set())
    for name, (module, help_text) in COMMANDS.items():
        if name in chosen:
            importlib.import_module(module).register(sub)
        else:
            sub.add_parser(name, help=help_text)
    return parser


def _one_line(text: str) -> str:
    """Whatever a message quotes (a file's bytes, a value with a newline), one line."""
    return " ".join(str(text).splitlines())


def fault_report(err: BaseException, argv: list[str] | None, output: str | None) -> Path:
    """Write the traceback of an internal fault to a file; return its path.

    The file goes beside the output folder (its parent) when that is
    writable, else into the temp folder — never into the output folder, whose
    contents are the run's all-or-nothing set.
    """
    text = (f"camcam {__version__} internal error\nargv: {argv!r}\n\n"
            + "".join(traceback.format_exception(type(err), err, err.__traceback__)))
    places = []
    if output:
        places.append(Path(output).resolve().parent)
    places.append(Path(tempfile.gettempdir()))
    for place in places:
        try:
            fd, name = tempfile.mkstemp(prefix="camcam-fault-", suffix=".txt", dir=place)
        except OSError:
            continue
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        return Path(name)
    raise OSError("no writable folder for the fault report")


def single_threaded_blas(environ=os.environ) -> None:
    """Ask OpenBLAS for one thread (``OPENBLAS_NUM_THREADS=1``) unless ``environ`` already sets it.

    It acts only on libraries loaded after it: :func:`main` calls it before its command imports
    numpy.  The results are the same bits: camcam's matrix products are small enough that OpenBLAS
    runs them on one thread anyway (``tests/data/sample_checksums.json`` holds with and without it).

    Examples
    --------
    >>> env = {}
    >>> single_threaded_blas(env)
    >>> env
    {'OPENBLAS_NUM_THREADS': '1'}
    >>> env = {"OPENBLAS_NUM_THREADS": "4"}
    >>> single_threaded_blas(env)
    >>> env
    {'OPENBLAS_NUM_THREADS': '4'}
    """
    environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status (see the module notes)."""
    single_threaded_blas()
    words = sys.argv[1:] if argv is None else list(argv)
    with import_guard():  # Ctrl-C while the command's modules load: one line and 130, never a traceback
        parser = build_parser(words)
    args = parser.parse_args(words)
    if not getattr(args, "func", None):
        parser.print_help()
        return USAGE_ERROR
    from camcam.cli.output import begin_warnings

    begin_warnings(bool(getattr(args, "verbose", False)))  # warnings on stdout and in the report; stderr with --verbose
    disk = DiskLog()
    with Watch() as watch:
        args.watch, args.disk_log = watch, disk
        try:
            status = int(args.func(args) or 0)
            watch.checkpoint()  # an interrupt a library swallowed still ends the run as one
            return status
        except CamcamError as err:
            print("camcam: error: " + _one_line(err), file=sys.stderr)
            return USAGE_ERROR
        except KeyboardInterrupt as err:  # Ctrl-C, SIGTERM, SIGHUP: say what is on disk
            signum = err.signum if isinstance(err, Interrupted) else 2
            what = "interrupted" if signum == 2 else f"terminated by {signal_name(signum)}"
            print(f"camcam: {what}; {disk.describe()}", file=sys.stderr)
            return exit_status(signum)
        except Exception as err:  # a fault of ours, never dressed up as the user's mistake
            try:
                where = f"details in {fault_report(err, argv, getattr(args, 'output', None))}"
            except OSError:
                where = "no file could be written for the details"
            print(f"camcam: internal error: {type(err).__name__}: {_one_line(err)}; {where}", file=sys.stderr)
            return INTERNAL_ERROR


def main_exit() -> None:
    """Console-script entry point."""
    raise SystemExit(main())
