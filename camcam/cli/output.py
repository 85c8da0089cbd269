"""Helpers the commands share: publishing the output set with its summary, JSON printing and warnings.

Warnings and notes (:func:`warn`) never go to stderr unless the command was given ``--verbose``: a run
that ends with status 2 or 3 prints exactly one stderr line, its cause and the way out.  They are
collected while the command works and printed on stdout with its summary (:func:`publish`: one
``warning: …`` line each, or a ``"warnings"`` list in the ``--json`` object); `camcam batch` takes each
spec's own from its :class:`~camcam.flow.Job`.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any, Callable, Sequence

from camcam.export.jsontext import to_json

__all__ = ["to_json", "print_json", "warn", "publish", "output_set", "add_output_arguments", "add_verbose_flag",
           "begin_warnings", "pending_warnings"]

#: Warnings and notes of the command running now, in order (:func:`warn`): (kind, message); and whether they
#: also go to stderr at once.
_warnings: list[tuple[str, str]] = []
_verbose = False


def print_json(obj: Any) -> None:
    sys.stdout.write(to_json(obj) + "\n")


def add_verbose_flag(parser) -> None:
    """The ``--verbose`` option of a command that may warn."""
    parser.add_argument("--verbose", action="store_true",
                        help="also print warnings and notes on stderr as they come (they are on stdout and in the "
                             "report in any case)")


def begin_warnings(verbose: bool = False) -> None:
    """Start a command's warnings afresh (:func:`camcam.cli.main` calls this for every command)."""
    global _verbose
    _warnings.clear()
    _verbose = verbose


def warn(message: str, kind: str = "warning") -> None:
    """Keep ``message`` for the command's stdout (:func:`publish`); on stderr too with ``--verbose``.
    ``kind`` is "warning" (something the user may want to change) or "note" (how the job was done).

    Examples
    --------
    >>> begin_warnings()
    >>> warn("a jump at a join"); warn("4-axis: X along the cam axis", "note")
    >>> pending_warnings(), pending_warnings("note")
    (['a jump at a join'], ['4-axis: X along the cam axis'])
    >>> begin_warnings()
    """
    _warnings.append((kind, message))
    if _verbose:
        print(f"camcam: {kind}: {message}", file=sys.stderr)


def pending_warnings(kind: str = "warning") -> list[str]:
    """The warnings (or notes) collected so far."""
    return [m for k, m in _warnings if k == kind]


def add_output_arguments(p) -> None:
    """``-o DIR`` and ``--force`` for a command that writes an output folder."""
    p.add_argument("-o", "--output", default="camcam-out", help="output folder (default ./camcam-out); "
                   "it must be new, empty, or hold an earlier run's files (with --force)")
    p.add_argument("--force", action="store_true", help="replace the files an earlier run left in the output folder")


def output_set(args, command: str):
    """The command's :class:`~camcam.export.files.OutputSet` for ``args.output``, checked now
    (a target it cannot use fails before any work is done)."""
    from pathlib import Path

    from camcam.export.files import OutputSet

    watch = getattr(args, "watch", None)
    out = OutputSet(Path(args.output), force=getattr(args, "force", False), log=getattr(args, "disk_log", None),
                    command=command, checkpoint=watch.checkpoint if watch is not None else None)
    out.check()
    return out


def publish(out, summary: dict, as_json: bool, show: Callable[[dict], None],
            after: Sequence[str] = ()) -> list[Path]:
    """Write ``out`` (all or nothing), then print ``summary`` as one JSON object, or as text.

    The text is ``show(summary)``, a "wrote <file>" line per file, the lines
    of ``after``, then a ``warning: …`` or ``note: …`` line per warning or
    note of the command (:func:`warn`).  ``summary["files"]`` lists the files
    written, ``summary["warnings"]`` and ``summary["notes"]`` the warnings and
    notes when there are any.
    """
    written = out.commit()
    summary["files"] = [str(p) for p in written]
    for kind in ("warning", "note"):
        if pending_warnings(kind):
            summary[kind + "s"] = pending_warnings(kind)
    if as_json:
        print_json(summary)
    else:
        show(summary)
        for p in written:
            print(f"wrote {p}")
        for line in after:
            print(line)
        for kind, message in _warnings:
            print(f"{kind}: {message}")
    return written
