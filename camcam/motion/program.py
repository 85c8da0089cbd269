"""Motion programs: laws laid over one cam revolution.

A program is a sequence of segments tiling 0–360° of cam angle.  Each segment
gives the follower displacement ``s(θ) = base + scale·S(T)``, T = (θ − start)/span,
so a rise law with ``scale = rise`` climbs by ``rise`` and a lift table (its own
S in mm or degrees) uses ``scale = 1``.

Units: displacement in mm (translating follower) or degrees (oscillating
follower).  Derivatives with respect to cam angle are per radian of cam angle.
Time derivatives at ``rpm`` are in mm, mm/s, m/s², m/s³ (translating) or deg,
rad/s, rad/s², rad/s³ (oscillating).
"""

from __future__ import annotations

import math
from dataclasses import KW_ONLY, dataclass, field

import numpy as np

from camcam.errors import MotionError
from camcam.motion.law import JUMP_ATOL, MotionLaw
from camcam.motion.piece_table import PieceTable

__all__ = ["Segment", "Join", "ProgramExtreme", "MotionProgram", "PHYSICAL_UNITS"]

#: Units of (displacement, velocity, acceleration, jerk) in time, per follower unit.
PHYSICAL_UNITS = {
    "mm": ("mm", "mm/s", "m/s²", "m/s³"),
    "deg": ("deg", "rad/s", "rad/s²", "rad/s³"),
}

#: Tolerance on the segment tiling in degrees: angles in specs are decimal
#: degrees, 1e-9° is far below any meaning and far above float rounding of 360.
TILE_ATOL_DEG = 1e-9


@dataclass(frozen=True)
class Segment:
    """One law over a cam-angle range: ``s = base + scale·S((θ − start)/span)``."""

    law: MotionLaw
    start_deg: float
    end_deg: float
    scale: float
    _: KW_ONLY
    base: float = 0.0

    @property
    def span_rad(self) -> float:
        return math.radians(self.end_deg - self.start_deg)

    def derivative(self, T, order: int) -> np.ndarray:
        """d^order s / dθ^order at T, per radian of cam angle."""
        return self.scale * self.law.evaluate(T, order) / self.span_rad**order

    def lifts(self, T, orders) -> list[np.ndarray]:
        """s (with ``base``) and its derivatives of each of ``orders`` at T: :meth:`derivative`, the law
        evaluated once for all orders."""
        rows = self.law.evaluate_orders(T, orders)
        return [self.scale * r / self.span_rad**k + (self.base if k == 0 else 0.0) for r, k in zip(rows, orders)]

    @property
    def end_lift(self) -> float:
        return self.base + self.scale * float(self.law.evaluate(1.0))


@dataclass(frozen=True)
class Join:
    """A jump of velocity (order 1) or acceleration (order 2) at a segment boundary.

    ``jump`` is right minus left, in the program's physical units.
    """

    angle_deg: float
    order: int
    jump: float
    unit: str

    def describe(self) -> str:
        what = {1: "velocity", 2: "acceleration"}[self.order]
        return f"{what} jumps by {self.jump:+.6g} {self.unit} at {self.angle_deg:g}°"


@dataclass(frozen=True)
class ProgramExtreme:
    """An extreme of a time derivative over the revolution and the cam angle where it occurs."""

    value: float
    angle_deg: float


@dataclass(frozen=True)
class MotionProgram:
    """Follower motion over one cam revolution.

    Parameters
    ----------
    segments : tuple of Segment
        Tiling 0–360° in order.
    rpm : float
        Cam speed, for time derivatives.
    unit : {"mm", "deg"}
        Follower displacement unit (translating or oscillating follower).

    Examples
    --------
    >>> from camcam.motion.catalog import make_law
    >>> from camcam.motion.standard import dwell
    >>> p = MotionProgram((Segment(make_law("cycloidal"), 0, 180, 10.0),
    ...                    Segment(make_law("cycloidal"), 180, 360, -10.0, base=10.0)), rpm=60)
    >>> float(p.lift(math.radians(90.0)))
    5.0
    >>> p.joins
    ()
    """

    segments: tuple[Segment, ...]
    rpm: float
    unit: str = "mm"
    _starts: np.ndarray = field(init=False, repr=False, compare=False)
    _ends: np.ndarray = field(init=False, repr=False, compare=False)
    _table: PieceTable | None = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.unit not in PHYSICAL_UNITS:
            raise ValueError(f"unit must be one of {sorted(PHYSICAL_UNITS)}, got {self.unit!r}")
        if not self.segments:
            raise MotionError("a motion program needs at least one segment")
        edges = [self.segments[0].start_deg] + [s.end_deg for s in self.segments]
        if abs(edges[0]) > TILE_ATOL_DEG or abs(edges[-1] - 360.0) > TILE_ATOL_DEG:
            raise MotionError(f"segments must tile 0–360°, they cover {edges[0]:g}–{edges[-1]:g}°")
        for prev, seg in zip(self.segments, self.segments[1:]):
            if abs(seg.start_deg - prev.end_deg) > TILE_ATOL_DEG:
                raise MotionError(f"segment at {seg.start_deg:g}° does not start where the previous ends ({prev.end_deg:g}°)")
        object.__setattr__(self, "_starts", np.array([s.start_deg for s in self.segments]))
        object.__setattr__(self, "_ends", np.array([s.end_deg for s in self.segments]))
        object.__setattr__(self, "_table", PieceTable.of(self.segments))

    # -- evaluation ---------------------------------------------------------
    @property
    def omega_rad_s(self) -> float:
        """Cam angular speed in rad/s."""
        return 2 * math.pi * self.rpm / 60.0

    def locate(self, theta_rad) -> tuple[np.ndarray, np.ndarray]:
        """(segment index, T) for cam angles in radians (any real value, taken mod 2π)."""
        deg = np.degrees(np.asarray(theta_rad, dtype=float))
        if not (deg.size and 0.0 <= deg.min() and deg.max() < 360.0):  # np.mod leaves such angles as they are
            deg = np.mod(deg, 360.0)
        idx = np.clip(np.searchsorted(self._starts, deg, side="right") - 1, 0, len(self.segments) - 1)
        start = self._starts[idx]
        end = self._ends[idx]
        T = np.clip((deg - start) / (end - start), 0.0, 1.0)
        return idx, T

    def spec_field(self, theta_rad: float) -> tuple[str, Segment]:
        """The spec's name for the motion at cam angle θ (rad), ``motion.segments[k]``, or ``motion.lift_table``
        for a table's program (one segment the spec does not list), and that segment.

        Examples
        --------
        >>> from camcam.motion.catalog import make_law
        >>> p = MotionProgram((Segment(make_law("cycloidal"), 0, 180, 10.0),
        ...                    Segment(make_law("cycloidal"), 180, 360, -10.0, base=10.0)), rpm=60)
        >>> p.spec_field(math.radians(200.0))[0]
        'motion.segments[1]'

        An angle at a dwell's end is the join of the segment that moves there:

        >>> from camcam.motion.standard import dwell
        >>> q = MotionProgram((Segment(make_law("cycloidal"), 0, 90, 10.0), Segment(dwell(), 90, 180, 0.0, base=10.0),
        ...                    Segment(make_law("cycloidal"), 180, 360, -10.0, base=10.0)), rpm=60)
        >>> [q.spec_field(math.radians(a))[0] for a in (90.0, 120.0, 180.0)]
        ['motion.segments[0]', 'motion.segments[1]', 'motion.segments[2]']
        """
        k = int(self.locate(np.array([theta_rad]))[0][0])
        if self.segments[k].scale == 0 and len(self.segments) > 1:
            # an angle at a dwell's end is a join: it belongs to the segment that moves there (campaign case 53:30
            # named "its dwell from 59° to 97°" for a cusp at 59°, the end of the rise before it)
            deg = math.degrees(theta_rad) % 360.0
            seg = self.segments[k]
            if abs(deg - seg.start_deg) <= 1e-9 or abs(deg - seg.start_deg) >= 360.0 - 1e-9:
                k = (k - 1) % len(self.segments)
            elif abs(seg.end_deg - deg) <= 1e-9 or abs(seg.end_deg - deg) >= 360.0 - 1e-9:
                k = (k + 1) % len(self.segments)
        seg = self.segments[k]
        return ("motion.lift_table" if seg.law.name.startswith("lift-table") else f"motion.segments[{k}]"), seg

    def lift(self, theta_rad, order: int = 0) -> np.ndarray:
        """d^order s/dθ^order at cam angles θ (rad): mm or deg, per radian^order."""
        return self._lift_orders(theta_rad, (order,))[0, ...]  # a 0-d array for a scalar θ, as before

    def lifts(self, theta_rad, K: int) -> np.ndarray:
        """[s, s′, …, s^(K)] at cam angles θ (rad), shape (K + 1, n): :meth:`lift` of every order up
        to ``K`` with the segments located once."""
        return self._lift_orders(np.atleast_1d(theta_rad), range(K + 1))

    def _lift_orders(self, theta_rad, orders) -> np.ndarray:
        """:meth:`lift` of each of ``orders`` at θ, shape (len(orders),) + θ's shape: one segment lookup."""
        idx, T = self.locate(np.asarray(theta_rad, dtype=float))
        shape = np.shape(T)
        idx, T = np.ravel(idx), np.ravel(T)
        if self._table is not None and not np.isnan(T).any():  # NaN: the laws' own check names it
            return self._table.lifts(idx, T, orders).reshape((len(orders),) + shape)
        out = np.empty((len(orders), T.size))
        for i in np.unique(idx):
            m = idx == i
            for row, values in zip(out, self.segments[i].lifts(T[m], orders)):
                row[m] = values
        return out.reshape((len(orders),) + shape)

    def to_physical(self, value, order: int):
        w = self.omega_rad_s
        value = np.asarray(value, dtype=float) * w**order
        if order == 0:
            return value
        if self.unit == "deg":
            return np.radians(value)
        return value if order == 1 else value / 1000.0

    def physical(self, theta_rad, order: int = 0) -> np.ndarray:
        """Time derivative ``order`` at cam angles θ (rad), in :data:`PHYSICAL_UNITS`."""
        return self.to_physical(self.lift(theta_rad, order), order)

    @property
    def units(self) -> tuple[str, str, str, str]:
        return PHYSICAL_UNITS[self.unit]

    # -- analysis -----------------------------------------------------------
    @property
    def closure(self) -> float:
        """Displacement at 360° minus displacement at 0° (0 for a closed program)."""
        return self.segments[-1].end_lift - self.segments[0].base - self.segments[0].scale * float(
            self.segments[0].law.evaluate(0.0)
        )

    @property
    def joins(self) -> tuple[Join, ...]:
        """Velocity and acceleration jumps at segment boundaries, 0°/360° included."""
        out = []
        n = len(self.segments)
        for i in range(n):
            left, right = self.segments[i - 1], self.segments[i]
            for order in (1, 2):
                lv = float(left.derivative(1.0, order))
                rv = float(right.derivative(0.0, order))
                if abs(rv - lv) > JUMP_ATOL * max(1.0, abs(lv), abs(rv)):
                    out.append(Join(right.start_deg, order, float(self.to_physical(rv - lv, order)), self.units[order]))
        return tuple(out)

    def extremes(self, order: int) -> tuple[ProgramExtreme, ProgramExtreme]:
        """(min, max) of time derivative ``order`` (0–3) over the revolution, exact.

        Each segment's extremes come from its law's exact extremes; a jump of
        the derivative below at a join makes this one infinite there.
        """
        cands = []
        for seg in self.segments:
            lo, hi = seg.law.extreme(order, rest_ends=False)
            k = seg.scale / seg.span_rad**order
            for e in (lo, hi):
                val = k * e.value if math.isfinite(e.value) or k != 0 else 0.0
                if order == 0:
                    val += seg.base
                ang = seg.start_deg + e.T * (seg.end_deg - seg.start_deg)
                cands.append((float(self.to_physical(val, order)), ang))
        for j in self.joins:
            if j.order == order - 1:
                cands.append((math.copysign(math.inf, j.jump), j.angle_deg))
            elif j.order < order - 1:
                cands += [(math.inf, j.angle_deg), (-math.inf, j.angle_deg)]
        lo = min(cands, key=lambda c: (c[0], c[1]))
        hi = max(cands, key=lambda c: (c[0], -c[1]))
        return ProgramExtreme(*lo), ProgramExtreme(*hi)

    def check_strict(self) -> None:
        """Raise :class:`MotionError` naming the first join with a jump."""
        if self.joins:
            raise MotionError(f"motion: {self.joins[0].describe()} (strict = true)")
