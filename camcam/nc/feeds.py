"""Each pass's feed and spindle speed from its cutting data, held at the cutting edge.

With cutting data (``[machining] flutes``, :mod:`camcam.nc.cutting_data`) every pass runs at its kind's
spindle speed (``Pass.spindle_rpm``; the writer prints the change at the pass's start) and feed, and
its comment states the figures (``Pass.cutting``).  Without, the passes are left as planned.

**The feed at the cutting edge.**  The controller runs the programmed F along the tool centre's
path; the chip load belongs to the cutting edge, which on an arc of the tool centre of radius R runs
on radius R ∓ r_t: R − r_t where the material lies on the arc centre's side (a convex part: the
profile round its nose, the roughing spiral), R + r_t where it lies away from it (a concave part:
the bore, a groove's outer wall).  The edge's speed is the centre's × (R ∓ r_t)/R, so for the edge to
run at the pass feed F the centre runs at

    F_centre = F · R / (R ∓ r_t),

Sandvik Coromant's circular-interpolation rule written with the part's radius r = R ∓ r_t
(external: vf_centre = vf · (Dm + Dc)/Dm, internal: (Dm − Dc)/Dm; "the feed (r ± r_tool)/r" of
issue 47).  The issue's wording "on a convex contour the cutting edge runs faster than the programmed
tool-centre feed" has it the wrong way round: on a convex part the edge is on the inside of the
centre's arc and runs *slower* (at r/(r + r_t) of it), which is why the centre is sped up there.
The factor is held within [:data:`MIN_ARC_FACTOR`, :data:`MAX_ARC_FACTOR`] (a convex nose much
smaller than the tool, a concave corner nearly the tool's radius), and the centre feed is rounded
to whole mm/min, so an unchanged figure prints no new F word (F is modal), and at most the post's
``max_feed_mm_min`` where it states one.  Lines keep the pass
feed.  A pass cutting on both sides (a full-width slot) keeps the pass feed on its arcs.

**Engagement.**  A pass whose radial engagement ae exceeds the nominal stepover (a groove's
full-width centre pass and the helical bore from solid: ae = D) runs at the rough feed ×
max(stepover·D/ae, :data:`MIN_ENGAGEMENT_FACTOR`): the chip load stays the catalogue's for its
stepover where the tool is wrapped in more material (Tungaloy's standard conditions give slotting
about half the side-milling chip load, e.g. carbon steel ø10-12: 0.045-0.07 against 0.09-0.11 mm).
The roughing spiral and a groove's rough rings hold ae within the stepover by construction
(:mod:`camcam.nc.roughing`), so their feed is the rough feed.
"""

from __future__ import annotations

import math
from dataclasses import replace

from camcam.nc.settings import MachiningSpec
from camcam.toolpath.path import ArcMove, Feed

__all__ = ["with_cutting_data", "centre_feed", "arc_factor", "engagement_factor", "MAX_ARC_FACTOR",
           "MIN_ARC_FACTOR", "MIN_ENGAGEMENT_FACTOR", "FULL_WIDTH_KINDS"]

#: Largest centre-feed factor on an arc (a convex radius a third of the centre path's).
MAX_ARC_FACTOR = 3.0
#: Smallest centre-feed factor on an arc (a concave radius five times the centre path's).
MIN_ARC_FACTOR = 0.2
#: Smallest feed factor for an engagement over the stepover (slotting: about half the side-milling chip load).
MIN_ENGAGEMENT_FACTOR = 0.5
#: Pass kinds that engage the tool's full diameter.
FULL_WIDTH_KINDS = ("slot", "bore")


def arc_factor(radius_mm: float, tool_radius_mm: float, material_at_centre: bool) -> float:
    """R / (R ∓ r_t) within [MIN_ARC_FACTOR, MAX_ARC_FACTOR]: the centre's feed over the edge's.

    Examples
    --------
    >>> arc_factor(28.0, 8.0, True), arc_factor(24.0, 8.0, False)  # a Ø40 convex part, a Ø64 bore
    (1.4, 0.75)
    """
    edge = radius_mm - tool_radius_mm if material_at_centre else radius_mm + tool_radius_mm
    if edge <= radius_mm / MAX_ARC_FACTOR:
        return MAX_ARC_FACTOR
    return max(radius_mm / edge, MIN_ARC_FACTOR)


def centre_feed(feed_mm_min: float, arc: ArcMove, tool_radius_mm: float, material_side: str,
                max_feed_mm_min: float | None = None) -> float:
    """The tool-centre feed (whole mm/min) that runs the cutting edge at ``feed_mm_min`` on ``arc``, the material
    on ``material_side`` ("left" or "right") of travel; at most ``max_feed_mm_min`` (the post's, if it states one)."""
    radius = math.hypot(arc.x - arc.cx, arc.y - arc.cy)
    centre_side = "left" if arc.ccw else "right"
    f = float(round(feed_mm_min * arc_factor(radius, tool_radius_mm, material_side == centre_side)))
    return f if max_feed_mm_min is None else min(f, float(math.floor(max_feed_mm_min)))


def engagement_factor(kind: str, stepover: float) -> float:
    """The feed factor of a pass of ``kind`` for its radial engagement over the nominal ``stepover`` (× D).

    Examples
    --------
    >>> engagement_factor("slot", 0.4), engagement_factor("slot", 0.6), engagement_factor("rough", 0.4)
    (0.5, 0.6, 1.0)
    """
    if kind not in FULL_WIDTH_KINDS:
        return 1.0
    return max(stepover / 1.0, MIN_ENGAGEMENT_FACTOR)  # ae = D: the nominal stepover·D over it


def _cutting(m: MachiningSpec, move) -> bool:
    """Whether ``move`` is one of the planned cutting moves (at the single feed), not a plunge."""
    if not isinstance(move, (Feed, ArcMove)) or move.feed_mm_min != m.feed_mm_min:
        return False
    vertical = isinstance(move, Feed) and move.x is None and move.y is None
    return not (vertical and m.plunge_feed_mm_min == m.feed_mm_min)


def with_cutting_data(passes, m: MachiningSpec) -> tuple:
    """``passes`` at their kinds' cutting data (unchanged without ``[machining] flutes``); see the module notes."""
    if not m.cutting:
        return tuple(passes)
    r_t = m.tool_diameter_mm / 2
    out = []
    for p in passes:
        data = m.cutting_for(p.kind)
        k = engagement_factor(p.kind, m.stepover)
        feed = float(round(data.feed_mm_min * k))
        side = {"climb": "right", "conventional": "left"}.get(p.direction)
        moves = []
        for mv in p.moves:
            if _cutting(m, mv):
                f = centre_feed(feed, mv, r_t, side, m.post.max_feed_mm_min) if isinstance(mv, ArcMove) and side \
                    else feed
                mv = replace(mv, feed_mm_min=f)
            moves.append(mv)
        text = data.describe() + (f", F x {k:g} for full-width engagement (stepover {m.stepover:g} x D): F{feed:g}"
                                  if k != 1.0 else "")
        text += ", edge feed on arcs" if side and any(isinstance(mv, ArcMove) for mv in moves) else ""
        out.append(replace(p, moves=tuple(moves), spindle_rpm=data.rpm, cutting=text))
    return tuple(out)
