"""The neutral tool path: moves a post prints, with no controller dialect in it.

:func:`contour_toolpath` turns a fitted contour into depth passes with
tangent lead-in/lead-out arcs, safe and clearance heights, optional roughing
at a finishing allowance and a spring pass.  :func:`rotary_toolpath` wraps a
developed polyline (x along the cam axis, y = arc length at ``radius_mm``) onto
the A axis for 4-axis cylindrical cams (inverse-time feeds are the writer's job).
"""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass, replace

import numpy as np

from camcam.errors import InputError
from camcam.toolpath.elements import Arc, Line, element_tangent

__all__ = ["Rapid", "Feed", "ArcMove", "Comment", "Pass", "PASS_KINDS", "Toolpath", "CutSettings", "contour_toolpath",
           "offset_elements", "rotary_toolpath", "slot_toolpath", "depth_levels", "join_toolpaths",
           "lead_pass_moves", "contour_moves", "shortest_rotation"]


@dataclass(frozen=True)
class Rapid:
    """G0 to (x, y, z) (and rotary ``a_deg``, tilt ``b_deg`` for 5-axis); ``None`` keeps an axis where it is."""

    x: float | None
    y: float | None
    z: float | None
    _: KW_ONLY
    a_deg: float | None = None
    b_deg: float | None = None


@dataclass(frozen=True)
class Feed:
    """G1 to (x, y, z) (and rotary ``a_deg``, tilt ``b_deg`` for 4/5-axis) at ``feed_mm_min``."""

    x: float | None
    y: float | None
    z: float | None
    feed_mm_min: float
    _: KW_ONLY
    a_deg: float | None = None
    length_mm: float = 0.0  # inverse-time feeds: path length (4-axis: at the reference radius; 5-axis: of the tool tip)
    b_deg: float | None = None


@dataclass(frozen=True)
class ArcMove:
    """G2/G3 in the XY plane to (x, y) about (cx, cy) at height z."""

    x: float
    y: float
    cx: float
    cy: float
    _: KW_ONLY
    ccw: bool
    z: float
    feed_mm_min: float


#: What a pass does: ``rough`` runs at a finishing allowance off the contour; ``finish`` cuts the
#: contour (at one depth level); ``spring`` repeats the final finish pass; ``slot`` runs inside a
#: groove where the tool's full width may engage (a groove's centre pass).
#: ``bore`` is the helical bore (from solid, so it may engage the full width too).
PASS_KINDS = ("rough", "finish", "spring", "slot", "bore")


@dataclass(frozen=True)
class Pass:
    """One pass of the tool along one contour at one depth: the record every consumer reads.

    Parameters
    ----------
    contour : int
        Index of the contour the pass follows (into the job's contours).
    kind : str
        One of :data:`PASS_KINDS`.
    z : float
        The pass depth: Z of the tool tip (disc cams, top face at 0), or its
        distance from the cam axis (4-axis cylindrical cams).
    moves : tuple
        The pass's moves, from the approach over its start to the retract.
    note : str
        How the pass is planned, where the kind does not say it all (a roughing
        spiral's turns): its comment and the pass table add it.
    direction : str
        "climb", "conventional" (the material on the right or left of travel with
        an M3 spindle, :mod:`camcam.nc.direction`), "both" (a full-width pass) or
        "" (not stated).
    cutting : str
        The pass's cutting data as stated (:mod:`camcam.nc.cutting_data`), or "".
    spindle_rpm : float or None
        The pass's spindle speed; the writer prints a change at the pass's start (None: as before).
    """

    contour: int
    kind: str
    z: float
    moves: tuple
    _: KW_ONLY
    note: str = ""
    direction: str = ""
    cutting: str = ""
    spindle_rpm: float | None = None

    def __post_init__(self) -> None:
        if self.kind not in PASS_KINDS:
            raise ValueError(f"kind: expected one of {PASS_KINDS}, got {self.kind!r}")

    @property
    def finishes(self) -> bool:
        """Whether the pass cuts the contour itself (not at a finishing allowance)."""
        return self.kind != "rough"


@dataclass(frozen=True)
class Comment:
    """A comment line between moves (a pass's name)."""

    text: str


@dataclass(frozen=True)
class Toolpath:
    """A frozen program in neutral form: its passes between a first and a last move (retracts).

    ``moves`` is every move in order: ``opening``, each pass's moves, ``closing``.
    """

    title: str
    passes: tuple[Pass, ...]
    spindle_rpm: float
    _: KW_ONLY
    tool_number: int = 1
    tool_diameter_mm: float = 0.0
    rotary: bool = False
    comments: tuple[str, ...] = ()
    opening: tuple = ()
    closing: tuple = ()
    five_axis: bool = False  # X Y Z A B with tool-centre-point control (the post's tcp_on/tcp_off)

    @property
    def moves(self) -> tuple:
        return self.opening + tuple(m for p in self.passes for m in p.moves) + self.closing

    @classmethod
    def of_moves(cls, title: str, moves, spindle_rpm: float, **kw) -> "Toolpath":
        """A toolpath of plain moves with no pass structure (tests, hand-made programs)."""
        return cls(title, (), spindle_rpm, opening=tuple(moves), **kw)


def join_toolpaths(title: str, paths) -> Toolpath:
    """One toolpath cutting ``paths`` in order: their passes, the first opening and the last closing.

    Every path must open and close the same way (retract to the safe height).
    """
    first = paths[0]
    comments = tuple(dict.fromkeys(c for p in paths for c in p.comments))
    passes = tuple(q for p in paths for q in p.passes)
    return Toolpath(title, passes, first.spindle_rpm, tool_number=first.tool_number,
                    tool_diameter_mm=first.tool_diameter_mm, rotary=first.rotary,
                    comments=comments, opening=first.opening, closing=paths[-1].closing)


def shortest_rotation(passes) -> tuple:
    """Rotary ``passes`` with A counting on: each pass's A words shifted by the whole turns that put its first
    A nearest to where the last pass left A, so that no move turns A back (for a controller that takes no
    rotary word in G0, :attr:`camcam.post.post.Post.rotary_rapid`).  A pass's rapids keep no A word.

    Examples
    --------
    >>> one = Pass(0, "slot", 40.0, (Rapid(20.0, 0.0, None), Feed(None, None, 40.0, 50.0, a_deg=0.0),
    ...                              Feed(20.0, None, 40.0, 300.0, a_deg=360.0), Rapid(None, None, 75.0)))
    >>> [m.a_deg for p in shortest_rotation((one, one)) for m in p.moves if isinstance(m, Feed)]
    [0.0, 360.0, 360.0, 720.0]
    """
    out, last = [], None
    for p in passes:
        first = next((m.a_deg for m in p.moves if getattr(m, "a_deg", None) is not None), None)
        shift = 0.0 if last is None or first is None else 360.0 * round((last - first) / 360.0)
        moves = tuple(replace(m, a_deg=None) if isinstance(m, Rapid) else
                      replace(m, a_deg=m.a_deg + shift) if getattr(m, "a_deg", None) is not None else m
                      for m in p.moves)
        out.append(replace(p, moves=moves))
        last = next((m.a_deg for m in reversed(moves) if getattr(m, "a_deg", None) is not None), last)
    return tuple(out)


@dataclass(frozen=True, kw_only=True)
class CutSettings:
    """How a contour is cut (mm, mm/min, rev/min).

    ``stock_side`` is the side of the direction of travel where the material
    is ("left" or "right"); leads and the finishing allowance go to the other.
    """

    depth_mm: float
    stepdown_mm: float
    feed_mm_min: float
    spindle_rpm: float
    plunge_feed_mm_min: float | None = None
    safe_z_mm: float = 25.0
    clearance_z_mm: float = 2.0
    top_z_mm: float = 0.0
    lead_radius_mm: float = 5.0
    stock_side: str = "right"
    finish_allowance_mm: float = 0.0
    spring_pass: bool = False
    tool_number: int = 1
    tool_diameter_mm: float = 0.0

    def __post_init__(self) -> None:
        checks = [
            ("depth_mm", self.depth_mm > 0, "> 0"), ("stepdown_mm", self.stepdown_mm > 0, "> 0"),
            ("feed_mm_min", self.feed_mm_min > 0, "> 0"), ("spindle_rpm", self.spindle_rpm > 0, "> 0"),
            ("lead_radius_mm", self.lead_radius_mm > 0, "> 0"),
            ("finish_allowance_mm", self.finish_allowance_mm >= 0, "≥ 0"),
            ("safe_z_mm", self.safe_z_mm >= self.clearance_z_mm > self.top_z_mm, "≥ clearance_z_mm > top_z_mm"),
            ("stock_side", self.stock_side in ("left", "right"), '"left" or "right"'),
        ]
        for name, ok, want in checks:
            if not ok:
                raise InputError(f"{name}: expected {want}, got {getattr(self, name)!r}")


def offset_elements(elements, distance_mm: float) -> tuple:
    """Offset a G1 contour by ``distance_mm`` to its left (negative: right); arcs stay arcs.

    Raises :class:`InputError` when an arc on the inner side would vanish.
    """
    out = []
    for e in elements:
        if isinstance(e, Line):
            t = element_tangent(e, False)
            n = np.array([-t[1], t[0]]) * distance_mm
            out.append(Line(tuple(np.add(e.start, n)), tuple(np.add(e.end, n))))
        else:
            r = e.radius - (distance_mm if e.ccw else -distance_mm)
            if r <= 1e-6:
                raise InputError(f"finish allowance {abs(distance_mm):g} mm exceeds an arc radius {e.radius:g} mm")
            c = np.asarray(e.centre)

            def move(p):
                d = np.subtract(p, c)
                return tuple(c + d / np.hypot(*d) * r)

            out.append(Arc(move(e.start), move(e.end), e.centre, e.ccw))
    return tuple(out)


def _pass_moves(elements, z, feed, plunge, lead, away_left, cs):
    """One depth pass: rapid over the lead-in start, plunge, lead-in arc, contour, lead-out arc, retract."""
    first, last = elements[0], elements[-1]
    p0 = np.asarray(first.start)
    t0 = element_tangent(first, False)
    s = 1.0 if away_left else -1.0
    n0 = s * np.array([-t0[1], t0[0]])
    c_in = p0 + lead * n0
    start = c_in - lead * t0
    p1 = np.asarray(last.end)
    t1 = element_tangent(last, True)
    n1 = s * np.array([-t1[1], t1[0]])
    c_out = p1 + lead * n1
    finish = c_out + lead * t1
    moves = [Rapid(float(start[0]), float(start[1]), None), Rapid(None, None, cs.clearance_z_mm),
             Feed(None, None, z, plunge),
             ArcMove(float(p0[0]), float(p0[1]), float(c_in[0]), float(c_in[1]), ccw=away_left, z=z, feed_mm_min=feed)]
    for e in elements:
        if isinstance(e, Line):
            moves.append(Feed(e.end[0], e.end[1], z, feed))
        else:
            moves.append(ArcMove(e.end[0], e.end[1], e.centre[0], e.centre[1], ccw=e.ccw, z=z, feed_mm_min=feed))
    moves.append(ArcMove(float(finish[0]), float(finish[1]), float(c_out[0]), float(c_out[1]), ccw=away_left, z=z,
                         feed_mm_min=feed))
    moves.append(Rapid(None, None, cs.clearance_z_mm))
    return moves


def lead_pass_moves(elements, z: float, cs: CutSettings) -> tuple:
    """One finish pass over ``elements`` at ``z`` with tangent lead arcs on the free side (``cs.stock_side``)."""
    plunge = cs.plunge_feed_mm_min or cs.feed_mm_min / 2
    return tuple(_pass_moves(tuple(elements), z, cs.feed_mm_min, plunge, cs.lead_radius_mm,
                             cs.stock_side == "right", cs))


def contour_moves(elements, z: float, feed_mm_min: float) -> list:
    """Feed moves along ``elements`` at height ``z`` (lines G1, arcs G2/G3)."""
    return _contour_moves(elements, z, feed_mm_min)


def depth_levels(cs: CutSettings, top_mm: float | None = None) -> list[float]:
    """Equal depth steps no deeper than ``stepdown_mm`` down to ``top − depth_mm``.

    ``top_mm`` is the surface the depth counts from (default ``cs.top_z_mm``;
    a cylindrical cam's blank radius for 4-axis passes).

    Examples
    --------
    >>> depth_levels(CutSettings(depth_mm=12, stepdown_mm=5, feed_mm_min=300, spindle_rpm=2000))
    [-4.0, -8.0, -12.0]
    """
    top = cs.top_z_mm if top_mm is None else top_mm
    n = max(1, math.ceil(cs.depth_mm / cs.stepdown_mm - 1e-9))
    return [top - cs.depth_mm * (k + 1) / n for k in range(n)]


def _contour_moves(elements, z, feed):
    moves = []
    for e in elements:
        if isinstance(e, Line):
            moves.append(Feed(e.end[0], e.end[1], z, feed))
        else:
            moves.append(ArcMove(e.end[0], e.end[1], e.centre[0], e.centre[1], ccw=e.ccw, z=z, feed_mm_min=feed))
    return moves


def slot_toolpath(elements, cs: CutSettings, title: str = "camcam", contour: int = 0, kind: str = "slot") -> Toolpath:
    """Depth passes along a contour inside a slot or groove: plunge at its start, no leads.

    For a groove both sides of the path are walls, so there is no free side
    for a lead arc; the plunge point lies in the groove (material the pass
    removes anyway).  ``spring_pass`` repeats the last pass; a finishing
    allowance does not apply (the flanks are cut by their own passes).
    ``kind`` is "slot" for a pass the tool's full width may engage (a
    groove's centre pass) or "finish" for a flank; ``contour`` indexes the
    job's contour in the passes.

    Examples
    --------
    >>> from camcam.toolpath.elements import Line
    >>> tp = slot_toolpath((Line((0.0, 0.0), (10.0, 0.0)),), CutSettings(depth_mm=6, stepdown_mm=3,
    ...                    feed_mm_min=300, spindle_rpm=2000))
    >>> sum(isinstance(m, Feed) for m in tp.moves)  # two plunges, two cuts
    4
    """
    if not elements:
        raise InputError("contour: no elements to cut")
    levels = depth_levels(cs)
    plunge = cs.plunge_feed_mm_min or cs.feed_mm_min / 2
    start = elements[0].start
    passes = []
    for z, k in [(z, kind) for z in levels] + ([(levels[-1], "spring")] if cs.spring_pass else []):
        moves = [Rapid(float(start[0]), float(start[1]), None), Rapid(None, None, cs.clearance_z_mm),
                 Feed(None, None, z, plunge)]
        moves += _contour_moves(elements, z, cs.feed_mm_min)
        moves.append(Rapid(None, None, cs.clearance_z_mm))
        passes.append(Pass(contour, k, z, tuple(moves)))
    return Toolpath(title, tuple(passes), cs.spindle_rpm, tool_number=cs.tool_number,
                    tool_diameter_mm=cs.tool_diameter_mm, rotary=False,
                    comments=(f"{len(levels)} depth passes to {levels[-1]:g} mm, plunged in the groove",),
                    opening=(Rapid(None, None, cs.safe_z_mm),), closing=(Rapid(None, None, cs.safe_z_mm),))


def contour_toolpath(elements, cs: CutSettings, title: str = "camcam", contour: int = 0) -> Toolpath:
    """Depth passes over a fitted contour (tool-centre elements in the direction of cut).

    Passes go down in equal steps no deeper than ``stepdown_mm``; with a
    finishing allowance every pass but a final full-depth pass runs offset away
    from the stock; ``spring_pass`` repeats the final pass.

    Examples
    --------
    >>> from camcam.toolpath.elements import Arc
    >>> c = (Arc((10.0, 0.0), (-10.0, 0.0), (0.0, 0.0), True), Arc((-10.0, 0.0), (10.0, 0.0), (0.0, 0.0), True))
    >>> tp = contour_toolpath(c, CutSettings(depth_mm=6, stepdown_mm=4, feed_mm_min=300, spindle_rpm=2000))
    >>> sum(isinstance(m, ArcMove) for m in tp.moves)
    8
    """
    if not elements:
        raise InputError("contour: no elements to cut")
    levels = depth_levels(cs)
    away_left = cs.stock_side == "right"
    plunge = cs.plunge_feed_mm_min or cs.feed_mm_min / 2
    allowance = cs.finish_allowance_mm > 0
    rough = offset_elements(elements, cs.finish_allowance_mm * (1 if away_left else -1)) \
        if allowance else tuple(elements)
    plan = [(rough, z, "rough" if allowance else "finish") for z in levels]
    plan += [(tuple(elements), levels[-1], "finish")] if allowance else []
    plan += [(tuple(elements), levels[-1], "spring")] if cs.spring_pass else []
    passes = tuple(Pass(contour, kind, z, tuple(_pass_moves(path, z, cs.feed_mm_min, plunge, cs.lead_radius_mm,
                                                             away_left, cs)))
                   for path, z, kind in plan)
    return Toolpath(title, passes, cs.spindle_rpm, tool_number=cs.tool_number, tool_diameter_mm=cs.tool_diameter_mm,
                    rotary=False,
                    comments=(f"{len(levels)} depth passes to {levels[-1]:g} mm",),
                    opening=(Rapid(None, None, cs.safe_z_mm),), closing=(Rapid(None, None, cs.safe_z_mm),))


def rotary_toolpath(points_xy, radius_mm: float, cs: CutSettings, title: str = "camcam",
                    developed_radius_mm: float | None = None, contour: int = 0, kind: str = "slot",
                    rotary_rapid: bool = True) -> Toolpath:
    """4-axis moves from a developed polyline: x stays X, y/radius becomes A (degrees).

    ``points_xy`` is (n, 2) on the developed plane at ``developed_radius_mm``
    (default ``radius_mm``; y = arc length there); each pass is one ``G1 X A``
    move per chord at the pass depth (Z = radius − depth from the axis, the
    blank's surface at ``radius_mm``); inverse-time lengths are the developed chords.

    A pass opens at the safe height with a rapid over its start, A turning there in the same G0
    (``rotary_rapid``; else A is left where it is: :func:`shortest_rotation`), a rapid down to
    the clearance plane and the plunge at the plunge feed (issue 47: the unwind from the last
    pass's A360 was a 10 s feed move, ``G1 Z52 A0 F6``).
    """
    pts = np.asarray(points_xy, float)
    if radius_mm <= 0:
        raise InputError(f"radius_mm: expected > 0, got {radius_mm!r}")
    dev_r = radius_mm if developed_radius_mm is None else developed_radius_mm
    if dev_r <= 0:
        raise InputError(f"developed_radius_mm: expected > 0, got {dev_r!r}")
    levels = depth_levels(cs, radius_mm)
    a = np.degrees(pts[:, 1] / dev_r)
    seg = np.hypot(*np.diff(pts, axis=0).T)
    plunge = cs.plunge_feed_mm_min or cs.feed_mm_min / 2
    passes = []
    for z in levels:
        moves = [Rapid(float(pts[0, 0]), 0.0, None,  # Y0: the tool axis through the cam axis
                       a_deg=float(a[0]) if rotary_rapid else None),
                 Rapid(None, None, radius_mm + cs.clearance_z_mm),
                 Feed(None, None, z, plunge, a_deg=float(a[0]), length_mm=cs.clearance_z_mm + radius_mm - z)]
        for k in range(1, len(pts)):
            moves.append(Feed(float(pts[k, 0]), None, z, cs.feed_mm_min, a_deg=float(a[k]),
                              length_mm=float(seg[k - 1])))
        moves.append(Rapid(None, None, radius_mm + cs.safe_z_mm))
        passes.append(Pass(contour, kind, z, tuple(moves)))
    return Toolpath(title, tuple(passes), cs.spindle_rpm, tool_number=cs.tool_number,
                    tool_diameter_mm=cs.tool_diameter_mm, rotary=True,
                    comments=(f"4-axis, developed at R{dev_r:g} mm",),
                    opening=(Rapid(None, None, radius_mm + cs.safe_z_mm),))
