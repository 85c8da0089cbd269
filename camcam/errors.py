"""Error classes.  Each also inherits the built-in error it refines, so callers
may catch either (``except ValueError`` keeps working).

The command line turns every :class:`CamcamError` into one line on stderr and
exit status 2; anything else is a bug and keeps its traceback.
"""

from __future__ import annotations

__all__ = ["CamcamError", "SpecError", "InputError", "MotionError", "GeometryError", "OutputError"]


class CamcamError(Exception):
    """Base of every error a user can cause with bad input."""


class SpecError(CamcamError, ValueError):
    """A spec value is missing, unknown or out of range.

    ``str(err)`` is ``"<key path>: <what was wrong and what was expected>"``.

    Examples
    --------
    >>> str(SpecError("motion.segments[2].to", "370 is past 360"))
    'motion.segments[2].to: 370 is past 360'
    """

    def __init__(self, path: str, message: str) -> None:
        self.path = path
        self.message = message
        super().__init__(f"{path}: {message}" if path else message)


class InputError(CamcamError, ValueError):
    """A data file (lift table, point cloud, post file) is malformed; the message names the row."""


class MotionError(CamcamError, ValueError):
    """A motion program is inconsistent (e.g. a strict program with a jump at a join)."""


class GeometryError(CamcamError, ValueError):
    """The cam cannot be built as specified (undercut, cusp, follower cannot reach)."""


class OutputError(CamcamError, OSError):
    """An input or output path cannot be used: the message names the path and the reason
    (no space left, read-only, not a folder, exists, held by another run)."""
