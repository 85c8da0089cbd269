"""Cycle time from a motion model: each printed move as a trapezoidal velocity profile (GRBL's planner model).

:mod:`camcam.verify.cycle_time` runs every move at its programmed rate from end to end; a machine
cannot: it accelerates out of each stop, slows for corners and stops at the end.  :func:`motion_time`
times the same printed moves (``Program.printed_moves``) with the planner GRBL 1.1 publishes
(gnea/grbl ``grbl/planner.c``), with the post's machine limits:

* **blocks.**  Each move is a block in axis space (X Y Z in mm, A in degrees, one norm over all four as
  GRBL's ``plan_buffer_line`` takes it): its length M (an arc: r · sweep, helical with its Z travel),
  unit vectors u where it starts and ends (a line: its direction; an arc: its tangents), its nominal
  duration T₀ as :mod:`~camcam.verify.cycle_time` gives it (M / F; a ``G93`` move 1/F min; a rapid its
  length at ``rapid_mm_min``) and nominal speed v = M / T₀ (GRBL: ``programmed_rate *= millimeters``
  in inverse time), held to ``rapid_mm_min`` on each linear axis, as GRBL holds a feed to its axes'
  rates (an arc: by its mean largest axis share, the mean of max(|cos φ|, |sin φ|) over its sweep, exact).
* **acceleration.**  Each axis has its own limit, ``max_accel_mm_s2`` for X Y Z, ``max_accel_deg_s2``
  for A; a line's acceleration along its path is the largest the slowest axis allows,
  a = minᵢ aᵢ / |uᵢ| (GRBL's ``limit_value_by_axis_maximum``): a move that turns A is limited by the
  rotary share of its motion.  An arc, whose direction turns through every axis share, takes the linear
  limit over its mean largest share (a_arc), and its speed is held to the centripetal limit
  v² ≤ a_arc · r (the normal acceleration of a circle at v); a controller that cuts arcs into chords (``arc_tolerance_mm``,
  GRBL's ``mc_arc``: floor(½ · sweep · r / sqrt(tol · (2r − tol))) chords) holds it instead to the
  junction speed between its chords (below, at their deflection sweep / chords), about 5 a · r at GRBL's
  defaults.
* **junctions.**  The speed where block k−1 (exit vector e) meets block k (entry vector s) is at most
  v_j² = a_j · δ · sin(θ/2) / (1 − sin(θ/2)), δ the ``junction_deviation_mm``, cos θ = −e · s (θ is
  π less the turn: 180° straight on, where v_j is unlimited; 0° a reversal, where it is 0), a_j the
  axis-limited acceleration along s − e (GRBL's ``junction_unit_vec``), and at most either block's
  nominal speed.  The program starts and ends at rest and stops for each tool change (``tool_change_s``
  added, as the feed-only figure does).
* **plan.**  Entry speeds are the largest every junction limit and the reachable limits of a backward
  pass (decelerate over each block to the next entry: w_k = min(J_k, w_{k+1} + 2 a_k M_k)) and a
  forward pass (accelerate: u_{k+1} = min(w_{k+1}, u_k + 2 a_k M_k)) allow, over the whole program at
  once: in squared speeds both recurrences are running minima of prefix sums (``np.minimum.accumulate``),
  exact.  A controller that plans over ``lookahead_blocks`` buffered blocks (GRBL: 16, its newest block
  planned to a stop) cannot enter a block faster than it can stop within the next B − 2 controller
  blocks (an arc counts its chords; GRBL runs block k with k + 1 … k + 14 planned behind it): entry² ≤
  2 · Σ aᵢ Mᵢ over them, and an arc of more chords than that is held to it within.  Because the
  backward recurrence is a running minimum, this cap is exactly the plan of each window (a stop at its
  end, every limit within it) while the forward pass is the controller's, which runs its blocks in
  order (``tests/verify/grbl_planner.py`` transcribes GRBL with its buffer as the reference).
* **profile.**  Each block accelerates at a from its entry speed, cruises at v and decelerates to its
  exit speed, or, when too short to reach v, peaks at v_p² = a · M + (v₀² + v₁²) / 2: a trapezoid or a
  triangle, timed in closed form.

Every block then takes at least T₀, so the model's figure is never below the feed-only one, and equals it
as the accelerations grow without bound (for feeds within the rapid rate).  A rapid's A turn (not in the printed move) is not timed, as in
the feed-only figure.  Passes: the writer records each pass's opening comment (``pass i/n: kind, …``);
:class:`MotionTime` holds both figures per pass (the moves before the first pass — the tool change and
the approach — count as ``start``).

Examples
--------
>>> from camcam.post.post import load_post
>>> moves = (("rapid", (0.0, 0.0, 0.0), (0.0, 0.0, 5.0)), ("line", (0.0, 0.0, 5.0), (100.0, 0.0, 5.0), 600.0, 0.0, 0.0))
>>> t = motion_time(moves, load_post("grbl"))  # 10 mm/s²: 5 mm up at 2500 mm/min, 100 mm at 10 mm/s
>>> round(t.feed_only_s, 3), round(t.total_s, 3)  # the 90° corner at 0.58 mm/s: under 100/10 + 10/10 + 2·sqrt(5/10) s
(10.12, 12.301)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from itertools import chain

import numpy as np

from camcam.verify.cycle_time import part_path_mm

__all__ = ["MotionTime", "PassTime", "motion_time", "profile_time_s", "junction_speed_sqr", "pass_label"]

#: The printed moves' kinds that move (the others: "comment", "tool change").
_CODES = {"rapid": 0, "line": 1, "inverse": 2, "arc": 3}

#: GRBL's ``junction_cos_theta`` beyond which a join is straight on (no limit) or a reversal (a stop).
_STRAIGHT_COS = 0.999999


@dataclass(frozen=True, kw_only=True)
class PassTime:
    """One pass's time, feed-only and from the motion model (seconds)."""

    label: str
    feed_only_s: float
    model_s: float

    def as_dict(self) -> dict:
        return {"pass": self.label, "feed_only_s": self.feed_only_s, "model_s": self.model_s}


@dataclass(frozen=True, kw_only=True)
class MotionTime:
    """A program's cycle time from the motion model beside the feed-only figure, per pass and in total."""

    passes: tuple[PassTime, ...]
    max_accel_mm_s2: float
    max_accel_deg_s2: float
    junction_deviation_mm: float

    @property
    def total_s(self) -> float:
        return math.fsum(p.model_s for p in self.passes)

    @property
    def feed_only_s(self) -> float:
        return math.fsum(p.feed_only_s for p in self.passes)

    def describe(self) -> str:
        """One line: the model's total, the feed-only one and the machine limits it used."""
        ratio = self.total_s / self.feed_only_s if self.feed_only_s > 0 else 1.0
        return (f"{_minutes(self.total_s)} with acceleration ({ratio:.2f} × the feed-only {_minutes(self.feed_only_s)}; "
                f"{self.max_accel_mm_s2:g} mm/s², {self.max_accel_deg_s2:g} °/s², "
                f"junction deviation {self.junction_deviation_mm:g} mm)")

    @classmethod
    def from_dict(cls, data: dict) -> "MotionTime":
        """The :meth:`as_dict` form read back (a report's ``machining.motion_time``)."""
        return cls(passes=tuple(PassTime(label=p["pass"], feed_only_s=p["feed_only_s"], model_s=p["model_s"])
                                for p in data["passes"]),
                   **{k: data[k] for k in ("max_accel_mm_s2", "max_accel_deg_s2", "junction_deviation_mm")})

    def as_dict(self) -> dict:
        return {"total_s": self.total_s, "feed_only_s": self.feed_only_s, "max_accel_mm_s2": self.max_accel_mm_s2,
                "max_accel_deg_s2": self.max_accel_deg_s2, "junction_deviation_mm": self.junction_deviation_mm,
                "passes": [p.as_dict() for p in self.passes]}


def _minutes(seconds: float) -> str:
    h, rest = divmod(seconds, 3600.0)
    m, s = divmod(rest, 60.0)
    if h >= 1:
        return f"{int(h)} h {int(m)} min"
    return f"{int(m)} min {s:.0f} s" if m >= 1 else f"{s:.1f} s"


def pass_label(comment: str) -> str | None:
    """The pass a writer's comment opens (``"pass 2/5: rough, …"`` → ``"2/5 rough"``), else None.

    Examples
    --------
    >>> pass_label("pass 2/5: rough, profile, Z-6"), pass_label("camcam 1.0")
    ('2/5 rough', None)
    """
    from camcam.nc.passes import MARKER_PREFIX

    if not comment.startswith(MARKER_PREFIX) or ":" not in comment:
        return None
    number, rest = comment[len(MARKER_PREFIX):].split(":", 1)
    return f"{number.strip()} {rest.split(',', 1)[0].strip()}"


def profile_time_s(length, v0, v1, v_nominal, accel):
    """Seconds to run ``length`` from speed ``v0`` to ``v1`` accelerating at ``accel`` toward ``v_nominal``
    (arrays or scalars; v0, v1 ≤ v_nominal and |v1² − v0²| ≤ 2 · accel · length, as a plan gives them).

    Examples
    --------
    >>> float(profile_time_s(100.0, 0.0, 0.0, 10.0, 10.0))  # L/v + v/a
    11.0
    >>> float(profile_time_s(1.0, 0.0, 0.0, 10.0, 10.0)) == 2 * math.sqrt(1.0 / 10.0)  # never reaches v
    True
    """
    length, v0, v1, vc, a = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in
                                                  (length, v0, v1, v_nominal, accel)))
    ramps = (2 * vc * vc - v0 * v0 - v1 * v1) / (2 * a)  # distance to reach vc and come back down
    cruise = ramps <= length
    peak = np.sqrt(np.maximum(a * length + 0.5 * (v0 * v0 + v1 * v1), 0.0))
    vp = np.where(cruise, vc, peak)
    t = (2 * vp - v0 - v1) / a
    with np.errstate(divide="ignore", invalid="ignore"):
        t = t + np.where(cruise, (length - ramps) / vc, 0.0)
    return t


def junction_speed_sqr(exit_vec, entry_vec, accel_axes, deviation_mm):
    """GRBL's largest squared speed through the join of a block leaving along ``exit_vec`` into one entering
    along ``entry_vec`` (unit rows, axis space): a_j · δ · sin(θ/2) / (1 − sin(θ/2)), cos θ = −e · s, a_j the
    ``accel_axes`` limit along s − e; ∞ straight on, 0 at a reversal.

    Examples
    --------
    >>> v2 = junction_speed_sqr(np.array([[1.0, 0, 0, 0]]), np.array([[0.0, 1, 0, 0]]), np.full(4, 100.0), 0.01)
    >>> round(float(v2[0]), 6)  # a 90° corner: a_j · δ · √½ / (1 − √½), a_j = 100 · √2 along the diagonal
    3.414214
    """
    e, s = np.atleast_2d(exit_vec), np.atleast_2d(entry_vec)
    cos_t = -np.einsum("ij,ij->i", e, s)
    j = s - e
    norm = np.linalg.norm(j, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        share = np.abs(j) / norm[:, None]
        a_j = 1.0 / np.max(share / accel_axes, axis=1)
        sin_half = np.sqrt(np.clip(0.5 * (1.0 - cos_t), 0.0, 1.0))
        v2 = a_j * deviation_mm * sin_half / (1.0 - sin_half)
    return np.where(cos_t < -_STRAIGHT_COS, np.inf, np.where(cos_t > _STRAIGHT_COS, 0.0, v2))


def _share_integral(phi):
    """∫₀^φ max(|cos t|, |sin t|) dt: √2 per quarter turn, sin ψ + sin 45° within one (ψ = φ to the nearest
    multiple of 90°).  An arc's direction turns as its radius does, so the mean of max(|cos|, |sin|) over
    its sweep is its mean largest linear axis share."""
    k = np.floor((phi + np.pi / 4) / (np.pi / 2))
    psi = phi - k * (np.pi / 2)
    return np.sqrt(2.0) * k + np.sin(psi) + np.sqrt(0.5)


def _arc_geometry(start, end, centre, ccw):
    """Radius (mean of the two ends', as the controller's check allows), sweep and start/end angles (radians)
    of XY arcs, rows of ``start``, ``end`` (X Y Z), ``centre`` (X Y) and ``ccw`` (as
    :meth:`camcam.verify.cycle_time.MoveTimer.arc`)."""
    a0 = np.arctan2(start[:, 1] - centre[:, 1], start[:, 0] - centre[:, 0])
    a1 = np.arctan2(end[:, 1] - centre[:, 1], end[:, 0] - centre[:, 0])
    sweep = np.where(ccw, a1 - a0, a0 - a1) % (2 * np.pi)
    r = 0.5 * (np.hypot(start[:, 0] - centre[:, 0], start[:, 1] - centre[:, 1])
               + np.hypot(end[:, 0] - centre[:, 0], end[:, 1] - centre[:, 1]))
    return r, sweep, a0, a1


def _blocks(printed_moves, rapid_mm_min: float):
    """The printed moves as blocks: arrays of axis-space deltas, lengths, entry/exit unit vectors, nominal
    seconds, arc radii (0 for lines) and largest axis shares (1 for lines), which follow a stop, and segment numbers; tool change seconds and
    labels per segment."""
    motion, segment_of, stop_before = [], [], []
    labels, changes = ["start"], [0.0]
    stop, seg = True, 0
    for move in printed_moves:
        kind = move[0]
        if kind in _CODES:
            motion.append(move)
            segment_of.append(seg)
            stop_before.append(stop)
            stop = False
        elif kind == "comment":
            label = pass_label(move[1])
            if label is not None:
                labels.append(label)
                changes.append(0.0)
                seg += 1
        else:  # a tool change: a stop, its seconds
            changes[-1] += move[1]
            stop = True
    n = len(motion)
    kind = np.fromiter((_CODES[m[0]] for m in motion), dtype=int, count=n)
    start = np.fromiter(chain.from_iterable(m[1] for m in motion), dtype=float, count=3 * n).reshape(n, 3)
    end = np.fromiter(chain.from_iterable(m[2] for m in motion), dtype=float, count=3 * n).reshape(n, 3)
    # the feed (mm/min) or F (1/min, G93); A where a line or G93 move starts and ends
    rate = np.fromiter((m[5] if m[0] == "arc" else m[3] if m[0] != "rapid" else 0.0 for m in motion), dtype=float,
                       count=n)
    a_from = np.fromiter((m[4] if m[0] in ("line", "inverse") else 0.0 for m in motion), dtype=float, count=n)
    a_to = np.fromiter((m[5] if m[0] in ("line", "inverse") else 0.0 for m in motion), dtype=float, count=n)
    delta = np.zeros((n, 4))
    delta[:, :3] = end - start
    turns = np.isin(kind, (1, 2))
    delta[turns, 3] = a_to[turns] - a_from[turns]
    length = np.linalg.norm(delta, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        unit = delta / length[:, None]
    unit_in, unit_out = unit.copy(), unit.copy()
    nominal_s = np.zeros(n)
    radius = np.zeros(n)
    arc_share = np.ones(n)
    rapid = kind == 0
    nominal_s[rapid] = length[rapid] / rapid_mm_min * 60.0
    line = kind == 1
    tip = line & (delta[:, 3] != 0.0)  # a tool-tip feed while A turns: the tip's path in the part (rare)
    path = length.copy()
    for i in np.flatnonzero(tip):
        path[i] = part_path_mm(motion[i][1], motion[i][2], a_from[i], a_to[i])
    nominal_s[line] = path[line] / rate[line] * 60.0
    inverse = kind == 2
    nominal_s[inverse] = 60.0 / rate[inverse]
    arc = kind == 3
    if arc.any():
        arcs = [m for m in motion if m[0] == "arc"]
        centre = np.fromiter(chain.from_iterable(m[3] for m in arcs), dtype=float, count=2 * len(arcs)).reshape(-1, 2)
        ccw = np.fromiter((m[4] for m in arcs), dtype=bool, count=len(arcs))
        r, sweep, a0, a1 = _arc_geometry(start[arc], end[arc], centre, ccw)
        planar = r * sweep
        dz = delta[arc, 2]
        m = np.hypot(planar, dz)
        sign = np.where(ccw, 1.0, -1.0)
        for vec, ang in ((unit_in, a0), (unit_out, a1)):
            t = np.zeros((arc.sum(), 4))
            t[:, 0], t[:, 1] = -np.sin(ang) * sign * planar / m, np.cos(ang) * sign * planar / m
            t[:, 2] = dz / m
            vec[arc] = t
        length[arc] = m
        radius[arc] = r
        with np.errstate(divide="ignore", invalid="ignore"):
            mean = np.abs(_share_integral(a0 + sign * sweep) - _share_integral(a0)) / sweep
        arc_share[arc] = np.maximum(np.where(sweep > 0, mean, 1.0) * planar, np.abs(dz)) / m
        nominal_s[arc] = m / rate[arc] * 60.0
    keep = length > 0.0
    return (delta[keep], length[keep], unit_in[keep], unit_out[keep], nominal_s[keep], radius[keep], arc_share[keep],
            np.asarray(stop_before, dtype=bool).reshape(n)[keep], np.asarray(segment_of, dtype=int).reshape(n)[keep],
            labels, changes, np.bincount(np.asarray(segment_of, dtype=int).reshape(n), weights=nominal_s,
                                         minlength=len(labels)))


def _chords(length, dz, radius, tolerance_mm):
    """Controller blocks per move: 1, or an arc's chords when the controller cuts arcs at ``tolerance_mm``
    (GRBL's ``mc_arc``: floor(½ · sweep · r / sqrt(tol · (2r − tol))), at least one)."""
    chords = np.ones(len(length))
    arc = radius > 0.0
    if tolerance_mm > 0.0 and arc.any():
        r = radius[arc]
        planar = np.sqrt(np.maximum(length[arc] ** 2 - dz[arc] ** 2, 0.0))
        chords[arc] = np.maximum(np.floor(0.5 * planar / np.sqrt(tolerance_mm * (2 * r - tolerance_mm))), 1.0)
    return chords


def _arc_speed_sqr(length, dz, radius, chords, accel, post):
    """The squared speed an arc is held to (arcs only meaningful): the centripetal a · r; where the controller
    cuts arcs into chords, the junction speed between them instead (GRBL's rule at the chords' deflection
    sweep / chords, a the arc's own)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        if post.arc_tolerance_mm <= 0.0:
            return accel * radius
        planar = np.sqrt(np.maximum(length ** 2 - dz ** 2, 0.0))
        half = np.cos(0.5 * planar / radius / chords)  # sin(θ/2) of GRBL's θ = π − deflection
        return np.where(chords > 1, accel * post.junction_deviation_mm * half / (1.0 - half), np.inf)


def motion_time(printed_moves, post) -> MotionTime:
    """The cycle time of ``printed_moves`` (``Program.printed_moves``) from the motion model (module docstring)
    with ``post``'s rapid rate, accelerations and junction deviation, per pass beside the feed-only figure.
    """
    (delta, length, unit_in, unit_out, nominal_s, radius, arc_share, stop_before, segment, labels, changes,
     feed_only) = _blocks(printed_moves, post.rapid_mm_min)
    a_lin, a_rot = post.max_accel_mm_s2, post.max_accel_deg_s2
    axes = np.array([a_lin, a_lin, a_lin, a_rot])
    n = len(length)
    model = np.zeros(len(labels))
    if n:
        with np.errstate(divide="ignore"):
            accel = 1.0 / np.max(np.abs(delta / length[:, None]) / axes, axis=1)
        arc = radius > 0.0
        accel[arc] = a_lin / arc_share[arc]
        v = length / nominal_s
        # no feed beyond the rapid rate on any linear axis (GRBL's plan_compute_profile_nominal_speed)
        with np.errstate(divide="ignore"):
            v = np.minimum(v, post.rapid_mm_min / 60.0 / np.max(np.abs(delta[:, :3] / length[:, None]), axis=1))
        v[arc] = np.minimum(length[arc] / nominal_s[arc], post.rapid_mm_min / 60.0 / arc_share[arc])
        chords = _chords(length, delta[:, 2], radius, post.arc_tolerance_mm)
        v[arc] = np.minimum(v[arc], np.sqrt(_arc_speed_sqr(length, delta[:, 2], radius, chords, accel, post)[arc]))
        # squared entry limits: junction rule, both nominal speeds, rest after a stop; the end at rest
        limit = np.zeros(n + 1)
        limit[1:n] = junction_speed_sqr(unit_out[:-1], unit_in[1:], axes, post.junction_deviation_mm)
        limit[1:n] = np.minimum(limit[1:n], np.minimum(v[:-1], v[1:]) ** 2)
        limit[:n][stop_before] = 0.0
        reach = 2.0 * accel * length
        prefix = np.concatenate(([0.0], np.cumsum(reach)))
        if post.lookahead_blocks:
            # the controller plans the blocks after an entry to a stop at its buffer's end: entry² ≤ 2 a × the
            # distance of the next lookahead_blocks − 2 controller blocks (arcs count their chords)
            count = np.concatenate(([0.0], np.cumsum(chords)))
            ahead = np.interp(count[:n] + post.lookahead_blocks - 2, count, prefix) - prefix[:n]
            limit[:n] = np.minimum(limit[:n], ahead)
            inside = chords > post.lookahead_blocks - 2  # a long arc: every chord's window lies in it
            v[inside] = np.minimum(v[inside], np.sqrt(reach[inside] / chords[inside] * (post.lookahead_blocks - 2)))
            limit[1:n] = np.minimum(limit[1:n], np.minimum(v[:-1], v[1:]) ** 2)
        # backward: w_k = min(J_k, w_{k+1} + c_k)  ⇔  w_k + S_k = min_{j ≥ k} (J_j + S_j)
        w = np.minimum.accumulate((limit + prefix)[::-1])[::-1] - prefix
        # forward: u_{k+1} = min(w_{k+1}, u_k + c_k)  ⇔  u_k − S_k = min_{j ≤ k} (w_j − S_j)
        u = np.minimum.accumulate(w - prefix) + prefix
        speed = np.sqrt(np.clip(np.minimum(u, limit), 0.0, None))
        t = profile_time_s(length, speed[:-1], speed[1:], v, accel)
        model = np.bincount(segment, weights=t, minlength=len(labels))
    changes = np.asarray(changes)
    passes = tuple(PassTime(label=label, feed_only_s=float(feed_only[k] + changes[k]), model_s=float(model[k] + changes[k]))
                   for k, label in enumerate(labels) if feed_only[k] + changes[k] + model[k] > 0.0 or k > 0)
    return MotionTime(passes=passes, max_accel_mm_s2=a_lin, max_accel_deg_s2=a_rot,
                      junction_deviation_mm=post.junction_deviation_mm)
