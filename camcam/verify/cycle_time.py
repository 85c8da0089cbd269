"""Cycle time of a printed program: the sum of its moves at the rates the program states.

The writer records every move it prints, from the printed numbers
(``Program.printed_moves``, :mod:`camcam.post.gcode`); :func:`cycle_time` times
them here, as the controller reads them:

* a feed move (a line or an arc with F, in any dialect) takes its path length
  over the modal feed; an arc's length is r · sweep (helical: the hypotenuse
  with the Z travel); a move that turns A at a tool-tip feed (a 5-axis line of
  a dialect without inverse time, under tool-centre-point control) is as long
  as the tip's path in the part, which turns with A (:func:`part_path_mm`);
* an inverse-time move (``G93``, every 4- and 5-axis move of the G-code posts)
  takes 1/F minutes, F as printed (rs274's canonical feed rates say the same:
  the move's XYZ length × F), and its length counts the tip's path in the part;
* a rapid (``G0``, ``FMAX``) runs its straight-line length at the post's
  ``rapid_mm_min`` (a controller that moves each axis at its own rate is
  faster on a diagonal: the estimate errs long there);
* each tool change adds the post's ``tool_change_s`` (camcam's programs have no dwells).

Acceleration is ignored: every move runs at its programmed rate from end to
end, so the estimate is a lower bound wherever the machine cannot reach the
rate (short blocks, corners): :mod:`camcam.verify.motion_time` times the same
moves with the post's accelerations.  A position the program never states (before the
first move) is taken as the work zero, as LinuxCNC's interpreter does; the pass comments
the writer records among the moves take no time.

Examples
--------
>>> moves = (("tool change", 10.0), ("rapid", (0.0, 0.0, 0.0), (0.0, 0.0, 5.0)),
...          ("line", (0.0, 0.0, 5.0), (10.0, 0.0, 5.0), 300.0, 0.0, 0.0))
>>> round(cycle_time(moves, rapid_mm_min=5000.0).total_s, 4)  # 10 s + 5 mm at 5 m/min + 10 mm at 300 mm/min
12.06
>>> t = CycleTime(feed_s=60.0, rapid_s=3.0, tool_change_s=10.0, feed_mm=400.0, rapid_mm=250.0, moves=5)
>>> t.total_s
73.0
>>> t.describe()
'1 min 13 s (feeds 60.0 s over 400 mm, rapids 3.0 s over 250 mm, tool changes 10.0 s)'
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["CycleTime", "MoveTimer", "cycle_time", "part_path_mm"]

#: Simpson intervals of a move's tip path in the part (even).
PATH_INTERVALS = 16


def part_path_mm(start, end, a0_deg: float = 0.0, a1_deg: float = 0.0) -> float:
    """Length of the tool tip's path in the part (mm) along a move from ``start`` to ``end`` (machine X Y Z)
    while A turns linearly from ``a0_deg`` to ``a1_deg`` about X: the part point under the tip is Rx(−A)·p.

    Its speed² is X′² + Y′² + Z′² + A′²(Y² + Z²) − 2A′(Y·Z′ − Z·Y′) (A′ in radians); Simpson's rule on
    :data:`PATH_INTERVALS` intervals.  Without a turn it is the straight length.

    Examples
    --------
    >>> round(part_path_mm((0.0, 0.0, 50.0), (0.0, 0.0, 50.0), 0.0, 90.0), 9)  # a quarter turn at R50
    78.53981634
    >>> part_path_mm((0.0, 0.0, 0.0), (3.0, 4.0, 0.0))
    5.0
    """
    da = math.radians(a1_deg - a0_deg)
    if da == 0.0:
        return math.dist(start, end)
    dx, dy, dz = (e - s for s, e in zip(start, end))
    n = PATH_INTERVALS
    total = 0.0
    for k in range(n + 1):
        u = k / n
        y, z = start[1] + u * dy, start[2] + u * dz
        speed = math.sqrt(max(dx * dx + dy * dy + dz * dz + da * da * (y * y + z * z) - 2 * da * (y * dz - z * dy),
                              0.0))
        total += speed * (1 if k in (0, n) else 4 if k % 2 else 2)
    return total / (3 * n)


@dataclass(frozen=True, kw_only=True)
class CycleTime:
    """A program's estimated run time, split by what takes it (seconds, mm)."""

    feed_s: float
    rapid_s: float
    tool_change_s: float
    feed_mm: float
    rapid_mm: float
    moves: int

    @property
    def total_s(self) -> float:
        return self.feed_s + self.rapid_s + self.tool_change_s

    def describe(self) -> str:
        """One line: the total as minutes and seconds, then its parts."""
        m, s = divmod(self.total_s, 60.0)
        total = f"{int(m)} min {s:.0f} s" if m >= 1 else f"{s:.1f} s"
        parts = [f"feeds {self.feed_s:.1f} s over {self.feed_mm:.0f} mm",
                 f"rapids {self.rapid_s:.1f} s over {self.rapid_mm:.0f} mm"]
        if self.tool_change_s:
            parts.append(f"tool changes {self.tool_change_s:.1f} s")
        return f"{total} ({', '.join(parts)})"

    def as_dict(self) -> dict:
        return {"total_s": self.total_s, "feed_s": self.feed_s, "rapid_s": self.rapid_s,
                "tool_change_s": self.tool_change_s, "feed_mm": self.feed_mm,
                "rapid_mm": self.rapid_mm, "moves": self.moves}


class MoveTimer:
    """Accumulates move times, one printed move after the other (positions in mm, as printed)."""

    def __init__(self, rapid_mm_min: float):
        self.rapid_mm_min = rapid_mm_min
        self.feed_min = self.rapid_min = self.feed_mm = self.rapid_mm = 0.0
        self.tool_change_s = 0.0
        self.moves = 0

    def rapid(self, start, end) -> None:
        d = math.dist(start, end)
        self.rapid_mm += d
        self.rapid_min += d / self.rapid_mm_min
        self.moves += 1

    def line(self, start, end, feed_mm_min: float, a0_deg: float = 0.0, a1_deg: float = 0.0) -> None:
        """A feed move at ``feed_mm_min`` along the tip's path in the part (A turning from ``a0_deg`` to ``a1_deg``)."""
        d = part_path_mm(start, end, a0_deg, a1_deg)
        self.feed_mm += d
        self.feed_min += d / feed_mm_min
        self.moves += 1

    def inverse_time(self, start, end, f_per_min: float, a0_deg: float = 0.0, a1_deg: float = 0.0) -> None:
        """A G93 move: 1/F minutes whatever its length; its length is the tip's path in the part."""
        self.feed_mm += part_path_mm(start, end, a0_deg, a1_deg)
        self.feed_min += 1.0 / f_per_min
        self.moves += 1

    def arc(self, start, end, centre, ccw: bool, feed_mm_min: float) -> None:
        """An XY arc (start/end carry Z: a change makes it helical) from ``start`` about ``centre``."""
        a0 = math.atan2(start[1] - centre[1], start[0] - centre[0])
        a1 = math.atan2(end[1] - centre[1], end[0] - centre[0])
        sweep = ((a1 - a0) if ccw else (a0 - a1)) % (2 * math.pi)
        r = 0.5 * (math.hypot(start[0] - centre[0], start[1] - centre[1])
                   + math.hypot(end[0] - centre[0], end[1] - centre[1]))
        d = math.hypot(r * sweep, end[2] - start[2])
        self.feed_mm += d
        self.feed_min += d / feed_mm_min
        self.moves += 1

    def tool_change(self, seconds: float) -> None:
        self.tool_change_s += seconds

    def result(self) -> CycleTime:
        return CycleTime(feed_s=60.0 * self.feed_min, rapid_s=60.0 * self.rapid_min, tool_change_s=self.tool_change_s,
                         feed_mm=self.feed_mm, rapid_mm=self.rapid_mm, moves=self.moves)


def cycle_time(printed_moves, rapid_mm_min: float) -> CycleTime:
    """The cycle time of ``printed_moves`` (``Program.printed_moves``: the moves as the writer printed them, in
    order), rapids at ``rapid_mm_min`` (the post's)."""
    timer = MoveTimer(rapid_mm_min)
    timed = {"rapid": timer.rapid, "line": timer.line, "inverse": timer.inverse_time, "arc": timer.arc,
             "tool change": timer.tool_change}
    for kind, *args in printed_moves:
        if kind != "comment":  # a pass's opening comment (camcam.verify.motion_time splits passes by it)
            timed[kind](*args)
    return timer.result()
