"""The sub-commands by name, with their one-line help, without importing them.

``camcam`` imports only the module of the command it runs (``camcam --help``
imports none): :func:`camcam.cli.build_parser` adds the chosen command's full
parser and a bare entry, with the help below, for every other one.
"""

from __future__ import annotations

__all__ = ["COMMANDS", "help_of"]

#: Command → (module with ``register(subparsers)`` and ``run(args)``, one-line help).
COMMANDS = {
    "laws": ("camcam.cli.laws", "list the motion laws and their characteristic values"),
    "motion": ("camcam.cli.motion", "tabulate and plot a spec's motion program"),
    "run": ("camcam.cli.run", "run the whole flow for a spec (default: the bundled sample job)"),
    "fit": ("camcam.cli.fit", "remove bad points from a lift table, fair it and fit a spline"),
    "optimize": ("camcam.cli.optimize", "optimise a B-spline cam curve ([optimize] table)"),
    "reverse": ("camcam.cli.reverse", "recover the follower motion from measured cam points"),
    "inspect": ("camcam.cli.inspect", "the part as measured (CMM, dial indicator, barrel walls) against the design, with a verdict"),
    "size": ("camcam.cli.size", "sweep a spec's [size] table: the smallest cam that meets every constraint"),
    "batch": ("camcam.cli.batch", "run many specs, each into its own folder, with one summary table and index page"),
}


def help_of(command: str) -> str:
    """The one-line help of ``command``.

    Examples
    --------
    >>> help_of("laws")
    'list the motion laws and their characteristic values'
    """
    return COMMANDS[command][1]
