"""The ``camcam`` command.

Each sub-command lives in its own module with ``register(subparsers)``; this
module assembles them and turns user errors into one line and exit status 2.
"""

from __future__ import annotations

import argparse
import sys

from camcam import __version__
from camcam.cli import batch, fit, laws, motion, optimize, reverse, run, size
from camcam.errors import CamcamError

__all__ = ["main"]

COMMANDS = (laws, motion, run, fit, optimize, reverse, size, batch)

#: Exit status for every user error (bad spec, table, points, arguments).
USAGE_ERROR = 2


class _Parser(argparse.ArgumentParser):
    """argparse, but a bad argument gives one line, not the usage block."""

    def error(self, message: str):  # noqa: D401
        print(f"camcam: error: {message} (see `{self.prog} --help`)", file=sys.stderr)
        raise SystemExit(USAGE_ERROR)


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="camcam", description="Cam design to verified NC programs.")
    parser.add_argument("--version", action="version", version=f"camcam {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    for module in COMMANDS:
        module.register(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if not getattr(args, "func", None):
        parser.print_help()
        return USAGE_ERROR
    try:
        return int(args.func(args) or 0)
    except CamcamError as err:
        # one line whatever the message quotes (a file's bytes, a value with a newline)
        print("camcam: error: " + " ".join(str(err).splitlines()), file=sys.stderr)
        return USAGE_ERROR
    except KeyboardInterrupt:
        print("camcam: interrupted; no output was written", file=sys.stderr)
        return 130


def main_exit() -> None:
    """Console-script entry point."""
    raise SystemExit(main())
