"""Cylindrical cams with an oscillating roller on a 5-axis machine: the tool axis on the roller axis.

Machine frame (DESIGN.md "Machine frames", printed in every program's
header): the cam axis is machine X with Y = Z = 0 on it and X0 at the cam's
left end face; A turns the part about +X (``a_axis = "right-hand"``: a part
point p sits at Rx(A)·p; ``"left-hand"``: at Rx(−A)·p); at B = 0 the tool axis
points along +Z, B tilts it in the X–Z plane to (sin B, 0, cos B), positive by
the right-hand rule about +Y; X Y Z are the tool tip (centre of the flat end)
with tool-centre-point control on.

The follower frame of :mod:`camcam.geometry.cylindrical` is this machine
frame: the cam turns by σθ about +X (p_fixed = Rx(σθ)·p_cam), the pivot sits
at (length/2, 0, d) and the roller axis points from the roller to the pivot
along (sin θf, 0, cos θf).  So the tool takes the roller's place when

    A = s·θ (degrees, s = σ for a right-hand A axis, −σ for a left-hand one),
    B = θf (the follower angle), tip on the roller axis at arm distance ℓ_tip:
    X = length/2 − ℓ_tip·sin θf,  Z = d − ℓ_tip·cos θf,  Y = 0.

With a tool of the roller's diameter the tool *is* the roller (extended
along its axis), so it cuts both walls exactly at every radius.  The tip
goes deep enough that both walls are cut down to the groove bottom r_b: a
wall point at arm distance ℓ lies r_r·cos α·|sin θf| above the axis point
and r_r·sin α aside it (α: the pressure angle), so the axis point at the
tip sits at radius z_tip = √(r_b² − r_r² sin²α_max) − r_r·√(sin²θf + ε²)
(ε = 0.01 keeps it smooth where θf changes sign).  The flat end's low edge
dips below r_b there, into the groove floor, which no roller touches.

Fit.  Between blocks every word moves linearly; A is linear in the cam angle,
so a block's interpolated pose at its A is compared with the exact pose at
the same cam angle.  A pose error moves the tool's side surface, normal to
the wall (the wall normal m = cos α·n ± sin α·e_Y, n = (−cos B, 0, sin B)),
by cos α·(n·ΔT − ℓ′·ΔB) at the distance ℓ′ from the tip (ΔT: tip error, ΔB:
tilt error in radians): linear in ℓ′, so the largest value over the cut
length [0, L] is at the tip or at L.  The fit places nodes on the printed
A grid and holds max(|n·ΔT|, |n·ΔT − L·ΔB|) — cos α ≤ 1 dropped — within
:attr:`FiveAxisBudget.fit_share <camcam.toolpath.budget.FiveAxisBudget.fit_share>` × tolerance on the
printed numbers; the result reports the same
figure on a denser sampling.  Feeds are inverse time (G93) with the tool
tip's path length in the part frame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import FitError, GeometryError, InputError
from camcam.geometry.build import BuiltCam
from camcam.nc.feeds import with_cutting_data
from camcam.nc.passes import with_markers
from camcam.nc.result import GroovePlan, MachiningResult
from camcam.nc.settings import MachiningSpec
from camcam.nc.tools import SAME_TOOL_MM, job_title
from camcam.toolpath.arcfit import FitResult
from camcam.toolpath.budget import DEFAULT_FIVE_AXIS_BUDGET, FiveAxisBudget
from camcam.toolpath.contours import CutContour, SegmentBlocks
from camcam.toolpath.deviation import Deviation
from camcam.toolpath.elements import Line
from camcam.toolpath.path import Feed, Pass, Rapid, Toolpath, depth_levels, shortest_rotation
from camcam.toolpath.quantizer import Quantizer

__all__ = ["ToolPose", "FivePath", "fit_five_axis", "machine_five_axis", "frame_comments", "tool_axis", "part_pose"]

#: Samples per block while fitting / when reporting the fitted figure.
FIT_SAMPLES, REPORT_SAMPLES = 24, 96
#: Smoothing of |sin θf| in the tip depth (rad).
EPS = 0.01
#: The groove contour's label (the pass comments and the pass table name it).
LABEL = "groove (5-axis, tool on the roller axis)"


def tool_axis(b_deg) -> np.ndarray:
    """Tool axis direction(s) (sin B, 0, cos B) in the machine frame, (n, 3)."""
    b = np.radians(np.atleast_1d(np.asarray(b_deg, float)))
    return np.stack([np.sin(b), np.zeros_like(b), np.cos(b)], axis=-1)


def part_pose(x, y, z, a_deg, b_deg, a_axis: str = "right-hand"):
    """Tool tip and axis in the part (cam) frame from machine words: Rx(∓A)·p (the contract's inverse).

    Examples
    --------
    >>> tip, axis = part_pose(10.0, 0.0, 70.0, 90.0, 0.0)
    >>> [round(float(v), 9) + 0.0 for v in tip[0]], [round(float(v), 9) + 0.0 for v in axis[0]]
    ([10.0, 70.0, 0.0], [0.0, 1.0, 0.0])
    """
    s = 1.0 if a_axis == "right-hand" else -1.0
    a = -s * np.radians(np.atleast_1d(np.asarray(a_deg, float)))
    c, sn = np.cos(a), np.sin(a)

    def rot(p):
        px, py, pz = (np.broadcast_to(np.asarray(v, float), a.shape) for v in p)
        return np.stack([px, c * py - sn * pz, sn * py + c * pz], axis=-1)

    ax = tool_axis(b_deg)
    ax = np.broadcast_to(ax, a.shape + (3,))
    return rot((x, y, z)), rot((ax[..., 0], ax[..., 1], ax[..., 2]))


@dataclass(frozen=True)
class ToolPose:
    """The exact 5-axis pose of a roller-sized tool along an oscillating roller's groove.

    ``sign`` turns the cam angle into A (s = σ, or −σ for a left-hand A axis);
    ``tip_radius`` is z_tip's constant part √(r_b² − r_t² sin²α_max).
    """

    cam: object
    tool_radius_mm: float
    sign: int
    tip_radius: float

    @staticmethod
    def of(cam, tool_radius_mm: float, a_axis: str) -> "ToolPose":
        sign = cam.sigma * (1 if a_axis == "right-hand" else -1)
        d, rb, rt = cam.follower.pivot_distance, cam.bottom_radius, tool_radius_mm
        th = np.linspace(0.0, 2 * math.pi, 14401)
        f = cam.lift(th, 1)
        ell = (d - rb + rt) / np.cos(f.value)  # a little deeper than the tip: α grows with ℓ
        tan_a = np.abs(f.d[1] * ell) / (d - ell * np.cos(f.value))
        sin2 = float((tan_a**2 / (1 + tan_a**2)).max())
        sin2 = min(1.0, sin2 * 1.02 + 1e-4)  # the grid's max can sit a little below the true one
        return ToolPose(cam, rt, sign, math.sqrt(rb * rb - rt * rt * sin2))

    def jets(self, theta, K: int = 0):
        """(X, Z, B[rad]) jets of the final pass's tip at program angles ``theta``."""
        cam, rt = self.cam, self.tool_radius_mm
        d = cam.follower.pivot_distance
        f = cam.lift(np.atleast_1d(np.asarray(theta, float)), K)
        s, c = f.sin(), f.cos()
        z = (s * s + EPS * EPS).sqrt() * (-rt) + self.tip_radius
        ell = (z * -1.0 + d) / c
        x = s * ell * -1.0 + 0.5 * cam.length
        return x, z, f

    def at(self, theta) -> np.ndarray:
        """(n, 3): X, Z, B in degrees of the final pass."""
        x, z, f = self.jets(theta, 0)
        return np.stack([x.value, z.value, np.degrees(f.value)], axis=-1)

    def a_deg(self, theta) -> np.ndarray:
        return self.sign * np.degrees(theta)

    def theta(self, a_deg) -> np.ndarray:
        return np.radians(np.asarray(a_deg, float)) / self.sign

    def cut_length(self) -> float:
        """Largest distance along the tool axis from the tip to the top of the walls (radius R), mm."""
        th = np.linspace(0.0, 2 * math.pi, 7201)
        x, z, f = self.jets(th)
        reach = (self.cam.base_radius + self.tool_radius_mm * np.abs(np.sin(f.value)) - z.value) / np.cos(f.value)
        return float(reach.max())

    def floor_radius(self) -> float:
        """Smallest radius the tool's flat end reaches (its low edge at the largest tilt), mm."""
        th = np.linspace(0.0, 2 * math.pi, 7201)
        _, z, f = self.jets(th)
        return float((z.value - self.tool_radius_mm * np.abs(np.sin(f.value))).min())


def block_errors(pose: ToolPose, p0: np.ndarray, p1: np.ndarray, cut_length: float, samples: int) -> np.ndarray:
    """Error model (mm) inside blocks from printed nodes ``p0`` to ``p1`` (n, 4: X, Z, A°, B°): (n, 2), the
    largest over ``samples`` interior points at the tip (ℓ′ = 0) and at the top of the cut (ℓ′ = L)."""
    t = (np.arange(samples) + 0.5) / samples
    p0, p1 = p0[:, None, :], p1[:, None, :]
    q = p0 + (p1 - p0) * t[None, :, None]  # (blocks, samples, 4)
    th = pose.theta(q[..., 2]).ravel()
    ex = pose.at(th).reshape(q.shape[0], samples, 3)
    bi, be = np.radians(q[..., 3]), np.radians(ex[..., 2])
    n_x, n_z = -np.cos(be), np.sin(be)
    dx, dz = q[..., 0] - ex[..., 0], q[..., 1] - ex[..., 1]
    d0 = n_x * dx + n_z * dz
    # the axis point at ℓ′ = L: T + L·(sin B, 0, cos B)
    d1 = d0 + cut_length * (n_x * (np.sin(bi) - np.sin(be)) + n_z * (np.cos(bi) - np.cos(be)))
    return np.stack([np.abs(d0).max(axis=1), np.abs(d1).max(axis=1)], axis=-1)


def _node(pose: ToolPose, a_deg: np.ndarray, quantizer: Quantizer) -> np.ndarray:
    a = quantizer.snap(a_deg)
    xzb = quantizer.snap(pose.at(pose.theta(a)))
    return np.column_stack([xzb[:, 0], xzb[:, 1], a, xzb[:, 2]])


def fit_five_axis(pose: ToolPose, tolerance_mm: float, quantizer: Quantizer, cut_length: float,
                  budget: FiveAxisBudget = DEFAULT_FIVE_AXIS_BUDGET) -> np.ndarray:
    """Printed nodes (n, 4: X, Z, A°, B°) over one revolution, every block within ``budget``'s share of the
    tolerance (:meth:`FiveAxisBudget.target_mm`).

    A march over the cam angle q (A = s·q): from each node, candidate ends at 0.3…2.5 × the last step
    (and the next motion-segment end, a node of its own) are tested together; the farthest end before
    the first one over the target is taken.
    """
    target = budget.target_mm(tolerance_mm)
    grid = np.linspace(0.3, 2.5, 23)
    nodes = [_node(pose, np.array([0.0]), quantizer)[0]]
    step = 1.0  # degrees of cam angle
    tiny = quantizer.step_mm
    for end in np.degrees(pose.cam.breaks[1:]):
        q = 0.0 if len(nodes) == 1 else abs(nodes[-1][2])
        while end - q > tiny / 2:
            while True:
                cand = np.unique(np.minimum(q + step * grid, end))
                ends = _node(pose, pose.sign * cand, quantizer)
                starts = np.repeat(nodes[-1][None, :], len(cand), axis=0)
                ok = block_errors(pose, starts, ends, cut_length, FIT_SAMPLES).max(axis=1) <= target
                if ok[0]:
                    k = len(ok) if ok.all() else int(np.argmin(ok))
                    break
                step *= 0.3
                if step < 10 * tiny:
                    raise FitError(f"5-axis fit: cannot hold {target:.4g} mm near cam angle {q:.4f}° "
                                        f"with {quantizer.decimals} decimals")
            chosen = ends[k - 1]
            step = abs(chosen[2] - nodes[-1][2])
            nodes.append(chosen)
            q = abs(chosen[2])
    return np.array(nodes)


def tip_lengths(nodes: np.ndarray) -> np.ndarray:
    """Tool-tip path length (mm) of each block in the part frame (Simpson on 9 points).

    The tip (X, 0, Z) turns with A about X, so its speed² is X′² + Z′² + (Z·A′)²."""
    t = np.linspace(0.0, 1.0, 9)
    p0, p1 = nodes[:-1], nodes[1:]
    dx, dz = p1[:, 0] - p0[:, 0], p1[:, 1] - p0[:, 1]
    da = np.radians(p1[:, 2] - p0[:, 2])
    z = p0[:, 1, None] + dz[:, None] * t[None, :]
    v = np.sqrt(dx[:, None] ** 2 + dz[:, None] ** 2 + (z * da[:, None]) ** 2)
    w = np.array([1, 4, 2, 4, 2, 4, 2, 4, 1]) / 24.0
    return v @ w


@dataclass(frozen=True, kw_only=True)
class FivePath:
    """The fitted 5-axis path of one pass: printed nodes, the error figures and the tool's reach."""

    nodes: np.ndarray
    cut_length_mm: float
    floor_radius_mm: float
    error_tip_mm: float
    error_top_mm: float
    worst_a_deg: float


def frame_comments(a_axis: str, sign: int, tcp: str) -> tuple[str, ...]:
    """The machine-frame contract as header comment lines."""
    turn = ("a positive A turns the part by the right-hand rule, a part point p sits at Rx(A)*p"
            if a_axis == "right-hand" else "a positive A turns the part by the left-hand rule, a part point p sits at Rx(-A)*p")
    return ("5-axis frame: cam axis = machine X, Y = Z = 0 on it, X0 at the cam's left end face",
            f"A turns the part about +X (a_axis {a_axis}): {turn}; A = {'+' if sign > 0 else '-'}cam angle",
            "B tilts the tool in the X-Z plane: axis (sin B, 0, cos B), B = 0 along +Z, B positive by the "
            "right-hand rule about +Y; B = follower angle (tool axis on the roller axis)",
            f"X Y Z = tool tip (centre of the flat end), tool-centre-point control on ({tcp})")


def _developed(pose: ToolPose, nodes: np.ndarray, rho: float) -> tuple:
    """The printed path's roller-axis point at cross-section ρ, developed at ρ: lines in (u, x)."""
    d = pose.cam.follower.pivot_distance
    b = np.radians(nodes[:, 3])
    ell_tip = (d - nodes[:, 1]) / np.cos(b)
    x = nodes[:, 0] + (ell_tip - (d - rho)) * np.sin(b)
    u = rho * pose.theta(nodes[:, 2])
    pts = np.column_stack([u, x])
    return tuple(Line(tuple(map(float, p)), tuple(map(float, q))) for p, q in zip(pts[:-1], pts[1:]))


def _lower_bound(pose: ToolPose, tolerance_mm: float, cut_length: float, lo: float, hi: float) -> float:
    """Chords the error model needs at least: ∫ √(max(|n·T″|, |n·(T″ + L·a″)|) / 8δ) dθ on [lo, hi]."""
    th = np.linspace(lo, hi, 4001)
    x, z, f = pose.jets(th, 2)
    b, b2 = f.d[0], f.d[2]
    n = (-np.cos(b), np.sin(b))
    k0 = n[0] * x.d[2] + n[1] * z.d[2]
    # a″ = (cos B·B″ − sin B·B′², 0, −sin B·B″ − cos B·B′²); n·a″ = −B″
    k1 = k0 - cut_length * b2
    k = np.maximum(np.abs(k0), np.abs(k1))
    return float(np.trapezoid(np.sqrt(k / (8 * tolerance_mm)), th))


def five_axis_path(pose: ToolPose, tolerance_mm: float, quantizer: Quantizer,
                   budget: FiveAxisBudget = DEFAULT_FIVE_AXIS_BUDGET) -> FivePath:
    """Fit one revolution (within ``budget``'s share of the tolerance) and measure it on the printed numbers."""
    cut = pose.cut_length()
    nodes = fit_five_axis(pose, tolerance_mm, quantizer, cut, budget)
    err = block_errors(pose, nodes[:-1], nodes[1:], cut, REPORT_SAMPLES)
    worst = int(np.argmax(err.max(axis=1)))
    return FivePath(nodes=nodes, cut_length_mm=cut, floor_radius_mm=pose.floor_radius(),
                    error_tip_mm=float(err[:, 0].max()), error_top_mm=float(err[:, 1].max()),
                    worst_a_deg=float(0.5 * (nodes[worst, 2] + nodes[worst + 1, 2])))


def _lowest_tip_z(nodes: np.ndarray, raise_mm: float, quantizer: Quantizer) -> float:
    """The lowest tip Z a pass raised ``raise_mm`` along the tool axis prints (its cutting blocks, on the grid)."""
    return float(quantizer.snap(nodes[:, 1] + raise_mm * np.cos(np.radians(nodes[:, 3]))).min())


def _pass_moves(nodes: np.ndarray, raise_mm: float, m: MachiningSpec, outer: float, r_t: float) -> list:
    """One depth pass, the tip raised ``raise_mm`` along the tool axis: down along the axis, round, back out."""
    b = np.radians(nodes[:, 3])
    xs = nodes[:, 0] + raise_mm * np.sin(b)
    zs = nodes[:, 1] + raise_mm * np.cos(b)
    lifted = np.column_stack([xs, zs, nodes[:, 2], nodes[:, 3]])
    lengths = tip_lengths(lifted)

    def clear(i):  # the point on the tool axis where the flat end's low edge is clearance above the cam
        c = (outer + m.clearance_z_mm + r_t * abs(math.sin(b[i])) - zs[i]) / math.cos(b[i])
        return xs[i] + c * math.sin(b[i]), zs[i] + c * math.cos(b[i]), c

    x0, z0, c0 = clear(0)
    x1, z1, c1 = clear(-1)
    a0, b0 = float(nodes[0, 2]), float(nodes[0, 3])
    moves = [Rapid(float(x0), 0.0, None, a_deg=a0, b_deg=b0), Rapid(None, None, float(z0)),
             Feed(float(xs[0]), 0.0, float(zs[0]), m.plunge_feed_mm_min, a_deg=a0, length_mm=c0, b_deg=b0)]
    for k in range(1, len(nodes)):
        moves.append(Feed(float(xs[k]), 0.0, float(zs[k]), m.feed_mm_min, a_deg=float(nodes[k, 2]),
                          length_mm=float(lengths[k - 1]),
                          b_deg=float(nodes[k, 3])))
    moves += [Feed(float(x1), 0.0, float(z1), m.plunge_feed_mm_min, a_deg=float(nodes[-1, 2]), length_mm=c1,
                   b_deg=float(nodes[-1, 3])),
              Rapid(None, None, outer + m.safe_z_mm)]
    return moves


def machine_five_axis(built: BuiltCam, m: MachiningSpec, name: str) -> MachiningResult:
    """The 5-axis program of a cylindrical cam with an oscillating roller (see the module notes)."""
    cam, post = built.cam, m.post
    r_t = m.tool_diameter_mm / 2
    if r_t > cam.roller_radius + SAME_TOOL_MM:
        raise GeometryError(f"machining.tool_diameter: {2 * r_t:g} mm is wider than the groove "
                            f"({2 * cam.roller_radius:g} mm, twice the roller radius)")
    if abs(r_t - cam.roller_radius) > SAME_TOOL_MM:
        raise GeometryError(f"machining.tool_diameter: a 5-axis groove is cut by a tool of the roller's diameter "
                            f"({2 * cam.roller_radius:g} mm) riding on the roller's axis; got {m.tool_diameter_mm:g} mm "
                            f"(axes = 4 takes a smaller tool)")
    if not post.five_axis:
        raise InputError(f"post {post.name}: has no 5-axis mode (tool-centre-point control); use axes = 4 or a post with one")
    pose = ToolPose.of(cam, r_t, m.a_axis)
    path = five_axis_path(pose, m.tolerance_mm, post.quantizer)
    bore = built.spec.bore / 2
    if path.floor_radius_mm <= bore:
        raise GeometryError(f"5-axis: the tool's flat end dips to radius {path.floor_radius_mm:.2f} mm at the largest "
                            f"tilt, into the bore (radius {bore:g} mm); expected a smaller bore or a shallower groove")
    nodes = path.nodes
    levels = depth_levels(m.cut_settings())
    n = len(levels)
    outer = cam.base_radius
    step = (outer - pose.tip_radius) / n
    # pass k (in cutting order) is the final pass raised (n − 1 − k)·step along the tool axis: the first the
    # highest.  Its Z is the lowest tip Z it prints (issue 43: the table said the final pass's tip radius less
    # the raise, so the first pass read 5.57 mm below the last where the program cuts it 5.57 mm above)
    raises = [(n - 1 - k) * step for k in range(n)]
    passes = tuple(Pass(0, "slot", _lowest_tip_z(nodes, h, post.quantizer), tuple(_pass_moves(nodes, h, m, outer, r_t)),
                        direction="both")
                   for h in raises)
    # A turns back in a G0 at the safe height, or counts on where the controller has no rotary G0 (issue 47)
    passes = with_cutting_data(passes if post.rotary_rapid else shortest_rotation(passes), m)
    passes = with_markers(passes, [LABEL])
    comments = frame_comments(m.a_axis, pose.sign, post.tcp_comment(m.tool_number)) + (
        f"tool D{m.tool_diameter_mm:g} flat end mill = the roller; the cut reaches {path.cut_length_mm:.2f} mm "
        f"up the tool from its tip",
        f"{n} depth passes raised along the tool axis; final tip deep enough to cut both walls to the groove "
        f"bottom R{cam.bottom_radius:g} [the flat end dips to R{path.floor_radius_mm:.2f} in the floor]",
        post.five_axis_feed_note)
    title = job_title(name, built.spec.kind, cam.kind, m.tool_diameter_mm, "lines", m.tolerance_mm, post.name) \
        + ", 5 axes"
    toolpath = Toolpath(title, passes, passes[0].spindle_rpm or m.spindle_rpm, tool_number=m.tool_number, tool_diameter_mm=m.tool_diameter_mm,
                        rotary=True, comments=comments,
                        opening=(Rapid(None, None, outer + m.safe_z_mm),),
                        closing=(Rapid(None, None, None, a_deg=None, b_deg=0.0),), five_axis=True)
    # printed without the 3-D check: camcam.verify.job_checks measures this program and adds its result to the
    # header (the same moves)
    program = post.write_program(toolpath, name, m.setup)
    rho = cam.base_radius
    curve = cam.developed_centre(rho)
    printed = _developed(pose, nodes, rho)
    worst = max(path.error_tip_mm, path.error_top_mm)
    dev = Deviation(max_deviation_mm=worst, path_to_curve_mm=worst, curve_to_path_mm=worst, margin_mm=0.0,
                    worst_point=(rho * float(pose.theta(path.worst_a_deg)), 0.0))
    segs, pieces_blocks, bounds = [], [], []
    for lo, hi in zip(cam.breaks[:-1], cam.breaks[1:]):
        a_lo, a_hi = sorted((pose.sign * math.degrees(lo), pose.sign * math.degrees(hi)))
        mid = 0.5 * (nodes[1:, 2] + nodes[:-1, 2])
        blocks = int(((mid > a_lo) & (mid < a_hi)).sum())
        bound = _lower_bound(pose, m.tolerance_mm, path.cut_length_mm, lo, hi)
        segs.append(SegmentBlocks(math.degrees(lo), math.degrees(hi), blocks, bound))
        pieces_blocks.append(blocks)
        bounds.append(bound)
    fit = FitResult(elements=printed, mode="lines", tolerance_mm=m.tolerance_mm, decimals=post.decimals, deviation=dev,
                    lower_bound=float(sum(bounds)), piece_blocks=tuple(pieces_blocks),
                    piece_lower_bounds=tuple(bounds))
    contour = CutContour(label=LABEL, curve=curve, fit=fit, printed=printed, deviation=dev, offset_mm=cam.roller_radius,
                         leads=False, segments=tuple(segs), stock_side="both")
    notes = (f"5-axis fit model (the tool side's normal displacement at the walls, printed numbers): "
             f"{path.error_tip_mm:.5f} mm at the tip, {path.error_top_mm:.5f} mm at the top of the cut; "
             f"{len(nodes) - 1} blocks per pass",
             f"5-axis: the cut reaches {path.cut_length_mm:.2f} mm up the tool from its tip; the flat end dips to "
             f"radius {path.floor_radius_mm:.2f} mm in the groove floor")
    if m.flute_stated and m.flute_length_mm < path.cut_length_mm:  # unstated, the flute is what the cut needs
        notes += (f"flute_length {m.flute_length_mm:g} mm is shorter than the {path.cut_length_mm:.2f} mm the walls need",)
    plan = GroovePlan(axes=5, reach_radius_mm=path.floor_radius_mm,
                      reach_why="the tilted flat end, so that both walls reach the bottom; no roller touches the floor",
                      cut_length_mm=path.cut_length_mm)
    return MachiningResult(name=name, cam_kind=built.spec.kind, follower_kind=cam.kind, post=post,
                           tool_diameter_mm=m.tool_diameter_mm, tolerance_mm=m.tolerance_mm, mode="lines",
                           contours=(contour,), toolpath=toolpath, program=program, reference_radius_mm=rho,
                           notes=notes, groove_plan=plan)
