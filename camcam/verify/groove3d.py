"""The cut groove of a barrel cam against the designed groove, in 3-D, normal to the walls.

What is compared
----------------
*Cut*: a flat end mill (a cylinder of ``radius_mm`` and cutting length
``length_mm`` from its tip) posed by the program's own axis words
(:class:`ToolPoses`: the tool tip X Y Z, A, B as printed), moving linearly in
all axis words from pose to pose, as the controller interpolates them.
*Design*: the roller, an unbounded cylinder of the roller radius posed by the
follower at every program angle (translating: axis radial at x = length/2 +
s(θ); oscillating, seed 002: axis along the arm through the pivot (length/2,
0, d), tilted by the swing θf).  The designed walls are the envelope of the
roller over the revolution, at every radius from the groove bottom up to the
outer radius (what the roller needs there, had it been long enough).

Machine frame (DESIGN.md "Machine frames"): cam axis = machine X, Y = Z = 0
on it, X0 at the left end face; a part point p sits at machine position
Rx(a)·p, a = A (``a_axis = "right-hand"``) or −A ("left-hand"); the tool
axis is (sin B, 0, cos B); X Y Z are the tool tip.  The follower at program
angle θ sees the cam turned by a = σθ (σ = +1 ccw, −1 cw).

How
---
At radius ρ a part point is (x, γ): γ its angle about X (from +Z, by the
right-hand rule).  A pose puts it at machine angle β = γ + a, and the tool
contains it when (closed form, ξ = x − X, η = ρ sin β + Y, ζ = ρ cos β − Z)

    (ξ cos B − ζ sin B)² + η² ≤ r²   and   0 ≤ ξ sin B + ζ cos B ≤ length,

an x-interval per (pose, γ).  The wall of the cut at (ρ, γ) is the extreme of
that interval over the whole motion; the designed wall the same over the
roller's motion.  Each is found by sampling the motion (the section of one
sample moves at most ``pose_step_mm`` from the next) and refining the best
sample by golden-section search between its neighbours (the motion parameter
is continuous).  A local maximum whose best sample is beaten by another
move's sample yet whose true value is higher is the only miss; it is bounded
by the scallop of a circle of the tool radius stepped by the pose step,
h²/(8r): ``sampling_bound_mm``.

The deviation normal to the wall: in the developed plane at ρ (u = ρ·γ, x,
a true length plane) the x-gap between cut and designed wall at one γ is
turned to the normal by cos ψ (ψ the designed wall's slope there, from the
envelope theorem), and from the in-plane normal to the 3-D normal of the
wall surface by √(1 − n_r²), n_r the radial component of the designed wall's
normal (the roller's surface normal at the contact).  The map uses this
first-order form; the reported extremes are refined in γ and ρ by golden
search and their in-plane distance taken exactly as the nearest point on the
designed wall curve.

Cam angles are reported as the program cam angle at which that part of the
groove passes under the follower (u/ρ on the developed plane, 0…360°).

Sign: positive = overcut (material removed beyond the designed wall),
negative = material left (the designed wall not reached).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.workers import parallel_map
from camcam.geometry.cylindrical import CylindricalCam
from camcam.verify.groove_envelope import envelope
from camcam.verify.groove_motion import ProgramMotion, RollerMotion, follower_poses, side_extent
from camcam.toolpath.budget import DEFAULT_GROOVE_BUDGET, GrooveBudget
from camcam.toolpath.poses import CylinderTool, ToolPoses, frozen_array

__all__ = ["WallExtreme", "WallDeviation", "GrooveMeasurement", "measure_groove", "pose_step_for", "WALL_LABELS",
           "design_walls", "cut_walls"]

WALL_LABELS = ("flank 0 (-X wall)", "flank 1 (+X wall)")

#: The pose step (mm) of a measurement made with no tolerance to size it by (:func:`measure_groove`'s default): its
#: sampling bound is 1.6e-4 mm for r = 8 mm.  A job's check takes :func:`pose_step_for` its tolerance.
POSE_STEP_MM = 0.1


@dataclass(frozen=True)
class WallExtreme:
    """A signed wall deviation (mm, + overcut) at radius ``radius_mm`` and program cam angle ``cam_angle_deg``."""

    deviation_mm: float
    radius_mm: float
    cam_angle_deg: float

    def describe(self) -> str:
        return f"r = {self.radius_mm:.2f} mm, cam angle {self.cam_angle_deg:.2f}°"


@dataclass(frozen=True)
class WallDeviation:
    """One wall's largest overcut and largest material left (both as signed deviations)."""

    index: int
    overcut: WallExtreme
    material_left: WallExtreme

    @property
    def label(self) -> str:
        return WALL_LABELS[self.index]

    @property
    def overcut_mm(self) -> float:
        """Largest material removed beyond the wall (0 when the cut never passes it)."""
        return max(self.overcut.deviation_mm, 0.0)

    @property
    def material_left_mm(self) -> float:
        """Largest material left on the wall (0 when the cut always reaches it)."""
        return max(-self.material_left.deviation_mm, 0.0)

    @property
    def worst(self) -> WallExtreme:
        return self.overcut if self.overcut_mm >= self.material_left_mm else self.material_left

    def as_dict(self) -> dict:
        o, m = self.overcut, self.material_left
        return {"wall": self.index, "label": self.label,
                "overcut_mm": self.overcut_mm, "overcut_radius_mm": o.radius_mm,
                "overcut_cam_angle_deg": o.cam_angle_deg,
                "material_left_mm": self.material_left_mm, "material_left_radius_mm": m.radius_mm,
                "material_left_cam_angle_deg": m.cam_angle_deg}


@dataclass(frozen=True, kw_only=True)
class GrooveMeasurement:
    """The 3-D wall deviation of a cut groove.

    ``deviation_mm[w, i, j]``: wall w (0: −X, 1: +X) at ``radii_mm[i]`` and
    program cam angle ``cam_angle_deg[j]``, normal to the wall (first order,
    see the module notes); ``walls`` hold the refined extremes.
    ``sampling_bound_mm`` bounds what the sampling of the motion may miss.
    """

    radii_mm: np.ndarray
    cam_angle_deg: np.ndarray
    deviation_mm: np.ndarray
    walls: tuple[WallDeviation, WallDeviation]
    sampling_bound_mm: float
    pose_step_mm: float
    uncut_points: int = 0

    @property
    def measured_mm(self) -> float:
        """The largest overcut or material left on either wall, as measured, mm."""
        return max(max(w.overcut_mm, w.material_left_mm) for w in self.walls)

    @property
    def max_deviation_mm(self) -> float:
        """:attr:`measured_mm` plus :attr:`sampling_bound_mm`: what the job is held to, mm.

        As the 2-D :class:`~camcam.toolpath.deviation.Deviation` adds its
        between-sample bound, so that a program within the tolerance is within it
        whatever the sampling of the motion missed.
        """
        return self.measured_mm + self.sampling_bound_mm

    @property
    def worst(self) -> WallDeviation:
        return max(self.walls, key=lambda w: max(w.overcut_mm, w.material_left_mm))

    def where(self) -> str:
        """Where the largest figure is, in words."""
        w = self.worst
        kind = "overcut" if w.overcut_mm >= w.material_left_mm else "material left"
        return f"{kind} on {w.label}, {w.worst.describe()}"

    def as_dict(self) -> dict:
        return {"max_deviation_mm": self.max_deviation_mm, "measured_mm": self.measured_mm,
                "sampling_bound_mm": self.sampling_bound_mm,
                "pose_step_mm": self.pose_step_mm, "radii_mm": [float(r) for r in self.radii_mm],
                "angle_step_deg": float(self.cam_angle_deg[1] - self.cam_angle_deg[0]),
                "uncut_points": self.uncut_points, "walls": [w.as_dict() for w in self.walls]}


# -- the measurement -----------------------------------------------------------------------
class _Setup:
    """Cam, design and cut motions with their samples, for evaluating walls at any (ρ, γ)."""

    def __init__(self, cam, tool, poses, pose_step_mm):
        self.cam = cam
        self.sigma = cam.sigma
        self.design = RollerMotion(cam)
        self.cut = ProgramMotion(poses, tool)
        rmax = cam.base_radius
        self.ds = self.design.samples(pose_step_mm, rmax)
        self.dposes = self.design.pose(self.ds)
        self.cs = self.cut.samples(pose_step_mm, rmax)
        self.cposes = self.cut.pose(self.cs)

    def gamma(self, cam_angle_rad):
        """Part angle γ of the groove point passing under the follower at program cam angle θc."""
        return -self.sigma * np.asarray(cam_angle_rad, float)

    def design_walls(self, rho, gamma):
        return envelope(self.design, self.ds, self.dposes, rho, gamma)

    def cut_walls(self, rho, gamma):
        return envelope(self.cut, self.cs, self.cposes, rho, gamma)

    def slope_and_normal(self, rho, gamma, theta, side):
        """cos ψ of the designed wall in the developed plane and √(1 − n_r²) at (ρ, γ), contact at θ."""
        X, Y, Z, a, B = self.design.pose(theta)
        r, L = self.design.r, self.design.L
        h = 1e-6
        vp = side_extent(X, Y, Z, a, B, r, L, rho, gamma + h, side)
        vm = side_extent(X, Y, Z, a, B, r, L, rho, gamma - h, side)
        v0 = side_extent(X, Y, Z, a, B, r, L, rho, gamma, side)
        slope = (vp - vm) / (2 * h * rho)  # dx/du at fixed θ: the envelope's slope (envelope theorem)
        cos_psi = 1.0 / np.sqrt(1.0 + slope**2)
        # the wall point and the roller's surface normal there (machine frame at pose θ)
        x = v0 if side == 1 else -v0
        beta = gamma + a
        P = np.stack([x, -rho * np.sin(beta), rho * np.cos(beta)], axis=-1)
        w = np.stack([np.sin(B), np.zeros_like(B), np.cos(B)], axis=-1)
        d = P - np.stack([X, Y, Z], axis=-1)
        nvec = d - np.sum(d * w, axis=-1, keepdims=True) * w
        nvec /= np.linalg.norm(nvec, axis=-1, keepdims=True)
        er = np.stack([np.zeros_like(beta), -np.sin(beta), np.cos(beta)], axis=-1)
        nr = np.sum(nvec * er, axis=-1)
        return cos_psi, np.sqrt(np.maximum(1.0 - nr**2, 0.0))

    def deviations(self, rho, cam_angle_rad):
        """First-order signed deviations (+ overcut) normal to both walls at (ρ, θc): ((k,), (k,)), uncut mask."""
        g = self.gamma(cam_angle_rad)
        cut = self.cut_walls(rho, g)
        des = self.design_walls(rho, g)
        width = des[0].value + des[1].value  # hi − lo of the designed groove
        uncut = ~np.isfinite(cut[0].value)
        out = []
        for side in (0, 1):
            cos_psi, f3 = self.slope_and_normal(rho, g, des[side].p, side)
            gap = np.where(uncut, -width, cut[side].value - des[side].value)
            out.append(gap * cos_psi * f3)
        return out, uncut

    def side_deviations(self, rho, cam_angle_rad, side):
        """:meth:`deviations` of wall ``side[i]`` at each (ρ[i], θc[i]), all in one envelope: (k,); ``rho`` and
        ``side`` are arrays like the angles (a scattered envelope gives each angle the figure it has alone)."""
        d0, d1 = self.deviations(rho, cam_angle_rad)[0]
        return np.where(np.asarray(side) == 0, d0, d1)

    def exact_deviations(self, rho, cam_angle_rad, side):
        """Signed 3-D deviations at (ρ[i], θc[i]) on wall ``side[i]``: the nearest point on the designed wall curve
        at ρ[i], each from 41 angles about its own (all in one envelope); arrays (k,)."""
        rho, side = np.asarray(rho, float), np.asarray(side)
        g = self.gamma(cam_angle_rad)
        cut = self.cut_walls(rho, g)
        des = self.design_walls(rho, g)
        pick = side == 0
        xc = np.where(pick, cut[0].value, cut[1].value)
        xd = np.where(pick, des[0].value, des[1].value)
        f3 = np.where(pick, self.slope_and_normal(rho, g, des[0].p, 0)[1],
                      self.slope_and_normal(rho, g, des[1].p, 1)[1])
        out = np.empty(len(g))
        cut_at = np.isfinite(xc)
        if not cut_at.all():  # nothing cut there: the first-order figure (the groove's width)
            out[~cut_at] = self.side_deviations(rho[~cut_at], cam_angle_rad[~cut_at], side[~cut_at])
        k = np.flatnonzero(cut_at)
        if len(k):
            span = 3.0 * np.abs(xc[k] - xd[k]) / rho[k] + 1e-9
            gg = g[k, None] + np.linspace(-span, span, 41, axis=1)
            near = self.design_walls(np.repeat(rho[k], 41), gg.ravel())
            dd = np.where(pick[k, None], near[0].value.reshape(gg.shape), near[1].value.reshape(gg.shape))
            d2 = (rho[k, None] * (gg - g[k, None])) ** 2 + (dd - xc[k, None]) ** 2
            best = np.array([_parabola_min(a, b)[1] for a, b in zip(gg, d2)])
            out[k] = np.where(xc[k] >= xd[k], 1.0, -1.0) * np.sqrt(np.maximum(best, 0.0)) * f3[k]
        return out


def _parabola_min(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """The smallest sample of y(x) on an even grid, moved to the vertex of the parabola through it and its neighbours."""
    j = int(np.argmin(y))
    if 0 < j < len(y) - 1:
        y0, y1, y2 = y[j - 1], y[j], y[j + 1]
        den = y0 - 2 * y1 + y2
        if den > 0:
            t = 0.5 * (y0 - y2) / den  # in grid steps, |t| ≤ 1/2
            return float(x[j] + t * (x[1] - x[0])), float(y1 - 0.25 * (y0 - y2) * t)
    return float(x[j]), float(y[j])


def _refine(setup: _Setup, found: list, rho_lo: float, rho_hi: float, d_rho: float,
            d_th: float) -> list[tuple[float, float, float]]:
    """Refine each grid extreme of sign·deviation at (ρ0, θc0): local grids in θc, then ρ, then θc again.

    ``found`` holds (side, sign, ρ0, θc0); all of them are refined together, each step one envelope of every
    extreme's angles (a scattered envelope's figure at an angle is the one it has alone: the same figures as
    one by one, a quarter of the envelopes).  Returns (ρ, θc, exact signed deviation there) for each.
    """
    n = len(found)
    if n == 0:
        return []
    side = np.array([f[0] for f in found])
    sign, rho0, th0 = (np.array([f[i] for f in found], float) for i in (1, 2, 3))

    def values(rho, th):
        """sign·deviation of each extreme's wall at (ρ, θc) (n, m) arrays: (n, m)."""
        m = th.shape[1]
        v = setup.side_deviations(rho.ravel(), th.ravel(), np.repeat(side, m)).reshape(n, m)
        return sign[:, None] * v

    def best_th(rho, th, half, m):
        tt = th[:, None] + np.linspace(-half, half, m)
        v = values(np.repeat(rho[:, None], m, axis=1), tt)
        return np.array([_parabola_min(t, -x)[0] for t, x in zip(tt, v)])

    th = best_th(rho0, th0, d_th, 33)
    lo, hi = np.maximum(rho_lo, rho0 - d_rho), np.minimum(rho_hi, rho0 + d_rho)
    rr = np.linspace(lo, hi, 9, axis=1)
    vals = values(rr, np.repeat(th[:, None], 9, axis=1))  # each radius at θc: one scattered envelope
    rho = rr[np.arange(n), np.argmax(vals, axis=1)]
    th = best_th(rho, th, d_th / 8, 17)
    exact = setup.exact_deviations(rho, th, side)
    return [(float(a), float(b), float(c)) for a, b, c in zip(rho, th, exact)]


def pose_step_for(tolerance_mm: float, tool_radius_mm: float,
                  budget: GrooveBudget = DEFAULT_GROOVE_BUDGET) -> float:
    """The pose step (mm) whose sampling bound h²/(8 r) is at most ``budget``'s
    :attr:`~camcam.toolpath.budget.GrooveBudget.sampling_share` × the tolerance (:meth:`GrooveBudget.pose_step_for
    <camcam.toolpath.budget.GrooveBudget.pose_step_for>`), and at most its ``pose_step_mm``.

    Examples
    --------
    >>> round(pose_step_for(0.02, 8.0), 6)  # cylindrical-translating's 0.02 mm: bound 4e-4 mm, 2 % of it
    0.16
    >>> pose_step_for(0.5, 8.0)  # a coarse tolerance: the resolution cap, bound 3.9e-3 mm
    0.5
    >>> round(pose_step_for(0.001, 8.0), 6)  # 0.001 mm: bound 2e-5 mm
    0.035777
    """
    return budget.pose_step_for(tolerance_mm, tool_radius_mm)


def measure_groove(cam: CylindricalCam, tool: CylinderTool, poses: ToolPoses, *, radii: int | np.ndarray = 11,
                   angle_step_deg: float = 0.25, pose_step_mm: float = POSE_STEP_MM,
                   workers: int = 1) -> GrooveMeasurement:
    """Measure the groove the poses cut against the designed groove: both walls, all radii, all angles.

    Parameters
    ----------
    cam : CylindricalCam
    tool : CylinderTool
        The flat end mill.
    poses : ToolPoses
        The program's poses as printed.
    radii : int or array
        Radii of the map: a count from the groove bottom to the outer radius, or the radii (mm).
    angle_step_deg : float
        Cam-angle step of the map (must divide 360).
    pose_step_mm : float
        Largest step of a tool section between motion samples before refinement.
    workers : int
        Processes that share the map's radii (:func:`camcam.workers.parallel_map`; the same figures for any
        count).  The four extremes are refined together in this process: a few envelopes of 4 × 33 angles, too
        little work to fork for.

    Returns
    -------
    GrooveMeasurement
        The map and, per wall, the largest overcut and material left, refined off the grid.

    Examples
    --------
    A roller-sized tool posed like the roller (tip 10 mm under the groove bottom) cuts the designed groove:

    >>> from camcam.geometry.cylindrical import BarrelTranslatingRoller, CylindricalCam
    >>> from camcam.motion.catalog import make_law
    >>> from camcam.motion.program import MotionProgram, Segment
    >>> law = make_law("cycloidal")
    >>> prog = MotionProgram((Segment(law, 0, 180, 20.0), Segment(law, 180, 360, -20.0, base=20.0)), rpm=60)
    >>> cam = CylindricalCam(BarrelTranslatingRoller(8.0), prog, 50.0, length=80.0, groove_depth=10.0)
    >>> X, Y, Z, a, B = follower_poses(cam, np.radians(np.arange(0.0, 360.01, 0.1)))
    >>> poses = ToolPoses(np.stack([X, Y, Z + 30.0], axis=-1), np.degrees(a), np.degrees(B))
    >>> m = measure_groove(cam, CylinderTool(8.0, 40.0), poses, radii=3, angle_step_deg=2.0)
    >>> bool(m.measured_mm < 1e-4)  # chords 0.1° apart: s″·Δθ²/8 ≤ 2e-5 mm
    True
    >>> round(m.sampling_bound_mm, 7)  # 0.1² / (8 · 8): what the motion's sampling could miss
    0.0001563
    """
    n_ang = int(round(360.0 / angle_step_deg))
    if abs(n_ang * angle_step_deg - 360.0) > 1e-9:
        raise ValueError(f"angle_step_deg must divide 360, got {angle_step_deg!r}")
    rb, R = cam.bottom_radius, cam.base_radius
    rad = np.linspace(rb, R, int(radii)) if np.ndim(radii) == 0 else np.asarray(radii, float)
    th = np.radians(np.arange(n_ang) * angle_step_deg)
    setup = _Setup(cam, tool, poses, pose_step_mm)
    rows = parallel_map(lambda rho: setup.deviations(float(rho), th), rad, workers)
    dev = np.empty((2, len(rad), n_ang))
    uncut = 0
    for i, ((d0, d1), u) in enumerate(rows):  # wall 0 = −X (flank 0), wall 1 = +X (flank 1)
        dev[0, i], dev[1, i] = d0, d1
        uncut += int(u.sum())
    d_rho = (rad[-1] - rad[0]) / max(len(rad) - 1, 1)
    d_th = math.radians(angle_step_deg)
    found = []  # per (wall, sign): the grid extreme and whether it is refined
    for side in (0, 1):
        for sign in (1.0, -1.0):
            flat = int(np.argmax(sign * dev[side]))
            i, j = np.unravel_index(flat, dev[side].shape)
            grid_v = float(dev[side, i, j])
            # nothing cut there (the figure is the groove width): no refinement
            found.append((side, sign, float(rad[i]), float(th[j]), grid_v,
                          bool(np.isfinite(grid_v) and abs(grid_v) < 0.5 * cam.roller_radius)))
    todo = [f for f in found if f[5]]
    done = iter(_refine(setup, [f[:4] for f in todo], float(rad[0]), float(rad[-1]), d_rho, d_th))
    refined = [next(done) if f[5] else None for f in found]
    ext = []
    for (side, sign, rho_g, t_g, grid_v, _), r in zip(found, refined):
        if r is None or sign * grid_v > sign * r[2]:  # the refined figure never reports less than the grid found
            rho, t, v = rho_g, t_g, grid_v
        else:
            rho, t, v = r
        ext.append(WallExtreme(float(v), float(rho), float(math.degrees(t) % 360.0)))
    walls = [WallDeviation(0, ext[0], ext[1]), WallDeviation(1, ext[2], ext[3])]
    bound = pose_step_mm**2 / (8.0 * tool.radius_mm)
    return GrooveMeasurement(radii_mm=frozen_array(rad), cam_angle_deg=frozen_array(np.degrees(th)),
                             deviation_mm=frozen_array(dev), walls=(walls[0], walls[1]),
                             sampling_bound_mm=float(bound), pose_step_mm=float(pose_step_mm), uncut_points=uncut)


def design_walls(cam: CylindricalCam, radius_mm: float, cam_angle_deg,
                 pose_step_mm: float = POSE_STEP_MM) -> np.ndarray:
    """The designed walls' x (−X wall, +X wall) at radius ρ and program cam angles θc: (n, 2), mm."""
    motion = RollerMotion(cam)
    s = motion.samples(pose_step_mm, cam.base_radius)
    g = -cam.sigma * np.radians(np.atleast_1d(np.asarray(cam_angle_deg, float)))
    e0, e1 = envelope(motion, s, motion.pose(s), float(radius_mm), g)
    return np.stack([-e0.value, e1.value], axis=-1)


def cut_walls(cam: CylindricalCam, tool: CylinderTool, poses: ToolPoses, radius_mm: float, cam_angle_deg,
              pose_step_mm: float = POSE_STEP_MM) -> np.ndarray:
    """The cut walls' x (−X wall, +X wall) at radius ρ and program cam angles θc: (n, 2), mm; NaN where uncut."""
    motion = ProgramMotion(poses, tool)
    s = motion.samples(pose_step_mm, cam.base_radius)
    g = -cam.sigma * np.radians(np.atleast_1d(np.asarray(cam_angle_deg, float)))
    e0, e1 = envelope(motion, s, motion.pose(s), float(radius_mm), g)
    out = np.stack([-e0.value, e1.value], axis=-1)
    return np.where(np.isfinite(out), out, np.nan)
