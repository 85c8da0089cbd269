"""Climb or conventional milling (``[machining] direction``): which way round a contour the tool runs.

The spindle turns clockwise seen from above (``M3``: every post's header
starts it so).  At the cutting edge a clockwise tool's tooth moves against the
tool's travel on its right-hand side, so with the material on the right of
the direction of travel the tooth enters the chip at its thickest and leaves
it thin: climb (down) milling; with the material on the left it is
conventional (up) milling (the G41-with-M3-is-climb rule of every controller
manual, e.g. LinuxCNC's "Cutter Compensation" page).

Around an outside contour (a disc cam's profile) climb is clockwise about the
part; around an inside one (the bore, a groove's inner wall seen from the
groove) counter-clockwise.  A pass whose tool engages on both sides (a
groove's full-width centre pass, ``slot``) is both, and is left as planned.
"""

from __future__ import annotations

from camcam.nc.settings import DIRECTIONS
from camcam.toolpath.elements import Arc, Line

__all__ = ["DIRECTIONS", "material_side", "reverse_elements", "direction_of", "orient"]


def material_side(direction: str) -> str:
    """The side of travel the material must be on ("right" or "left") for ``direction`` with an M3 spindle.

    Examples
    --------
    >>> material_side("climb"), material_side("conventional")
    ('right', 'left')
    """
    if direction not in DIRECTIONS:
        raise ValueError(f"direction: expected one of {DIRECTIONS}, got {direction!r}")
    return "right" if direction == "climb" else "left"


def direction_of(side: str) -> str:
    """"climb", "conventional" or "both" for a pass with the material on ``side`` ("right", "left", "both").

    Examples
    --------
    >>> direction_of("right"), direction_of("both")
    ('climb', 'both')
    """
    return {"right": "climb", "left": "conventional"}.get(side, "both")


def reverse_elements(elements) -> tuple:
    """The same closed or open chain run the other way: reversed order, each line and arc turned round.

    Examples
    --------
    >>> reverse_elements((Line((0.0, 0.0), (1.0, 0.0)), Arc((1.0, 0.0), (0.0, 1.0), (0.0, 0.0), True)))
    (Arc(start=(0.0, 1.0), end=(1.0, 0.0), centre=(0.0, 0.0), ccw=False), Line(start=(1.0, 0.0), end=(0.0, 0.0)))
    """
    return tuple(Line(e.end, e.start) if isinstance(e, Line) else Arc(e.end, e.start, e.centre, not e.ccw)
                 for e in reversed(tuple(elements)))


def orient(elements, side: str, direction: str) -> tuple[tuple, str]:
    """``elements`` with the material on ``side`` of travel, turned round if ``direction`` needs the other side:
    (elements, the material's side of the returned travel).  A two-sided pass (``side`` "both") stays."""
    if side not in ("left", "right"):
        return tuple(elements), side
    want = material_side(direction)
    return (tuple(elements), side) if side == want else (reverse_elements(elements), want)
