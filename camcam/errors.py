"""Error classes.  Each also inherits the built-in error it refines, so callers
may catch either (``except ValueError`` keeps working).

Two families, told apart by the exit status of the command line:

* :class:`CamcamError` and its children are the user's: a bad spec, data file,
  post file or a cam that cannot be built as specified.  One line on stderr,
  exit status 2, nothing written.
* :class:`CamcamFault` and its children (:class:`FitError`) are ours: the
  input was fine but a stage could not do its job.  Like any other unexpected
  exception they give one line "internal error: …; details in <file>", the
  traceback in that file, and exit status 1.

A run whose files were written but whose verdict is FAIL exits with status 3
(:mod:`camcam.verdict`).
"""

from __future__ import annotations

__all__ = ["CamcamError", "SpecError", "InputError", "MotionError", "GeometryError", "CamcamFault", "FitError", "PostError", "OutputError"]


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

    def __reduce__(self):
        # pickled as (path, message): a check run in a child process (camcam.workers) raises it in the parent
        return (type(self), (self.path, self.message))


class InputError(CamcamError, ValueError):
    """A data file (lift table, point cloud, post file) is malformed; the message names the row."""


class MotionError(CamcamError, ValueError):
    """A motion program is inconsistent (e.g. a strict program with a jump at a join)."""


class GeometryError(CamcamError, ValueError):
    """The cam cannot be built as specified (undercut, cusp, follower cannot reach)."""


class OutputError(CamcamError, OSError):
    """An input or output path cannot be used: the message names the path and the reason
    (no space left, read-only, not a folder, exists, held by another run)."""


class CamcamFault(RuntimeError):
    """A stage failed on valid input: a defect or a limit of camcam, not the user's mistake."""


class FitError(CamcamFault):
    """The NC fit could not bring a contour within its tolerance on valid input.

    Examples
    --------
    >>> isinstance(FitError("profile: 0.012 mm over 0.01 mm"), RuntimeError)
    True
    """


class PostError(CamcamFault):
    """A fitted path cannot be printed as fitted (an arc the post cannot hold after rounding)."""
