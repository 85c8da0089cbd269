"""Passes of a disc or face-groove job: what each one cuts, at which depth, with which moves.

Every pass opens with a :class:`~camcam.toolpath.path.Comment` that names it
(``pass 3/9: rough, Z-6``); the material-removal check reads these names back
from the printed program (and rs274's ``COMMENT`` lines) to know which passes
may slot.

* ``rough``: a spiral from the blank to the finish allowance at one depth
  level (:func:`spiral_moves`), entered outside the material (its contour
  is the profile it roughs to); a narrower tool's rough offsets in a groove;
* ``finish``, ``spring``: the fitted contour with tangent lead arcs on the
  free side, exactly as before roughing existed;
* ``slot``: a groove's centre pass with a tool as wide as the groove: full
  engagement allowed, ramped down along the contour;
* ``bore``: the helical bore (:mod:`camcam.nc.bore`), a slot too.

Groove passes (slot, rough offsets, flanks) are ramped down along their contour, each ramp ending at
one of its joints (:func:`ramp_loop_passes`): every move is a whole fitted element.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from camcam.nc.roughing import Spiral
from camcam.toolpath.elements import Line
from camcam.toolpath.path import (ArcMove, Comment, CutSettings, Feed, Pass, Rapid, contour_moves,
                                  lead_pass_moves)

__all__ = ["SLOT_KINDS", "spiral_moves", "finish_moves", "ramp_loop_passes", "with_markers",
           "MARKER_PREFIX"]

#: Pass kinds whose tool may engage its full diameter.
SLOT_KINDS = ("slot", "bore")

#: How a pass's comment starts; the removal check parses ``pass i/n: kind``.
MARKER_PREFIX = "pass "


def spiral_moves(sp: Spiral, z: float, cs: CutSettings) -> tuple:
    """Rapid over the entry (outside the blank), plunge there, feed onto the spiral, spiral, retract."""
    plunge = cs.plunge_feed_mm_min or cs.feed_mm_min / 2
    s = sp.elements[0].start
    moves = [Rapid(sp.entry[0], sp.entry[1], None), Rapid(None, None, cs.clearance_z_mm), Feed(None, None, z, plunge),
             Feed(float(s[0]), float(s[1]), z, cs.feed_mm_min)]
    moves += contour_moves(sp.elements, z, cs.feed_mm_min)
    moves.append(Rapid(None, None, cs.clearance_z_mm))
    return tuple(moves)


def finish_moves(elements, z: float, cs: CutSettings) -> tuple:
    """The fitted contour at ``z`` with tangent lead arcs on the free side (``cs.stock_side``)."""
    return lead_pass_moves(elements, z, cs)


def _ramp(elements, z0: float, z1: float, feed: float) -> list:
    """Moves along ``elements`` descending linearly in arc length from z0 to z1 (helical arcs)."""
    lengths = np.array([e.length for e in elements])
    ends = z0 + (z1 - z0) * np.cumsum(lengths) / lengths.sum()
    out = []
    for e, z in zip(elements, ends):
        z = float(z)
        if isinstance(e, Line):
            out.append(Feed(e.end[0], e.end[1], z, feed))
        else:
            out.append(ArcMove(e.end[0], e.end[1], e.centre[0], e.centre[1], ccw=e.ccw, z=z, feed_mm_min=feed))
    return out


def _whole_elements(elements, lengths, i: int, run: float) -> tuple[tuple, int]:
    """Whole elements of a closed contour from index ``i`` on (cyclically, laps over if need be) until their
    length reaches ``run``; and the index after the last one."""
    out, acc, n = [], 0.0, len(elements)
    while acc < run:
        out.append(elements[i])
        acc += lengths[i]
        i = (i + 1) % n
    return tuple(out), i


def _start_joint(lengths, runs) -> int:
    """The joint of a closed contour (element index) to start its ramps from: the one whose ramps, each of at
    least its run in ``runs`` and ending at the first joint at or past it, from where the last ended, add up
    to the least length (the first such index on a tie).

    Examples
    --------
    >>> _start_joint([3.0, 1.0, 3.0, 1.0], [4.5])  # from joint 1 or 3: 1 + 3 + 1 = 5; from 0 or 2: 3 + 1 + 3 = 7
    1
    """
    cum = np.concatenate([[0.0], np.cumsum(lengths)])
    total = float(cum[-1])
    laps = math.ceil((sum(runs) + len(runs) * max(lengths)) / total) + 2  # each ramp overshoots < one element
    unrolled = np.concatenate([cum[:-1] + k * total for k in range(laps)] + [[laps * total]])
    pos = cum[:-1].copy()
    for r in runs:
        pos = unrolled[np.searchsorted(unrolled, pos + r, side="left")]
    return int(np.argmin(pos - cum[:-1]))


def ramp_loop_passes(contour: int, kind: str, elements, levels, z_top: float, ramp_angle_deg: float,
                     cs: CutSettings, spring: bool) -> list[Pass]:
    """A closed contour cut down to each level: ramp along it (≤ ``ramp_angle_deg``), then one full lap.

    The ramp of the next level starts where the lap ended, so the tool winds
    down without leaving the groove; ``spring`` repeats the last lap.

    A ramp ends at a joint of the contour, the first at or past the length its
    drop needs at the ramp angle, so it may be a little shallower than the
    angle.  Every move is then one of the fitted elements, each measured as
    printed; a ramp cut inside an element would add a point no fit measured,
    rounded to the post's grid (case 49:29 of ``benchmarks/anycam.py``: a dwell
    arc's printed spiral cut at a point 0.0012 mm off it, the pieces 0.0047 mm
    from the groove's centre at a tolerance of 0.0043 mm).  The ramps start at
    the joint from which they overshoot their runs least (:func:`_start_joint`).
    """
    plunge = cs.plunge_feed_mm_min or cs.feed_mm_min / 2
    lengths = [e.length for e in elements]
    if not sum(lengths) > 0:
        raise ValueError(f"contour {contour}: a closed contour of length {sum(lengths):g} mm cannot be ramped along")
    slope = math.tan(math.radians(ramp_angle_deg))
    # a hair longer than the drop needs: the printed slope stays under the limit
    runs = [(z_prev - z) / slope * (1 + 1e-9) for z_prev, z in zip([z_top, *levels[:-1]], levels)]
    i = _start_joint(lengths, runs)  # the joint the ramps overshoot their runs least from
    p0 = elements[i].start
    head = [Rapid(float(p0[0]), float(p0[1]), None), Rapid(None, None, cs.clearance_z_mm),
            Feed(None, None, z_top, plunge)]
    passes, z_prev = [], z_top
    for k, (z, run) in enumerate(zip(levels, runs)):
        moves = list(head) if k == 0 else []
        ramp, i = _whole_elements(elements, lengths, i, run)
        moves += _ramp(ramp, z_prev, z, cs.feed_mm_min)
        lap = tuple(elements[i:]) + tuple(elements[:i])
        moves += contour_moves(lap, z, cs.feed_mm_min)
        passes.append(Pass(contour, kind, z, tuple(moves)))
        z_prev = z
    passes[-1] = Pass(contour, kind, levels[-1], passes[-1].moves + (Rapid(None, None, cs.clearance_z_mm),))
    if spring:
        start = lap[0].start
        moves = [Rapid(float(start[0]), float(start[1]), None), Rapid(None, None, cs.clearance_z_mm),
                 Feed(None, None, levels[-1], plunge)] + contour_moves(lap, levels[-1], cs.feed_mm_min)
        moves.append(Rapid(None, None, cs.clearance_z_mm))
        passes.append(Pass(contour, "spring", levels[-1], tuple(moves)))
    return passes


def with_markers(passes, labels) -> tuple:
    """``passes``, each opened by a comment naming it:
    ``pass i/n: kind, contour label, Z…[, direction][, note][, cutting data]``."""
    n = len(passes)
    return tuple(replace(p, moves=(Comment(f"{MARKER_PREFIX}{i + 1}/{n}: {p.kind}, {labels[p.contour]}, Z{p.z:g}"
                                           + "".join(f", {t}" for t in (p.direction, p.note, p.cutting) if t)),)
                         + p.moves)
                 for i, p in enumerate(passes))
