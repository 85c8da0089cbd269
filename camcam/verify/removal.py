"""The material-removal check: the interpreted program against the blank, 2.5-D, at every Z level.

The moves come from the printed numbers (:func:`camcam.post.readback.read_program`
in process, or rs274's canonical output in the tests).  The material is kept
as one shapely region per slab between consecutive cutting levels (the
constant-Z feed heights, from the blank's top down); a flat end mill whose tip
is at or below a slab's bottom removes the disc it sweeps from that slab.
Along every feed move, sampled every :data:`SAMPLE_MM`:

* **engagement**: the width, across the direction of travel, of the material
  the tool's leading half meets (points of its front semicircle, at
  :data:`PROBE_INSET_MM` inside the edge, that lie in the material of a slab
  above the tip).  Side milling at a step ``ae`` gives ``ae``, a slot the full
  diameter.  Held to the stepover except in passes of a slot kind;
* **plunge**: a feed move descending steeper than the ramp angle (beyond the
  printed rounding) while the tool's disc overlaps material in a slab it
  enters;
* **rapid**: a G0 whose swept disc overlaps material of a slab above its tip.

The cut part is measured exactly on the printed path, not on the slabs:
``material left`` is the largest distance, beyond the tool radius, from a
point of the design boundary (sampled from the exact curves) to the nearest
feed path at the final depth, and ``overcut`` the deepest the tool's disc
reaches into the part from any feed move below the top.  Any slab material
left more than the tolerance off the part (a corner the roughing missed)
counts as material left too, measured against the part as measuring polygons
whose chords keep within the budget's ``polygon_share`` of the tolerance
whatever the cam's size (:func:`design_keep`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

import numpy as np
import shapely
from shapely import affinity

from camcam.workers import ChildGroup, resolve
from camcam.nc.passes import SLOT_KINDS
from camcam.post.readback import read_program
from camcam.nc.roughing import polygon_distance
from camcam.nc.stock import measuring_circle, measuring_polygon
from camcam.verify.swept import PROBE_INSET_MM, SAMPLE_MM, TOUCH_MM, moves_of, parse_marker, sweep_slabs, where
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.verdict import Check

if TYPE_CHECKING:  # imported where a tree is built (_tree)
    from scipy.spatial import cKDTree

__all__ = ["RemovalReport", "check_moves", "check_program", "SAMPLE_MM", "PROBE_INSET_MM", "parse_marker"]

#: Spacing of path samples for the material-left / overcut distances (mm): error (h/2)²/(2 r_t), < 1e-5 mm.
DENSE_MM = 0.02
#: Points a leaf of the material check's k-d trees holds (:func:`_tree`).
TREE_LEAF = 64
#: The material-left search looks first at path points this far beyond the tool radius from the part (mm):
#: a finishing pass; the boundary points it leaves farther are searched among all (the same figure).
LEFT_FIRST_MM = 0.1

@dataclass(frozen=True, kw_only=True)
class RemovalReport:
    """The figures of the check (mm, degrees); ``*_where`` name the pass and the point."""

    tool_radius_mm: float
    stepover_mm: float
    ramp_angle_deg: float
    tolerance_mm: float
    allowance_mm: float
    levels: tuple[float, ...]
    passes: int
    max_engagement_mm: float
    engagement_where: str
    max_slot_engagement_mm: float
    plunges: int
    plunge_where: str
    rapid_touches: int
    rapid_where: str
    material_left_mm: float
    left_where: str
    overcut_mm: float
    overcut_where: str
    rough_clearance_mm: float | None
    rough_clearance_where: str
    #: the largest chord error of the polygons the material is measured against (:func:`design_keep`)
    polygon_error_mm: float = 0.0

    def checks(self) -> tuple[Check, ...]:
        out = [
            Check("plunges into material", float(self.plunges), 0.0, "moves", ok=self.plunges == 0,
                  where=self.plunge_where, advice="enter outside the material or ramp at the ramp angle"),
            Check("rapids touching material", float(self.rapid_touches), 0.0, "moves", ok=self.rapid_touches == 0,
                  where=self.rapid_where, advice="raise clearance_z above the blank"),
            Check("radial engagement", self.max_engagement_mm, self.stepover_mm, "mm",
                  ok=self.max_engagement_mm <= self.stepover_mm + TOUCH_MM, where=self.engagement_where,
                  advice=self._engagement_advice()),
            Check("material left over the profile", self.material_left_mm, self.tolerance_mm, "mm",
                  ok=self.material_left_mm <= self.tolerance_mm, where=self.left_where,
                  advice="the finish pass does not reach the profile: check the stock and the depth"),
            Check("overcut into the profile", self.overcut_mm, self.tolerance_mm, "mm",
                  ok=self.overcut_mm <= self.tolerance_mm, where=self.overcut_where,
                  advice="a pass cuts into the part: check the stock, the tool and the allowance"),
        ]
        if self.rough_clearance_mm is not None:
            out.append(Check("roughing stock over the profile (at least the allowance)", self.rough_clearance_mm,
                             self.allowance_mm, "mm", ok=self.rough_clearance_mm >= self.allowance_mm - TOUCH_MM,
                             where=self.rough_clearance_where, advice="report a bug: the roughing came too close"))
        return tuple(out)

    def _engagement_advice(self) -> str:
        """The way out of an engagement over the stepover, by the pass that meets it.

        A roughing spiral plans its turns within the stepover, concave stretches included
        (:func:`camcam.nc.roughing.loops_needed`): an excess there is a fault of that plan, and a lower
        stepover brings the turns closer together (the engagement falls with it).  A finishing pass takes the
        allowance, which wraps round the tool where the profile bends inward to about its radius.
        """
        kind = self.engagement_where.split(":", 1)[1].split(",")[0].strip() if ":" in self.engagement_where else ""
        if kind == "rough":
            return "lower [machining] stepover (the roughing should have held it: please report this spec)"
        return ("the finishing pass meets the allowance wrapped round the tool in a concave corner: "
                "lower [machining] finish_allowance or use a smaller tool")

    def as_dict(self) -> dict:
        return {
            "tool_radius_mm": self.tool_radius_mm, "stepover_mm": self.stepover_mm,
            "ramp_angle_deg": self.ramp_angle_deg, "tolerance_mm": self.tolerance_mm,
            "finish_allowance_mm": self.allowance_mm, "levels_mm": list(self.levels), "passes_checked": self.passes,
            "max_engagement_mm": self.max_engagement_mm, "max_engagement_where": self.engagement_where,
            "max_slot_engagement_mm": self.max_slot_engagement_mm,
            "plunges_into_material": self.plunges, "plunge_where": self.plunge_where,
            "rapids_touching_material": self.rapid_touches, "rapid_where": self.rapid_where,
            "material_left_mm": self.material_left_mm, "material_left_where": self.left_where,
            "overcut_mm": self.overcut_mm, "overcut_where": self.overcut_where,
            "rough_clearance_mm": self.rough_clearance_mm, "rough_clearance_where": self.rough_clearance_where,
            "measuring_polygon_error_mm": self.polygon_error_mm,
        }


def check_moves(events, region, top_z: float, keep, boundary: np.ndarray, tool_radius_mm: float, stepover_mm: float,
                ramp_angle_deg: float, tolerance_mm: float, allowance_mm: float, decimals: int,
                slot_kinds=SLOT_KINDS, workers: int = 1) -> RemovalReport:
    """Check interpreted ``events`` (moves and comment strings) against the blank ``region`` (shapely).

    ``keep`` is the material that must remain at the final depth (shapely),
    ``boundary`` dense points (n, 2) on the parts of its outline the program
    machines (from the exact curves); the slabs are swept by ``workers``
    processes (:func:`~camcam.verify.swept.sweep_slabs`: the same figures for any count), and with more
    than one the figures at the finished surface are measured in a child of their own beside them.
    """
    r_t = tool_radius_mm
    keep = shapely.Polygon(keep) if keep.geom_type == "Polygon" else shapely.MultiPolygon(keep)
    shapely.prepare(keep)
    moves = moves_of(events)
    cut_moves = [m for m in moves if m.kind != "rapid"]
    levels = sorted({round(m.p1[2], 6) for m in cut_moves if m.p0[2] == m.p1[2] and m.p1[2] < top_z - 1e-9},
                    reverse=True)
    bounds = [top_z] + levels
    slabs = [shapely.Polygon(region) for _ in levels]
    for s in slabs:
        shapely.prepare(s)
    rounding = 2 * 10.0 ** -decimals
    slope = math.tan(math.radians(ramp_angle_deg))
    passes = len({m.pass_label for m in moves if m.pass_label})
    # the figures at the finished surface need only the moves and the part, not the slabs: with workers to
    # spare they are computed in a child process beside the move-by-move removal below (the same call, the
    # same figures; stopped if the removal fails), else in this one (a fork costs system CPU: its
    # copied page tables and pages)
    at_finish = (cut_moves, levels, top_z, keep, boundary, r_t)
    with ChildGroup() as finishing:
        finish = finishing.later(_finish_figures, *at_finish) if workers > 1 else _finish_figures(*at_finish)
        swept = sweep_slabs(moves, slabs, bounds, r_t, slope, rounding, slot_kinds, workers)
        left, left_at, over, over_at, clearance, clear_at = resolve(finish)
    keep_band = keep.buffer(tolerance_mm, quad_segs=32)
    # the feed moves' tool centres every DENSE_MM, sampled once for every slab that needs them (not once a slab)
    path = functools.cache(lambda: np.concatenate([np.empty((0, 3)), *(m.samples(DENSE_MM) for m in cut_moves)]))
    for i, s in enumerate(swept.slabs):
        rest = s.difference(keep_band)
        if rest.area <= 1e-6:
            continue
        # the slabs are polygons: a swept disc falls short of its circle by r_t·(1 − cos(π/128)) (3.0e-3 mm
        # for a Ø20 mm tool), more than a fine tolerance, so a piece of what is left counts only if some point
        # of it (a vertex or a point inside) is exactly uncut, measured on the moves themselves (:func:`_uncut`);
        # a sliver between a disc's polygon and its circle has none.  A piece that counts is measured at its
        # vertices, as before (disc-groove at 0.001 mm said FAIL on such slivers: 0.001708 mm "left" where
        # the tool had cut; tests/nc/test_removal.py has the case).
        pieces = shapely.get_parts(rest)
        pts, owner = shapely.get_coordinates(pieces, return_index=True)
        dist = polygon_distance(keep, pts)  # shapely.distance's figures, through an R-tree of keep's edges
        j = _first_uncut(pieces, pts, owner, dist, left, lambda: _centre_tree(path(), bounds[i + 1]), r_t)
        if j is not None:
            left = float(dist[j])
            left_at = (f"slab Z{bounds[i + 1]:g}…Z{bounds[i]:g}: material at X{pts[j, 0]:.3f} Y{pts[j, 1]:.3f} "
                       "not cut")
    return RemovalReport(tool_radius_mm=r_t, stepover_mm=stepover_mm, ramp_angle_deg=ramp_angle_deg,
                         tolerance_mm=tolerance_mm, allowance_mm=allowance_mm, levels=tuple(levels), passes=passes,
                         max_engagement_mm=swept.engagement_mm, engagement_where=swept.engagement_where,
                         max_slot_engagement_mm=swept.slot_engagement_mm, plunges=swept.plunges,
                         plunge_where=swept.plunge_where, rapid_touches=swept.rapids, rapid_where=swept.rapid_where,
                         material_left_mm=left, left_where=left_at, overcut_mm=over, overcut_where=over_at,
                         rough_clearance_mm=clearance, rough_clearance_where=clear_at)


def _first_uncut(pieces, pts: np.ndarray, owner: np.ndarray, dist: np.ndarray, left: float, centres, r_t: float):
    """Of the ``pieces`` a slab leaves (their vertices ``pts`` (n, 2), each vertex's piece ``owner``, ascending,
    and its distance ``dist`` from the part), the farthest-reaching one farther than ``left`` that is really
    there: some probe of it (a vertex, or a point inside) outside every tool disc (:func:`_uncut`; ``centres()``
    makes the tree, only when a piece is to be probed).  Returns the index into ``pts`` of that piece's
    farthest vertex, or None.

    Every candidate's probes are measured in one query: the same verdicts as piece by piece, farthest first
    (a slab strewn with slivers leaves a thousand pieces; tests/nc/test_removal.py keeps that search as the
    oracle).
    """
    top = np.full(len(pieces), -np.inf)
    np.maximum.at(top, owner, dist)
    order = np.argsort(-top, kind="stable")
    reach = order[top[order] > left]  # the farthest first
    if len(reach) == 0:
        return None
    first = np.searchsorted(owner, np.arange(len(pieces) + 1))  # a piece's vertices: pts[first[k]:first[k + 1]]
    inside = shapely.point_on_surface(pieces[reach])
    n_in = (~shapely.is_empty(inside)).astype(int)  # a degenerate piece may have no point inside
    inner = shapely.get_coordinates(inside)  # one row a point that is not empty, in the pieces' order
    at = np.cumsum(n_in) - n_in
    probes, group = [], []
    for r, k in enumerate(reach.tolist()):
        probes += [pts[first[k]:first[k + 1]], inner[at[r]:at[r] + n_in[r]]]
        group.append(np.full(first[k + 1] - first[k] + n_in[r], r))
    uncut = np.zeros(len(reach), bool)
    np.logical_or.at(uncut, np.concatenate(group), _uncut(centres(), np.vstack(probes), r_t))
    if not uncut.any():
        return None
    k = int(reach[np.argmax(uncut)])
    return int(first[k] + np.argmax(dist[first[k]:first[k + 1]]))


def _centre_tree(path: np.ndarray, floor_z: float):
    """A k-d tree of the tool-centre points ``path`` (n, 3) (every :data:`DENSE_MM` along the feed moves) where
    the tool is at or below ``floor_z`` (the criterion :func:`_remove` cuts a slab by); None if there are none."""
    centres = path[path[:, 2] <= floor_z + 1e-6, :2]
    return _tree(centres) if len(centres) else None


def _uncut(tree, pts: np.ndarray, r_t: float) -> np.ndarray:
    """Which ``pts`` (n, 2) no tool disc about the centres of ``tree`` (:func:`_centre_tree`) covers, (n,) bools.

    The moves are sampled every h = :data:`DENSE_MM`: a point within ``r_t`` of a move lies within
    √(r_t² + (h/2)²) ≤ ``r_t`` + (h/2)²/(2 r_t) of its samples (5e-6 mm for a Ø20 mm tool), so that is the
    reach tested; it could count as covered a point at most that far beyond a disc.
    """
    if tree is None:
        return np.ones(len(pts), bool)
    d, _ = tree.query(pts, distance_upper_bound=r_t + (DENSE_MM / 2) ** 2 / (2 * r_t))
    return ~np.isfinite(d)


def _tree(points: np.ndarray) -> cKDTree:
    """A k-d tree of ``points`` (n, 2) split at sliding midpoints, not medians.

    The points lie along curves (the boundary, the passes, often two passes on
    one path); median splits cut such sets into long thin cells, and a query
    about a tool radius away visits many of them: 0.25 s against 0.03 s for the
    material-left query of the default sample.  The distances found are the same.

    Leaves hold up to :data:`TREE_LEAF` points, not scipy's 16: fewer, larger cells are fewer steps
    down the tree for points ordered along curves, and a leaf's points are compared in one loop in C.
    On disc-groove at 0.001 mm the 84 201 path points' query of the boundary tree took 0.24 → 0.15 CPU s
    and the boundary's query of the path tree 0.12 → 0.08 s, the same distances (2026-12-06; 32 and
    128 points a leaf were between the two, 256 slower again).

    The tree is loaded here, not with the module: `camcam run` imports this module in its main process
    (with the NC result), but builds the trees only in the material check's child; and it is loaded
    without the rest of scipy.spatial (:mod:`camcam.verify.kdtree`: 0.10–0.14 CPU s instead of 0.35–0.53).
    """
    from camcam.verify.kdtree import cKDTree

    return cKDTree(points, leafsize=TREE_LEAF, balanced_tree=False, compact_nodes=False)


def _finish_figures(moves, levels, top_z, keep, boundary, r_t):
    """Material left at the final depth, overcut anywhere below the top, and the roughing's distance from the part.

    All moves' samples are measured in one pass.  A path point farther than
    ``near`` from every boundary point only needs its exact distance where
    nothing nearer decides the figure (a centre inside the part, a boundary
    point no path point comes near, a roughing that never comes near); so a
    move whose :data:`SAMPLE_MM` samples all keep ``near`` + half their
    spacing off the boundary, outside the part (every point of it is then
    farther than ``near``, and outside), is sampled densely only if such a
    figure needs it.
    """
    if not levels:
        return math.inf, "nothing is cut", 0.0, "", None, ""
    final = levels[-1]
    near = r_t + 1.0
    tree = _tree(boundary)
    far = _far_moves(moves, tree, keep, near, top_z)
    none = np.empty((0, 3))
    dense = [none if f else m.samples(DENSE_MM) for m, f in zip(moves, far)]
    below = [p[:, 2] < top_z - 1e-9 for p in dense]
    q = np.concatenate([p[b] for p, b in zip(dense, below)] or [none])
    ends = np.cumsum([0] + [int(b.sum()) for b in below])
    d, _ = tree.query(q[:, :2], distance_upper_bound=near, workers=-1)  # exact either way; threads only speed it
    inside = shapely.contains_xy(keep, q[:, 0], q[:, 1])
    if inside.any():  # a centre inside the part: its exact distance to the boundary
        d[inside], _ = tree.query(q[inside, :2])
    sd = np.where(inside, -d, d)
    at_final = np.zeros(len(q), bool)
    final_far = []  # far moves at the final depth (sampled only if a boundary point has no path point near)
    for i, m in enumerate(moves):
        if far[i]:
            if m.p0[2] <= final + 1e-6 and m.p1[2] <= final + 1e-6:  # z is linear along a move
                final_far.append(m)
        elif len(dense[i]) and np.all(dense[i][:, 2] <= final + 1e-6):
            at_final[ends[i]:ends[i + 1]] = True
    if at_final.any() or final_far:
        # a boundary point's nearest path point is within ``near`` whenever any is: search those first, and
        # among them first those within ``tight`` of the boundary.  A boundary point b whose nearest of
        # those is within ``tight`` has its true nearest p* among them: d(p*) ≤ |p* − b| ≤ ``tight``.
        close = at_final & np.isfinite(d)
        tight = r_t + LEFT_FIRST_MM
        first = close & (d <= tight)
        d_left = np.full(len(boundary), np.inf)
        if first.any():
            d_left, _ = _tree(q[first, :2]).query(boundary, distance_upper_bound=tight, workers=-1)
        again = ~np.isfinite(d_left)
        if again.any() and close.any():
            d_left[again], _ = _tree(q[close, :2]).query(boundary[again], distance_upper_bound=near, workers=-1)
        beyond = ~np.isfinite(d_left)
        if beyond.any():
            pts = np.concatenate([q[at_final, :2], *(m.samples(DENSE_MM)[:, :2] for m in final_far)])
            d_left[beyond], _ = _tree(pts).query(boundary[beyond])
        k = int(np.argmax(d_left))
        left, left_at = float(d_left[k] - r_t), f"design boundary at X{boundary[k, 0]:.3f} Y{boundary[k, 1]:.3f}"
    else:
        left, left_at = math.inf, "no feed move at the final depth"
    over, over_at, clear, clear_at = -math.inf, "", None, ""
    distant = []  # roughing moves with no point within ``near`` of the part
    for i, m in enumerate(moves):
        if far[i]:
            if m.pass_kind == "rough":
                distant.append(i)
            continue
        lo, hi = ends[i], ends[i + 1]
        if lo == hi:
            continue
        k = int(np.argmin(sd[lo:hi]))
        if np.isfinite(sd[lo + k]) and r_t - sd[lo + k] > over:
            over, over_at = float(r_t - sd[lo + k]), where(m.pass_label, q[lo + k])
        if m.pass_kind == "rough":
            if not np.isfinite(sd[lo + k]):
                distant.append(i)
                continue
            c = float(sd[lo + k] - r_t)
            if clear is None or c < clear:
                clear, clear_at = c, where(m.pass_label, q[lo + k])
    if clear is None:  # no roughing move comes near: the true distances of those that are far (else they lose)
        for i in sorted(distant):
            p = moves[i].samples(DENSE_MM)
            p = p[p[:, 2] < top_z - 1e-9]
            if not len(p):
                continue
            dd, _ = tree.query(p[:, :2])
            s_ = np.where(shapely.contains_xy(keep, p[:, 0], p[:, 1]), -dd, dd)
            k = int(np.argmin(s_))
            c = float(s_[k] - r_t)
            if clear is None or c < clear:
                clear, clear_at = c, where(moves[i].pass_label, p[k])
    return max(left, 0.0), left_at, max(over, 0.0), over_at, clear, clear_at


def _far_moves(moves, tree, keep, near: float, top_z: float) -> list[bool]:
    """Per move: every point of it is farther than ``near`` from the boundary points and outside ``keep``.

    Judged on its :data:`SAMPLE_MM` samples: each point of a move lies within
    half that spacing of one, so samples ``near`` + half the spacing off and
    outside the part prove it (a move crossing the top face is never far).
    """
    coarse = [m.samples(SAMPLE_MM) for m in moves]
    if not coarse:
        return []
    c = np.concatenate(coarse)
    dc, _ = tree.query(c[:, :2], distance_upper_bound=near + 0.5 * SAMPLE_MM + 1e-9, workers=-1)
    ok = ~np.isfinite(dc) & ~shapely.contains_xy(keep, c[:, 0], c[:, 1])
    ends = np.cumsum([0] + [len(p) for p in coarse])
    out = []
    for i, p in enumerate(coarse):
        under = p[:, 2] < top_z - 1e-9
        out.append(bool(ok[ends[i]:ends[i + 1]].all()) and (under.all() or not under.any()))
    return out


def check_program(text: str, post, blank, m, built, workers: int = 1) -> RemovalReport:
    """Read the printed ``text`` back and check it against ``blank`` (the NC stage's in-process check), its
    slabs swept by ``workers`` processes.

    Holes cut through the part (the helical bore, the dowel hole: ``bore`` passes) deeper than every other
    pass — a face groove's bore goes through the cam, the groove only to its depth — are checked on their
    own against the holes (:func:`_hole_split`): the 2.5-D design of one final depth would otherwise take
    the groove as uncut below its bottom (design-space case 43:76 said FAIL, material left 109 mm).
    """
    events = read_program(text, post)
    allowance = m.finish_allowance_mm if not blank.groove else 0.0
    args = (m.tool_diameter_mm / 2, m.stepover_mm, m.ramp_angle_deg, m.tolerance_mm, allowance, post.decimals)
    split = _hole_split(events, blank.top_z_mm)
    if split is None:
        keep, boundary, polygon_error = design_keep(blank, built, m.tolerance_mm)
        r = check_moves(events, blank.region, blank.top_z_mm, keep, boundary, *args, workers=workers)
        return replace(r, polygon_error_mm=polygon_error)
    others, holes = split
    keep, boundary, polygon_error = design_keep(replace(blank, bore_machined=False, dowel=None), built, m.tolerance_mm)
    r = check_moves(others, blank.region, blank.top_z_mm, keep, boundary, *args, workers=workers)
    hole_keep, hole_boundary, hole_error = _hole_design(blank, blank.region, DEFAULT_BUDGET.polygon_mm(m.tolerance_mm))
    h = check_moves(holes, blank.region, blank.top_z_mm, hole_keep, hole_boundary, *args, workers=workers)
    return _joined(r, h, max(polygon_error, hole_error))


def _hole_split(events, top_z: float):
    """(the other passes' events, the hole passes' events) when the program's ``bore`` passes reach deeper than
    every other pass, else None.  The moves before the first pass comment go with the others."""
    others, holes, target = [], [], None
    for e in events:
        if isinstance(e, str) and e.startswith("pass "):
            target = holes if e.partition(": ")[2].startswith("bore,") else others
        (target if target is not None else others).append(e)
    if not holes:
        return None

    def deepest(evs) -> float:
        return min((e.z for e in evs if not isinstance(e, str) and e.kind != "rapid"), default=top_z)

    return (others, holes) if deepest(holes) < deepest(others) - 1e-9 else None


def _hole_design(blank, region, chord: float, spacing_mm: float = DENSE_MM):
    """(``region`` less the holes the program cuts (the bore, the dowel hole), dense points (n, 2) on them, their
    measuring polygons' largest chord error)."""
    keep, pts, errors = region, [np.empty((0, 2))], [0.0]
    holes = ([(blank.bore_mm / 2, (0.0, 0.0))] if blank.bore_machined else []) + (
        [(blank.dowel.diameter / 2, blank.dowel.centre)] if blank.dowel is not None else [])
    for r, (cx, cy) in holes:
        hole = measuring_circle(r, chord)
        errors.append(hole.error_mm)
        keep = keep.difference(affinity.translate(hole.polygon, cx, cy))
        a = np.linspace(0, 2 * math.pi, int(2 * math.pi * r / spacing_mm) + 1, endpoint=False)
        pts.append(np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)]))
    return keep, np.concatenate(pts), max(errors)


def _joined(r: RemovalReport, h: RemovalReport, polygon_error_mm: float) -> RemovalReport:
    """The report of a program checked in two parts (:func:`_hole_split`): the worse figure of each, counts added."""
    left, left_at = max((r.material_left_mm, r.left_where), (h.material_left_mm, h.left_where))
    over, over_at = max((r.overcut_mm, r.overcut_where), (h.overcut_mm, h.overcut_where))
    return replace(r, levels=tuple(sorted(set(r.levels) | set(h.levels), reverse=True)), passes=r.passes + h.passes,
                   max_slot_engagement_mm=max(r.max_slot_engagement_mm, h.max_slot_engagement_mm),
                   plunges=r.plunges + h.plunges, plunge_where=r.plunge_where or h.plunge_where,
                   rapid_touches=r.rapid_touches + h.rapid_touches, rapid_where=r.rapid_where or h.rapid_where,
                   material_left_mm=left, left_where=left_at, overcut_mm=over, overcut_where=over_at,
                   polygon_error_mm=polygon_error_mm)


def design_keep(blank, built, tolerance_mm: float, spacing_mm: float = DENSE_MM, budget: FitBudget = DEFAULT_BUDGET):
    """(material that must remain at the final depth, dense points on the machined part of its outline, the
    largest chord error of the polygons that bound it, mm).

    The material is bounded by measuring polygons (:func:`~camcam.nc.stock.measuring_polygon`,
    :func:`~camcam.nc.stock.measuring_circle`) whose chords stay within the budget's
    ``polygon_share`` of ``tolerance_mm`` (:meth:`FitBudget.polygon_mm`), whatever the cam's size: the
    figures measured against them (material left in a slab, the band a slab's rest is judged by) are within
    that of the exact curves'.  Not ``blank.part``, a planning polygon whose chords grow with the cam.
    """
    cam = built.cam
    chord = budget.polygon_mm(tolerance_mm)
    curves = [cam.flanks[0], cam.flanks[1]] if blank.groove else [cam.profile]
    polys = [measuring_polygon(c, chord) for c in curves]
    if blank.groove:
        keep = blank.region.difference(polys[1].polygon.difference(polys[0].polygon))
    else:
        keep = polys[0].polygon
    pts = [_dense(c, spacing_mm) for c in curves]
    keep, holes, hole_error = _hole_design(blank, keep, chord, spacing_mm)
    return keep, np.concatenate(pts + [holes]), max(max(p.error_mm for p in polys), hole_error)


def _dense(curve, spacing_mm: float) -> np.ndarray:
    br = curve.breaks
    out = []
    for a, b in zip(br, br[1:]):
        coarse = curve.evaluate(np.linspace(a, b, 65))
        length = float(np.hypot(*np.diff(coarse, axis=0).T).sum())
        n = max(2, int(math.ceil(length / spacing_mm)))
        out.append(curve.evaluate(np.linspace(a, b, n, endpoint=False)))
    return np.concatenate(out)
