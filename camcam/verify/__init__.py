"""Checks with programs nobody on the project wrote (LinuxCNC's rs274 interpreter)."""

from camcam.verify.rs274 import CanonMove, rs274_available, run_rs274, feed_passes

__all__ = ["CanonMove", "rs274_available", "run_rs274", "feed_passes"]
