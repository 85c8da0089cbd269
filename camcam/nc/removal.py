"""The material-removal check: the interpreted program against the blank, 2.5-D, at every Z level.

The moves come from the printed numbers (:func:`camcam.nc.readback.read_program`
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
counts as material left too.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import shapely
from shapely.geometry import LineString, Point

from camcam.forked import ChildGroup, resolve
from camcam.nc.passes import SLOT_KINDS
from camcam.nc.readback import read_program
from camcam.nc.roughing import polygon_distance
from camcam.nc.stock import bore_region
from camcam.verdict import Check

if TYPE_CHECKING:  # imported where a tree is built (_tree)
    from scipy.spatial import cKDTree

__all__ = ["RemovalReport", "check_moves", "check_program", "SAMPLE_MM", "PROBE_INSET_MM", "parse_marker"]

#: Spacing of the samples along a move for engagement and plunge tests (mm).
SAMPLE_MM = 0.5
#: Spacing of path samples for the material-left / overcut distances (mm): error (h/2)²/(2 r_t), < 1e-5 mm.
DENSE_MM = 0.02
#: The material-left search looks first at path points this far beyond the tool radius from the part (mm):
#: a finishing pass; the boundary points it leaves farther are searched among all (the same figure).
LEFT_FIRST_MM = 0.1
#: The engagement probe runs this far inside the tool's edge (mm): the swept regions are polygons within
#: 2.4e-3 mm of their circles, so a probe on the edge would find slivers that are not there.
PROBE_INSET_MM = 0.01
#: A disc overlapping material by less than this is touching, not cutting (mm): above the 2.4e-3 mm by which
#: a swept region (a polygon, 128 sides per circle) falls short of its circles.
TOUCH_MM = 5e-3
#: Probes across the tool's front semicircle (evenly spaced across the direction of travel).
PROBE_STEPS = 97


def parse_marker(text: str) -> tuple[str, str] | None:
    """``"pass 3/9: rough, spiral…, Z-6"`` → ("rough", the whole text); other comments → None."""
    if not text.startswith("pass ") or ":" not in text:
        return None
    kind = text.split(":", 1)[1].strip().split(",")[0].strip()
    return kind, text


@dataclass(frozen=True)
class _Move:
    kind: str  # rapid, line, arc
    p0: tuple
    p1: tuple
    centre: tuple | None
    ccw: bool
    pass_kind: str
    pass_label: str

    def samples(self, spacing: float) -> np.ndarray:
        """(n, 3) points along the move, ends included, z linear in XY length (or in z for a vertical move)."""
        (x0, y0, z0), (x1, y1, z1) = self.p0, self.p1
        if self.kind == "arc":
            c = self.centre
            a0 = math.atan2(y0 - c[1], x0 - c[0])
            a1 = math.atan2(y1 - c[1], x1 - c[0])
            sweep = (a1 - a0) if self.ccw else (a0 - a1)
            sweep = sweep % (2 * math.pi) or 2 * math.pi
            r0, r1 = math.hypot(x0 - c[0], y0 - c[1]), math.hypot(x1 - c[0], y1 - c[1])
            n = max(2, int(math.ceil(0.5 * (r0 + r1) * sweep / spacing)) + 1)
            u = np.linspace(0.0, 1.0, n)
            ang = a0 + (1.0 if self.ccw else -1.0) * sweep * u
            r = r0 + (r1 - r0) * u
            return np.column_stack([c[0] + r * np.cos(ang), c[1] + r * np.sin(ang), z0 + (z1 - z0) * u])
        L = math.hypot(x1 - x0, y1 - y0)
        n = max(2, int(math.ceil(max(L, abs(z1 - z0)) / spacing)) + 1)
        u = np.linspace(0.0, 1.0, n)[:, None]
        return (1 - u) * np.array(self.p0) + u * np.array(self.p1)

    @property
    def xy_length(self) -> float:
        (x0, y0, _), (x1, y1, _) = self.p0, self.p1
        if self.kind == "arc":
            return float(np.hypot(*np.diff(self.samples(0.05)[:, :2], axis=0).T).sum())
        return math.hypot(x1 - x0, y1 - y0)


def _moves(events) -> list[_Move]:
    out, pos, kind, label = [], None, "", ""
    for ev in events:
        if isinstance(ev, str):
            mk = parse_marker(ev)
            if mk is not None:
                kind, label = mk
            continue
        p1 = (ev.x, ev.y, ev.z)
        if pos is not None and p1 != pos:
            out.append(_Move(ev.kind, pos, p1, ev.centre, ev.ccw, kind, label))
        pos = p1
    return out


def _where(label: str, p) -> str:
    return f"{label or 'before the first pass'} at X{p[0]:.3f} Y{p[1]:.3f} Z{p[2]:.3f}"


@dataclass(frozen=True)
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

    def checks(self) -> tuple[Check, ...]:
        out = [
            Check("plunges into material", float(self.plunges), 0.0, "moves", self.plunges == 0,
                  where=self.plunge_where, advice="enter outside the material or ramp at the ramp angle"),
            Check("rapids touching material", float(self.rapid_touches), 0.0, "moves", self.rapid_touches == 0,
                  where=self.rapid_where, advice="raise clearance_z above the blank"),
            Check("radial engagement", self.max_engagement_mm, self.stepover_mm, "mm",
                  self.max_engagement_mm <= self.stepover_mm + TOUCH_MM, where=self.engagement_where,
                  advice="lower [machining] stepover or use a larger tool"),
            Check("material left over the profile", self.material_left_mm, self.tolerance_mm, "mm",
                  self.material_left_mm <= self.tolerance_mm, where=self.left_where,
                  advice="the finish pass does not reach the profile: check the stock and the depth"),
            Check("overcut into the profile", self.overcut_mm, self.tolerance_mm, "mm",
                  self.overcut_mm <= self.tolerance_mm, where=self.overcut_where,
                  advice="a pass cuts into the part: check the stock, the tool and the allowance"),
        ]
        if self.rough_clearance_mm is not None:
            out.append(Check("roughing stock over the profile (at least the allowance)", self.rough_clearance_mm,
                             self.allowance_mm, "mm", self.rough_clearance_mm >= self.allowance_mm - TOUCH_MM,
                             where=self.rough_clearance_where, advice="report a bug: the roughing came too close"))
        return tuple(out)

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
        }


def _probe(slab, pts, t, n, r_p, v):
    """Whether the front-semicircle points at perpendicular coordinates ``v`` (per sample) lie in ``slab``."""
    along = np.sqrt(np.maximum(r_p * r_p - v * v, 0.0))
    x = pts[:, 0, None] + along * t[:, 0, None] + v * n[:, 0, None]
    y = pts[:, 1, None] + along * t[:, 1, None] + v * n[:, 1, None]
    return shapely.contains_xy(slab, x.ravel(), y.ravel()).reshape(x.shape)


def _front_extent(slab, pts: np.ndarray, tangents: np.ndarray, r_probe: float) -> np.ndarray:
    """Width across travel of the material the tool's leading semicircle meets, per sample (mm).

    Probes on the semicircle at :data:`PROBE_STEPS` perpendicular coordinates;
    each end of the engaged span is then bisected to 1/64 of a step.  An end
    at the tool's edge counts the probe's inset too.
    """
    t = tangents
    n = np.column_stack([-t[:, 1], t[:, 0]])
    v = np.linspace(-r_probe, r_probe, PROBE_STEPS)
    inside = _probe(slab, pts, t, n, r_probe, np.broadcast_to(v, (len(pts), len(v))))
    hit = inside.any(axis=1)
    if not hit.any():
        return np.zeros(len(pts))
    idx = np.arange(len(v))
    k_lo = np.where(inside, idx, len(v)).min(axis=1)
    k_hi = np.where(inside, idx, -1).max(axis=1)
    p, tt, nn = pts[hit], t[hit], n[hit]
    k_lo, k_hi = k_lo[hit], k_hi[hit]
    # both ends of the span bisected at once: rows [0, m) the low end, [m, 2m) the high end
    k = np.concatenate([k_lo, k_hi])
    outward = np.repeat([-1, 1], len(k_lo))
    at_edge = np.where(outward < 0, k == 0, k == len(v) - 1)
    good = v[k].copy()  # in material
    bad = np.where(at_edge, good, v[np.clip(k + outward, 0, len(v) - 1)])  # out of material
    p2, t2, n2 = (np.concatenate([x, x]) for x in (p, tt, nn))
    for _ in range(6):
        mid = 0.5 * (good + bad)
        ins = _probe(slab, p2, t2, n2, r_probe, mid[:, None])[:, 0]
        good, bad = np.where(ins, mid, good), np.where(ins, bad, mid)
    ends = np.where(at_edge, good + outward * PROBE_INSET_MM, good)
    width = np.zeros(len(pts))
    width[hit] = ends[len(k_lo):] - ends[:len(k_lo)]
    return width


def check_moves(events, region, top_z: float, keep, boundary: np.ndarray, tool_radius_mm: float, stepover_mm: float,
                ramp_angle_deg: float, tolerance_mm: float, allowance_mm: float, decimals: int,
                slot_kinds=SLOT_KINDS) -> RemovalReport:
    """Check interpreted ``events`` (moves and comment strings) against the blank ``region`` (shapely).

    ``keep`` is the material that must remain at the final depth (shapely),
    ``boundary`` dense points (n, 2) on the parts of its outline the program
    machines (from the exact curves).
    """
    r_t = tool_radius_mm
    keep = shapely.Polygon(keep) if keep.geom_type == "Polygon" else shapely.MultiPolygon(keep)
    shapely.prepare(keep)
    moves = _moves(events)
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
    # the figures at the finished surface need only the moves and the part, not the slabs: they are
    # computed in a child process beside the move-by-move removal below (the same call, the same figures);
    # stopped if the removal fails
    with ChildGroup() as finishing:
        finish = finishing.later(_finish_figures, cut_moves, levels, top_z, keep, boundary, r_t)
        slabs, eng, eng_at, slot_eng, plunges, plunge_at, rapids, rapid_at = _remove(
            moves, slabs, bounds, r_t, slope, rounding, slot_kinds)
        left, left_at, over, over_at, clearance, clear_at = resolve(finish)
    keep_band = keep.buffer(tolerance_mm, quad_segs=32)
    for i, s in enumerate(slabs):
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
        top = np.full(len(pieces), -np.inf)
        np.maximum.at(top, owner, dist)
        tree = None
        for k in np.argsort(-top, kind="stable").tolist():  # the farthest piece first
            if top[k] <= left:
                break
            tree = _centre_tree(cut_moves, bounds[i + 1]) if tree is None else tree
            mine = np.flatnonzero(owner == k)
            probe = np.vstack([pts[mine], shapely.get_coordinates(shapely.point_on_surface(pieces[k]))])
            if _uncut(tree, probe, r_t).any():
                j = int(mine[np.argmax(dist[mine])])
                left = float(dist[j])
                left_at = (f"slab Z{bounds[i + 1]:g}…Z{bounds[i]:g}: material at X{pts[j, 0]:.3f} Y{pts[j, 1]:.3f} "
                           "not cut")
                break
    return RemovalReport(r_t, stepover_mm, ramp_angle_deg, tolerance_mm, allowance_mm, tuple(levels), passes,
                         eng, eng_at, slot_eng, plunges, plunge_at, rapids, rapid_at, left, left_at, over, over_at,
                         clearance, clear_at)


def _centre_tree(moves, floor_z: float):
    """A k-d tree of tool-centre points every :data:`DENSE_MM` along the feed ``moves``, where the tool is at or
    below ``floor_z`` (the criterion :func:`_remove` cuts a slab by); None if there are none."""
    centres = [p[p[:, 2] <= floor_z + 1e-6, :2] for p in (m.samples(DENSE_MM) for m in moves)]
    centres = np.concatenate([np.empty((0, 2)), *centres])
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


def _remove(moves, slabs: list, bounds: list, r_t: float, slope: float, rounding: float, slot_kinds) -> tuple:
    """Take each move's cut out of the slabs, in program order, and find on the way the largest engagement
    (and in slots), the plunges into material and the rapids that touch it.

    ``slabs[i]`` is the material between ``bounds[i + 1]`` and ``bounds[i]``;
    returns (slabs after the program, engagement, where, slot engagement,
    plunges, where, rapids, where).
    """
    slabs = list(slabs)
    eng, eng_at, slot_eng = 0.0, "", 0.0
    plunges, plunge_at, rapids, rapid_at = 0, "", 0, ""

    def slab_hits(i, geom) -> bool:
        return float(shapely.distance(slabs[i], geom)) < r_t - TOUCH_MM if not slabs[i].is_empty else False

    for m in moves:
        z0, z1 = m.p0[2], m.p1[2]
        zlo = min(z0, z1)
        if m.kind == "rapid":
            geom = LineString([m.p0[:2], m.p1[:2]]) if m.p0[:2] != m.p1[:2] else Point(m.p1[:2])
            for i in range(len(slabs)):
                if bounds[i] > zlo + 1e-6 and slab_hits(i, geom):
                    rapids += 1
                    rapid_at = rapid_at or _where(m.pass_label, m.p1)
                    break
            continue
        pts = m.samples(SAMPLE_MM)
        xy_len = m.xy_length
        if z1 < z0 - 1e-9 and (z0 - z1) > xy_len * slope + rounding:
            geom = LineString(pts[:, :2]) if xy_len > 0 else Point(m.p1[:2])
            for i in range(len(slabs)):
                if bounds[i] > z1 + 1e-6 and bounds[i + 1] < z0 - 1e-6 and slab_hits(i, geom):
                    plunges += 1
                    plunge_at = plunge_at or _where(m.pass_label, m.p1)
                    break
        if xy_len > 0 and len(pts) > 1:
            d = np.diff(pts[:, :2], axis=0)
            norm = np.hypot(d[:, 0], d[:, 1])
            ok = norm > 0
            probe_pts, tang, zs = pts[1:][ok], d[ok] / norm[ok, None], pts[1:, 2][ok]
            for i in range(len(slabs)):
                sel = zs <= bounds[i + 1] + 1e-6
                if not sel.any() or slabs[i].is_empty:
                    continue
                w = _front_extent(slabs[i], probe_pts[sel, :2], tang[sel], r_t - PROBE_INSET_MM)
                k = int(np.argmax(w))
                if m.pass_kind in slot_kinds:
                    slot_eng = max(slot_eng, float(w[k]))
                elif w[k] > eng:
                    eng, eng_at = float(w[k]), _where(m.pass_label, probe_pts[sel][k])
        for i in range(len(slabs)):
            below = pts[:, 2] <= bounds[i + 1] + 1e-6
            if not below.any() or slabs[i].is_empty:
                continue
            runs = np.split(np.arange(len(pts)), np.where(np.diff(below.astype(int)) != 0)[0] + 1)
            cuts = []
            for run in runs:
                if not below[run[0]]:
                    continue
                seg = pts[run, :2]
                geom = LineString(seg) if len(seg) > 1 and np.ptp(seg, axis=0).max() > 0 else Point(seg[0])
                cuts.append(geom.buffer(r_t, quad_segs=32))
            if cuts:
                slabs[i] = slabs[i].difference(shapely.union_all(cuts))
                shapely.prepare(slabs[i])
    return slabs, eng, eng_at, slot_eng, plunges, plunge_at, rapids, rapid_at


def _tree(points: np.ndarray) -> cKDTree:
    """A k-d tree of ``points`` (n, 2) split at sliding midpoints, not medians.

    The points lie along curves (the boundary, the passes, often two passes on
    one path); median splits cut such sets into long thin cells, and a query
    about a tool radius away visits many of them: 0.25 s against 0.03 s for the
    material-left query of the default sample.  The distances found are the same.

    scipy.spatial is imported here, not with the module: `camcam run` imports this module in its
    main process (with the NC result), but builds the trees only in the material check's child,
    and scipy.spatial's import (0.2 s wall, 0.3 CPU s) stays off the main process's path.
    """
    from scipy.spatial import cKDTree

    return cKDTree(points, balanced_tree=False, compact_nodes=False)


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
            over, over_at = float(r_t - sd[lo + k]), _where(m.pass_label, q[lo + k])
        if m.pass_kind == "rough":
            if not np.isfinite(sd[lo + k]):
                distant.append(i)
                continue
            c = float(sd[lo + k] - r_t)
            if clear is None or c < clear:
                clear, clear_at = c, _where(m.pass_label, q[lo + k])
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
                clear, clear_at = c, _where(moves[i].pass_label, p[k])
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


def check_program(text: str, post, blank, m, built) -> RemovalReport:
    """Read the printed ``text`` back and check it against ``blank`` (the NC stage's in-process check)."""
    events = read_program(text, post)
    keep, boundary = design_keep(blank, built)
    return check_moves(events, blank.region, blank.top_z_mm, keep, boundary, m.tool_diameter_mm / 2, m.stepover_mm,
                       m.ramp_angle_deg, m.tolerance_mm, m.finish_allowance_mm if not blank.groove else 0.0,
                       post.decimals)


def design_keep(blank, built, spacing_mm: float = DENSE_MM):
    """(material that must remain at the final depth, dense points on the machined part of its outline)."""
    cam = built.cam
    curves = [cam.flanks[0], cam.flanks[1]] if blank.groove else [cam.profile]
    keep = blank.region.difference(blank.part) if blank.groove else blank.part
    pts = [_dense(c, spacing_mm) for c in curves]
    if blank.bore_machined:
        keep = keep.difference(bore_region(blank))
        r = blank.bore_mm / 2
        a = np.linspace(0, 2 * math.pi, int(2 * math.pi * r / spacing_mm) + 1, endpoint=False)
        pts.append(np.column_stack([r * np.cos(a), r * np.sin(a)]))
    return keep, np.concatenate(pts)


def _dense(curve, spacing_mm: float) -> np.ndarray:
    br = curve.breaks
    out = []
    for a, b in zip(br, br[1:]):
        coarse = curve.evaluate(np.linspace(a, b, 65))
        length = float(np.hypot(*np.diff(coarse, axis=0).T).sum())
        n = max(2, int(math.ceil(length / spacing_mm)))
        out.append(curve.evaluate(np.linspace(a, b, n, endpoint=False)))
    return np.concatenate(out)
