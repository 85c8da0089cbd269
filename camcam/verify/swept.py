"""The tool's sweep through the slabs, move by move: engagement, plunges, rapids (:mod:`camcam.verify.removal`).

The material is one shapely region per slab between consecutive cutting
levels; each feed move, in program order, is measured against the material
its slabs still hold (the width its front semicircle meets, whether it plunges
or a rapid touches) and then takes its swept disc out of them (a run of
moves that cannot change the figures is taken out in one cut).  A slab's
material depends only on the moves that cut it, so the slabs are swept
independently (:func:`sweep_slabs`, shared between processes) and their
figures combined as one pass over all of them would find them.
"""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass

import numpy as np
import shapely
from shapely.geometry import LineString, Point

from camcam.workers import parallel_map
from camcam.nc.passes import SLOT_KINDS

__all__ = ["Move", "moves_of", "parse_marker", "where", "front_extent", "cut_below", "sweep_slabs", "Sweep",
           "SAMPLE_MM", "PROBE_INSET_MM", "TOUCH_MM", "PROBE_STEPS", "CUT_QUAD_SEGS", "BATCH_SAMPLES"]

#: Spacing of the samples along a move for engagement and plunge tests (mm).
SAMPLE_MM = 0.5
#: The engagement probe runs this far inside the tool's edge (mm): the swept regions are polygons within
#: 2.4e-3 mm of their circles, so a probe on the edge would find slivers that are not there.
PROBE_INSET_MM = 0.01
#: A disc overlapping material by less than this is touching, not cutting (mm): above the 2.4e-3 mm by which
#: a swept region (a polygon, 128 sides per circle) falls short of its circles.
TOUCH_MM = 5e-3
#: Probes across the tool's front semicircle (evenly spaced across the direction of travel).
PROBE_STEPS = 97
#: Samples a batch of feed moves holds at most (:func:`_sweep_slab`): probed and cut together.  The check of
#: disc-oscillating-flat at 0.001 mm took 0.153, 0.135 and 0.149 CPU s with 64, 256 and 1024 (best of 3, one
#: process): larger batches probe more moves a second time where a width could exceed the largest so far.
BATCH_SAMPLES = 256
#: Segments per quarter circle of a swept region (:func:`cut_below`): its polygon falls short of the circle by
#: r_t·(1 − cos(π/128)), 3.0e-4 · r_t.
CUT_QUAD_SEGS = 32


def parse_marker(text: str) -> tuple[str, str] | None:
    """``"pass 3/9: rough, spiral…, Z-6"`` → ("rough", the whole text); other comments → None."""
    if not text.startswith("pass ") or ":" not in text:
        return None
    kind = text.split(":", 1)[1].strip().split(",")[0].strip()
    return kind, text


@dataclass(frozen=True)
class Move:
    """One interpreted move: kind (rapid, line, arc), ends, arc centre and direction, the pass it belongs to."""

    kind: str  # rapid, line, arc
    p0: tuple
    p1: tuple
    _: KW_ONLY
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


def moves_of(events) -> list[Move]:
    """The moves of interpreted ``events`` (moves and comment strings), each with its pass marker's kind and text."""
    out, pos, kind, label = [], None, "", ""
    for ev in events:
        if isinstance(ev, str):
            mk = parse_marker(ev)
            if mk is not None:
                kind, label = mk
            continue
        p1 = (ev.x, ev.y, ev.z)
        if pos is not None and p1 != pos:
            out.append(Move(ev.kind, pos, p1, centre=ev.centre, ccw=ev.ccw, pass_kind=kind, pass_label=label))
        pos = p1
    return out


def where(label: str, p) -> str:
    """The report's place of a figure: the pass and the point."""
    return f"{label or 'before the first pass'} at X{p[0]:.3f} Y{p[1]:.3f} Z{p[2]:.3f}"


def _probe(slab, pts, t, n, r_p, v):
    """Whether the front-semicircle points at perpendicular coordinates ``v`` (per sample) lie in ``slab``."""
    along = np.sqrt(np.maximum(r_p * r_p - v * v, 0.0))
    x = pts[:, 0, None] + along * t[:, 0, None] + v * n[:, 0, None]
    y = pts[:, 1, None] + along * t[:, 1, None] + v * n[:, 1, None]
    return shapely.contains_xy(slab, x.ravel(), y.ravel()).reshape(x.shape)


def front_extent(slab, pts: np.ndarray, tangents: np.ndarray, r_probe: float, over: float = -math.inf) -> np.ndarray:
    """Width across travel of the material the tool's leading semicircle meets, per sample (mm).

    Probes on the semicircle at :data:`PROBE_STEPS` perpendicular coordinates;
    each end of the engaged span is then bisected to 1/64 of a step.  An end
    at the tool's edge counts the probe's inset too.

    A sample whose width cannot exceed ``over`` (a largest width met already) is not bisected and
    comes back as 0: its bisected ends would lie within the probes next outside its span, so its width is
    at most theirs apart.  The samples that can exceed it get the same widths as without ``over``, so the
    largest width and the first sample with it are the same whenever it exceeds ``over``.  A move no
    width of the semicircle can exceed is not probed at all.

    Examples
    --------
    Material to the left of the path: the span runs from the path (bisected to 1/64 of the 0.104 mm step
    next to it) to the edge and the inset, 5.01 mm; it cannot exceed 6 mm.

    >>> half = shapely.box(-50.0, 0.0, 50.0, 50.0)
    >>> pts, t = np.array([[0.0, 0.0]]), np.array([[1.0, 0.0]])
    >>> float(front_extent(half, pts, t, 5.0)[0].round(3)), float(front_extent(half, pts, t, 5.0, over=6.0)[0])
    (5.008, 0.0)
    """
    t = tangents
    n = np.column_stack([-t[:, 1], t[:, 0]])
    v = np.linspace(-r_probe, r_probe, PROBE_STEPS)
    # the widest span any sample can have: both ends at the tool's edge (as the ends are worked out below)
    if (v[-1] + PROBE_INSET_MM) - (v[0] - PROBE_INSET_MM) <= over:
        return np.zeros(len(pts))
    inside = _probe(slab, pts, t, n, r_probe, np.broadcast_to(v, (len(pts), len(v))))
    hit = inside.any(axis=1)
    if not hit.any():
        return np.zeros(len(pts))
    idx = np.arange(len(v))
    last = len(v) - 1
    k_lo = np.where(inside, idx, len(v)).min(axis=1)
    k_hi = np.where(inside, idx, -1).max(axis=1)
    # a span's bisected ends lie between its outermost probes in material and the next probes out (or at the
    # edge, the inset beyond): a sample whose bound is at most ``over`` cannot exceed it
    lo_bound = np.where(k_lo == 0, v[0] - PROBE_INSET_MM, v[np.clip(k_lo - 1, 0, last)])
    hi_bound = np.where(k_hi == last, v[last] + PROBE_INSET_MM, v[np.clip(k_hi + 1, 0, last)])
    hit &= hi_bound - lo_bound > over
    if not hit.any():
        return np.zeros(len(pts))
    p, tt, nn = pts[hit], t[hit], n[hit]
    k_lo, k_hi = k_lo[hit], k_hi[hit]
    # both ends of the span bisected at once: rows [0, m) the low end, [m, 2m) the high end
    k = np.concatenate([k_lo, k_hi])
    outward = np.repeat([-1, 1], len(k_lo))
    at_edge = np.where(outward < 0, k == 0, k == last)
    good = v[k].copy()  # in material
    bad = np.where(at_edge, good, v[np.clip(k + outward, 0, last)])  # out of material
    p2, t2, n2 = (np.concatenate([x, x]) for x in (p, tt, nn))
    for _ in range(6):
        mid = 0.5 * (good + bad)
        ins = _probe(slab, p2, t2, n2, r_probe, mid[:, None])[:, 0]
        good, bad = np.where(ins, mid, good), np.where(ins, bad, mid)
    ends = np.where(at_edge, good + outward * PROBE_INSET_MM, good)
    width = np.zeros(len(pts))
    width[hit] = ends[len(k_lo):] - ends[:len(k_lo)]
    return width


@dataclass(frozen=True, kw_only=True)
class Sweep:
    """The program's sweep through the slabs: the material left in each and the figures found on the way."""

    slabs: tuple  # shapely regions after the program, top slab first
    engagement_mm: float  # largest width met outside slots, and where
    engagement_where: str
    slot_engagement_mm: float
    plunges: int  # feed moves plunging into material, and the first
    plunge_where: str
    rapids: int  # rapids touching material, and the first
    rapid_where: str


@dataclass(frozen=True)
class _SlabSweep:
    """One slab's sweep: its material after the program, its largest engagement (width, move, where), its
    slot engagement and the moves that plunge into it or touch it at rapid."""

    slab: object
    engagement: tuple[float, int, str]
    slot_engagement_mm: float
    plunge_moves: tuple[int, ...]
    rapid_moves: tuple[int, ...]


def _move_samples(m: Move, slope: float, rounding: float):
    """A feed move's samples, whether it descends steeper than the ramp, and its probe points and directions."""
    pts = m.samples(SAMPLE_MM)
    xy_len = m.xy_length
    z0, z1 = m.p0[2], m.p1[2]
    steep = z1 < z0 - 1e-9 and (z0 - z1) > xy_len * slope + rounding
    plunge_geom = (LineString(pts[:, :2]) if xy_len > 0 else Point(m.p1[:2])) if steep else None
    probe = None
    if xy_len > 0 and len(pts) > 1:
        d = np.diff(pts[:, :2], axis=0)
        norm = np.hypot(d[:, 0], d[:, 1])
        ok = norm > 0
        probe = pts[1:][ok], d[ok] / norm[ok, None], pts[1:, 2][ok]
    return pts, plunge_geom, probe


def _sweep_slab(i: int, slab, moves: list, samples: list, bounds: list, r_t: float, slot_kinds) -> _SlabSweep:
    """Slab ``i`` (the material between ``bounds[i + 1]`` and ``bounds[i]``) swept by every move in program order.

    Runs of feed moves wholly at or below the slab's floor that do not plunge (a rapid or a plunge ends a run)
    are taken in batches of up to :data:`BATCH_SAMPLES` samples (:func:`_batch_step`): the figures of move by
    move, with one probe and one cut a batch instead of one a move.  A move wholly above the floor neither
    meets nor cuts this slab's material: it is passed over.
    """
    state = _Slab(slab, 0.0, -1, "", 0.0)
    plunges, rapids = [], []
    top, floor = bounds[i], bounds[i + 1]

    def hits(geom) -> bool:
        return not state.slab.is_empty and float(shapely.distance(state.slab, geom)) < r_t - TOUCH_MM

    # moves whose whole swept region this slab has lost (every sample at or below its floor), by their path in
    # XY: a later move along the same path (the same contour one level deeper, which passes through this slab
    # too) sweeps only what they took.  Nothing lies in front of it (its probes lie inside that region by the
    # probe's inset less the swept polygons' shortfall from their circles) and its cut, the same polygon,
    # takes nothing away: it is skipped.  The slab stays the same region, only not re-noded by a difference
    # that removes nothing.  Only for tools whose polygons fall short by less than the inset: r_t < 33 mm
    swept_paths = set() if r_t * (1.0 - math.cos(math.pi / (4 * CUT_QUAD_SEGS))) < PROBE_INSET_MM else None
    batch: list[tuple[int, Move, tuple]] = []
    batch_size = 0

    def flush():
        nonlocal batch_size
        if batch:
            _batch_step(state, batch, floor, r_t, slot_kinds, swept_paths)
            batch.clear()
            batch_size = 0

    for j, (m, sampled) in enumerate(zip(moves, samples)):
        z0, z1 = m.p0[2], m.p1[2]
        if m.kind == "rapid":
            flush()
            geom = LineString([m.p0[:2], m.p1[:2]]) if m.p0[:2] != m.p1[:2] else Point(m.p1[:2])
            if top > min(z0, z1) + 1e-6 and hits(geom):
                rapids.append(j)
            continue
        pts, plunge_geom, _ = sampled
        if plunge_geom is not None:
            flush()
            if top > z1 + 1e-6 and floor < z0 - 1e-6 and hits(plunge_geom):
                plunges.append(j)
        below = pts[:, 2] <= floor + 1e-6
        if not below.any():
            continue  # nothing of it probed or cut in this slab (:func:`_move_step`): the batch goes on
        whole = bool(below.all())
        if whole and swept_paths is not None and _path(m) in swept_paths:
            continue
        if whole and plunge_geom is None:
            if batch and (batch_size + len(pts) > BATCH_SAMPLES
                          or (m.pass_kind in slot_kinds) != (batch[0][1].pass_kind in slot_kinds)):
                flush()
            batch.append((j, m, sampled))
            batch_size += len(pts)
            continue
        flush()
        _move_step(state, j, m, sampled, floor, r_t, slot_kinds, swept_paths, whole)
    flush()
    return _SlabSweep(state.slab, (state.eng, state.eng_move, state.eng_at), state.slot_eng, tuple(plunges),
                      tuple(rapids))


@dataclass
class _Slab:
    """A slab's material as the sweep goes, and the largest engagements met so far (width, move, where)."""

    slab: object
    eng: float
    eng_move: int
    eng_at: str
    slot_eng: float


def _path(m: Move) -> tuple:
    """A feed move's path in XY (:func:`_sweep_slab`'s swept paths)."""
    return (m.kind, m.p0[:2], m.p1[:2], m.centre[:2] if m.centre is not None else None, m.ccw)


def _move_step(state: _Slab, j: int, m: Move, sampled: tuple, floor: float, r_t: float, slot_kinds,
               swept_paths: set | None, whole: bool) -> None:
    """Feed move ``j`` against the slab ``state`` holds: its engagement, then its cut (``whole``: every sample of
    it at or below ``floor``, so its path is swept whole)."""
    pts, _, probe = sampled
    if probe is not None:
        probe_pts, tang, zs = probe
        sel = zs <= floor + 1e-6
        if sel.any() and not state.slab.is_empty:
            slot = m.pass_kind in slot_kinds
            # only a width over the largest met so far changes the figures (the first of equals is kept)
            w = front_extent(state.slab, probe_pts[sel, :2], tang[sel], r_t - PROBE_INSET_MM,
                             state.slot_eng if slot else state.eng)
            k = int(np.argmax(w))
            if slot:
                state.slot_eng = max(state.slot_eng, float(w[k]))
            elif w[k] > state.eng:
                state.eng, state.eng_move, state.eng_at = float(w[k]), j, where(m.pass_label, probe_pts[sel][k])
    state.slab = cut_below(state.slab, pts, floor, r_t)
    if swept_paths is not None and whole:
        swept_paths.add(_path(m))


def _batch_step(state: _Slab, batch: list, floor: float, r_t: float, slot_kinds, swept_paths: set | None) -> None:
    """Feed moves ``batch`` ((j, move, samples), in program order, every sample at or below ``floor``, all in slot
    passes or none) against the slab ``state`` holds, with the figures of :func:`_move_step` move by move.

    Every move's probes are first measured against the slab as the batch finds it.  That slab holds all the
    material each move meets move by move (the moves before it only take material away), so a front's width
    there is at least its width move by move.  A move whose widths there do not exceed the largest met so far
    cannot change the figures: it is only cut, together with the others like it before the next move that
    could.  That one goes through :func:`_move_step`, against the slab as the moves before it left it.
    """
    if len(batch) == 1:
        _move_step(state, *batch[0], floor, r_t, slot_kinds, swept_paths, True)
        return
    slot = batch[0][1].pass_kind in slot_kinds
    bound = np.zeros(len(batch))  # per move, its largest width against the slab as the batch finds it
    probed = [n for n, (_, _, sampled) in enumerate(batch) if sampled[2] is not None]
    if probed and not state.slab.is_empty:
        probes = [batch[n][2][2] for n in probed]  # (points, tangents, z) of each probed move
        w = front_extent(state.slab, np.concatenate([p[0][:, :2] for p in probes]),
                         np.concatenate([p[1] for p in probes]), r_t - PROBE_INSET_MM,
                         state.slot_eng if slot else state.eng)
        starts = np.cumsum([0] + [len(p[0]) for p in probes[:-1]])
        bound[probed] = np.maximum.reduceat(w, starts)
    pending: list[int] = []  # moves to be cut before the next one measured

    def cut_pending():
        if pending:
            moves = [batch[n][1] for n in pending]
            state.slab = _cut_moves(state.slab, [batch[n][2][0] for n in pending], moves, r_t)
            if swept_paths is not None:
                swept_paths.update(_path(m) for m in moves)
            pending.clear()

    for n, (j, m, sampled) in enumerate(batch):
        if bound[n] <= (state.slot_eng if slot else state.eng):
            pending.append(n)
            continue
        cut_pending()
        if swept_paths is not None and _path(m) in swept_paths:
            continue  # as move by move: a path cut earlier in the batch
        _move_step(state, j, m, sampled, floor, r_t, slot_kinds, swept_paths, True)
    cut_pending()


def _cut_moves(slab, samples: list, moves: list, r_t: float):
    """``slab`` less the discs of radius ``r_t`` swept along ``moves`` (their ``samples``, every one to be cut),
    each run of joined moves one line (:func:`_take_out`)."""
    runs, run = [], []
    for k, (pts, m) in enumerate(zip(samples, moves)):
        if run and m.p0 != moves[k - 1].p1:
            runs.append(np.concatenate(run))
            run = []
        run.append(pts[:, :2] if not run else pts[1:, :2])
    runs.append(np.concatenate(run))
    return _take_out(slab, runs, r_t)


def cut_below(slab, pts: np.ndarray, floor: float, r_t: float):
    """``slab`` less the discs of radius ``r_t`` swept along the samples ``pts`` (n, 3) at or below ``floor``
    (each run of such samples one line, :func:`_take_out`)."""
    below = pts[:, 2] <= floor + 1e-6
    if not below.any():
        return slab
    runs = np.split(np.arange(len(pts)), np.where(np.diff(below.astype(int)) != 0)[0] + 1)
    return _take_out(slab, [pts[run, :2] for run in runs if below[run[0]]], r_t)


def _take_out(slab, runs: list, r_t: float):
    """``slab`` less the discs of radius ``r_t`` swept along each of ``runs`` (XY points (k, 2), a line each, or a
    point where they do not move), :data:`CUT_QUAD_SEGS` segments per quarter circle; prepared."""
    if slab.is_empty or not runs:
        return slab
    geoms = [LineString(seg) if len(seg) > 1 and np.ptp(seg, axis=0).max() > 0 else Point(seg[0]) for seg in runs]
    slab = slab.difference(shapely.union_all(shapely.buffer(np.array(geoms, dtype=object), r_t,
                                                            quad_segs=CUT_QUAD_SEGS)))
    shapely.prepare(slab)
    return slab


def sweep_slabs(moves: list, slabs: list, bounds: list, r_t: float, slope: float, rounding: float,
                slot_kinds=SLOT_KINDS, workers: int = 1) -> Sweep:
    """Take each move's cut out of the slabs, in program order, and find on the way the largest engagement
    (and in slots), the plunges into material and the rapids that touch it.

    ``slabs[i]`` is the material between ``bounds[i + 1]`` and ``bounds[i]``.
    The slabs are swept one per process, ``workers`` at a time, the top one
    (which every deeper move cuts too) first; the figures are those of one
    pass over moves and slabs together: a move counts once however many slabs
    it plunges into or touches, the first move named, and the largest
    engagement is the first met in (move, slab) order.
    """
    samples = [None if m.kind == "rapid" else _move_samples(m, slope, rounding) for m in moves]
    swept = parallel_map(lambda i: _sweep_slab(i, slabs[i], moves, samples, bounds, r_t, slot_kinds),
                         range(len(slabs)), workers)
    best = max(((s.engagement[0], -s.engagement[1], -i) for i, s in enumerate(swept) if s.engagement[1] >= 0),
               default=None)
    eng, eng_at = (0.0, "") if best is None else (best[0], swept[-best[2]].engagement[2])
    plunges = sorted({j for s in swept for j in s.plunge_moves})
    rapids = sorted({j for s in swept for j in s.rapid_moves})
    return Sweep(slabs=tuple(s.slab for s in swept), engagement_mm=eng, engagement_where=eng_at,
                 slot_engagement_mm=max((s.slot_engagement_mm for s in swept), default=0.0),
                 plunges=len(plunges),
                 plunge_where=where(moves[plunges[0]].pass_label, moves[plunges[0]].p1) if plunges else "",
                 rapids=len(rapids),
                 rapid_where=where(moves[rapids[0]].pass_label, moves[rapids[0]].p1) if rapids else "")
