"""Helpers the commands share: publishing the output set with its summary, JSON printing and warnings."""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any, Callable, Sequence

from camcam.export.jsontext import to_json

__all__ = ["to_json", "print_json", "warn", "publish", "output_set", "add_output_arguments"]


def print_json(obj: Any) -> None:
    sys.stdout.write(to_json(obj) + "\n")


def warn(message: str) -> None:
    print(f"camcam: warning: {message}", file=sys.stderr)


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

    The text is ``show(summary)``, a "wrote <file>" line per file, then the
    lines of ``after``.  ``summary["files"]`` lists the files written.
    """
    written = out.commit()
    summary["files"] = [str(p) for p in written]
    if as_json:
        print_json(summary)
    else:
        show(summary)
        for p in written:
            print(f"wrote {p}")
        for line in after:
            print(line)
    return written
