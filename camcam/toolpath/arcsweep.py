"""Arcs within a post's largest sweep per block, as printed.

A post allows at most ``max_arc_sweep_deg`` per arc block (120° on the
bundled posts; some controllers refuse more, and an R-format arc is
ambiguous at 180°).  A planner that makes an arc of exactly the limit does
not meet it: rounding the ends and the centre to the post's grid moves each
end's angle by up to ~√2·10⁻ᵈ/r, and the controller then sweeps a hair more
(issue 43: ``sweeps 120.000° > max_arc_sweep_deg 120`` on a dwell-only cam,
whose contour is a circle fitted as three 120° arcs).

So the limit is judged where it counts, on the arc the controller cuts from
the printed numbers (:func:`printed_sweep_rad`, the same function the post's
writer checks every arc with), and an arc over it is cut into the fewest
equal parts on its own circle that each print within it
(:func:`within_sweep`).  The parts lie on the arc they replace (a printed
arc's end radius is kept: the radius is interpolated in angle, the spiral
a controller cuts), so a contour measured after the split is the contour
that is printed.

Examples
--------
>>> from camcam.toolpath.quantizer import Quantizer
>>> q = Quantizer(4)
>>> third = Arc((48.0, 0.0), (-24.0, 41.569219381653), (0.0, 0.0), True)   # 120° of a circle
>>> round(math.degrees(printed_sweep_rad(third, q)), 6) > 120.0
True
>>> parts = within_sweep((third,), q, 120.0)
>>> len(parts), all(math.degrees(printed_sweep_rad(p, q)) <= 120.0 for p in parts)
(2, True)
"""

from __future__ import annotations

import math

from camcam.toolpath.elements import Arc
from camcam.toolpath.quantizer import Quantizer

__all__ = ["printed_sweep_rad", "split_arc", "within_sweep", "parts_within", "passes_within_sweep"]


def printed_sweep_rad(arc: Arc, quantizer: Quantizer) -> float:
    """The sweep (rad) of ``arc`` as the controller cuts it from the printed ends, centre or R word."""
    return quantizer.printed_elements((arc,))[0].sweep


def split_arc(arc: Arc, parts: int) -> tuple[Arc, ...]:
    """``arc`` cut into ``parts`` equal sweeps; the joints on the arc (radius interpolated in angle between
    the start and end radii, as the controller cuts a printed arc), the last part ending at ``arc.end``.

    Examples
    --------
    >>> a, b = split_arc(Arc((1.0, 0.0), (-1.0, 0.0), (0.0, 0.0), True), 2)
    >>> tuple(round(v, 12) + 0.0 for v in a.end), b.end
    ((0.0, 1.0), (-1.0, 0.0))
    """
    if parts == 1:
        return (arc,)
    cx, cy = arc.centre
    a0, sweep, r0, r1 = arc.start_angle, arc.sweep, arc.radius, arc.end_radius
    sign = 1.0 if arc.ccw else -1.0
    joints = [arc.start]
    for k in range(1, parts):
        u = k / parts
        r = r0 + (r1 - r0) * u
        a = a0 + sign * sweep * u
        joints.append((cx + r * math.cos(a), cy + r * math.sin(a)))
    joints.append(arc.end)
    return tuple(Arc(p, q, arc.centre, arc.ccw) for p, q in zip(joints[:-1], joints[1:]))


def parts_within(arc: Arc, quantizer: Quantizer, max_sweep_deg: float) -> tuple[Arc, ...]:
    """``arc`` itself if it prints within ``max_sweep_deg``, else the fewest equal parts that each do.

    The count starts one below the exact sweep over the limit and grows until every
    printed part is within it (one more part is enough but for arcs of a few
    grid steps' radius, where rounding turns angles by whole degrees).  It starts
    one below because rounding may also turn the other way: a 271° arc of radius
    0.25 mm on a 0.01 mm grid prints within 90° in three parts of 90.33° (found by
    hypothesis, ``tests/toolpath/test_arcsweep.py``).
    """
    limit = math.radians(max_sweep_deg)
    if printed_sweep_rad(arc, quantizer) <= limit:
        return (arc,)
    parts = max(2, math.ceil(arc.sweep / limit) - 1)
    while True:
        split = split_arc(arc, parts)
        if all(printed_sweep_rad(p, quantizer) <= limit for p in split):
            return split
        parts += 1
        if parts > 360:
            raise ValueError(f"an arc of radius {arc.radius:g} mm cannot be printed in parts within "
                             f"{max_sweep_deg:g}° on a {quantizer.step_mm:g} mm grid")


def within_sweep(elements, quantizer: Quantizer, max_sweep_deg: float) -> tuple:
    """``elements`` with every arc over ``max_sweep_deg`` as printed cut into parts (:func:`parts_within`);
    lines and arcs within it are kept as they are (the same objects)."""
    out = []
    for e in elements:
        if isinstance(e, Arc):
            out.extend(parts_within(e, quantizer, max_sweep_deg))
        else:
            out.append(e)
    return tuple(out)


def passes_within_sweep(passes, quantizer: Quantizer, max_sweep_deg: float) -> tuple:
    """``passes`` (:class:`~camcam.toolpath.path.Pass`, in program order) with every
    :class:`~camcam.toolpath.path.ArcMove` over ``max_sweep_deg`` as printed cut into parts
    (:func:`parts_within`): lead arcs, roughing spirals, ramps.  Each arc starts where the moves before
    it end, across passes.  A helical arc's drop is shared out equally over its equal parts, so a
    ramp's slope stays as planned."""
    from dataclasses import replace

    from camcam.toolpath.path import ArcMove, Comment  # the moves' types; path does not import this module

    at = [None, None, None]
    out = []
    for ps in passes:
        moves = []
        for m in ps.moves:
            if isinstance(m, ArcMove) and None not in at[:2] and (at[0], at[1]) != (m.x, m.y):
                parts = parts_within(Arc((at[0], at[1]), (m.x, m.y), (m.cx, m.cy), m.ccw), quantizer, max_sweep_deg)
                z0 = m.z if at[2] is None else at[2]
                moves += [m] if len(parts) == 1 else [
                    ArcMove(p.end[0], p.end[1], m.cx, m.cy, ccw=m.ccw, z=m.z if k == len(parts) else
                            z0 + (m.z - z0) * k / len(parts), feed_mm_min=m.feed_mm_min) for k,
                                                      p in enumerate(parts, 1)]
            else:
                moves.append(m)
            if not isinstance(m, Comment):
                at = [v if v is not None else a for v, a in zip((m.x, m.y, m.z), at)]
        out.append(ps if len(moves) == len(ps.moves) else replace(ps, moves=tuple(moves)))
    return tuple(out)
