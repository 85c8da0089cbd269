"""Reverse design: measured points + the cam's and follower's geometry → the follower motion.

:func:`reverse_design` orders the points by their polar angle about the cam
axis, estimates the curve's slopes (:mod:`camcam.reverse.slopes`), solves each
point for its cam angle and lift (:mod:`camcam.reverse.disc`,
:mod:`camcam.reverse.cylindrical`), checks that the cam angles come out in the
points' order and cover the revolution, and fits the motion
(:mod:`camcam.reverse.fit`).

Lift units are those of a motion program: mm, or degrees for an oscillating
follower.  A disc cam's lift is measured from the base circle (as the forward
model).  A cylindrical cam's geometry fixes the follower only relative to the
groove, so its lift is the displacement from the centre of the swing (the
forward model centres the design's swing the same way; :func:`design_motion`
gives the design in that reference).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError, InputError
from camcam.geometry.followers import follower_kind
from camcam.motion.program import MotionProgram
from camcam.reverse.cylindrical import BarrelFollower, flank_tangents, solve_cylindrical
from camcam.reverse.disc import disc_follower, profile_normals, solve_disc
from camcam.reverse.fit import DEFAULT_MAX_GAP_DEG, RecoveredMotion, fit_motion
from camcam.reverse.points import MeasuredPoints
from camcam.reverse.slopes import periodic_fit
from camcam.geometry.params import CamSpec, FollowerSpec

__all__ = ["ReverseOptions", "ReverseResult", "reverse_design", "design_motion", "BASE_TOL"]

#: A disc profile may dip this far (mm or deg of lift) inside the base circle before the
#: points are taken not to fit ``base_radius``: ten times a few micrometres of noise.
BASE_TOL = 0.02


@dataclass(frozen=True, kw_only=True)
class ReverseOptions:
    """``fit``: "periodic" or "bspline" (default: bspline, seed 002, for cylindrical cams; periodic for discs).
    ``smoothing``: GCV smoothing of the profile fit and of the recovered lifts (for measured, noisy points).
    ``slopes``: "spline" (periodic fits) or "central" (seed 002's three-point differences; cylindrical only).
    ``flank``: which groove wall a cylindrical cam's points lie on (0: −X side, 1: +X side)."""

    fit: str | None = None
    smoothing: bool = True
    slopes: str = "spline"
    flank: int = 0
    max_gap_deg: float = DEFAULT_MAX_GAP_DEG


@dataclass(frozen=True, kw_only=True)
class ReverseResult:
    """The recovered motion and per-point figures (in the points' polar order).

    ``point_velocity`` is the per-point velocity (lift/deg) of seed 002's eq. 18
    for cylindrical cams, None for discs.
    """

    motion: RecoveredMotion
    cam_kind: str
    follower_kind: str
    unit: str
    point_angles_deg: np.ndarray
    point_lift: np.ndarray
    point_velocity: np.ndarray | None


#: With smoothing on, points whose polar angles about the cam axis lie closer than this share of their
#: mean spacing are averaged into one point: no smoothing spline can tell them apart, and the banded
#: solve of the profile's smoothing spline loses definiteness on spacings near 1e-6 of the mean (a
#: 199 999-point file has neighbours 1e-10 rad apart; it still solves at 1e-4, so 1e-3 leaves a margin).
MERGE_SHARE = 1e-3

#: With smoothing on, at most this many points (after merging) go into the fits: a larger file is
#: averaged in runs of k consecutive points (in polar order), k the fewest that bring it within.  A
#: smoothing spline with a knot at every point and a bandwidth of thousands of points is singular in
#: float64 (a 199 999-point cylinder's radius, pure noise, asks for a straight line).  5000 points a
#: revolution are 0.072° apart; averaging points along an arc of curvature κ moves them inward by
#: κ·w²/24 (w the run's arc length): 3e-5 mm for a 300 mm perimeter with κ = 1/5 mm⁻¹.  Measured on
#: 199 999 noisy points, 5000 and 20 000 give the same errors (1.5e-4 and 1.6e-4 mm of lift), and
#: seed 002's chord B-spline of the lifts takes 7.7 against 22 CPU s.
MAX_FIT_POINTS = 5_000


#: A cyclic gap in the points' polar angles above this many degrees: every point lies on one side of
#: the cam axis, so the rows are not a profile measured round the cam (e.g. (angle, radius) rows read
#: as x, y).  A smaller gap is left to the cam-angle coverage check (``--max-gap``).
ONE_SIDE_GAP_DEG = 180.0


def _not_round_the_axis(points: MeasuredPoints, u, v, phi: np.ndarray, names: tuple[str, str]) -> InputError:
    """The one-line error for points that do not surround the cam axis, saying what they look like."""
    gaps = np.diff(np.concatenate([phi, [phi[0] + 2 * math.pi]]))
    i = int(np.argmax(gaps))
    lo, hi = math.degrees(phi[(i + 1) % phi.size]), math.degrees(phi[i])
    a, b = names
    ranges = f"{a} {u.min():.4g} … {u.max():.4g} mm, {b} {v.min():.4g} … {v.max():.4g} mm"
    hint = ""
    for name, col in ((a, u), (b, v)):
        if col.min() >= -2 * math.pi and col.max() <= 2 * math.pi and col.max() - col.min() > 3.0:
            hint = (f"; the {name} column holds values within ±2π only, like angles in radians: reverse design reads "
                    f"cartesian {a}, {b} in mm, so convert (angle, radius) rows to {a} = r·cos, {b} = r·sin first")
            break
    return InputError(
        f"{points.source}: the points do not go round the cam axis: their polar angles about it all lie from "
        f"{lo:.2f}° to {hi:.2f}° (no point in the other {math.degrees(gaps[i]):.2f}°; {ranges}); expected a profile "
        f"measured round the cam{hint}"
    )


def _polar_order(points: MeasuredPoints, X: np.ndarray, axes: tuple[int, int], merge: bool
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The points ordered by their polar angle φ about the cam axis (columns ``axes`` of ``X``).

    Returns (index of each ordered point's first file row, φ strictly rising in [0, 2π), the ordered
    points).  ``merge`` (with smoothing): points closer in φ than :data:`MERGE_SHARE` of the mean spacing
    are averaged, and more than :data:`MAX_FIT_POINTS` are averaged in runs of consecutive points;
    otherwise two points at one polar angle are refused.
    """
    names = ("xyz"[axes[0]], "xyz"[axes[1]])
    u, v = X[:, axes[0]], X[:, axes[1]]
    phi = np.mod(np.arctan2(v, u), 2 * math.pi)
    order = np.argsort(phi, kind="stable")
    phi = phi[order]
    if np.max(np.diff(np.concatenate([phi, [phi[0] + 2 * math.pi]]))) > math.radians(ONE_SIDE_GAP_DEG):
        raise _not_round_the_axis(points, u, v, phi, names)
    Xo = X[order]
    if merge:
        gap_after = np.diff(np.concatenate([phi, [phi[0] + 2 * math.pi]]))
        ends = gap_after >= MERGE_SHARE * 2 * math.pi / phi.size
        runs = int(np.count_nonzero(ends))
        k = max(1, math.ceil(runs / MAX_FIT_POINTS))
        if runs < phi.size or k > 1:
            # group id of each point: its run of close points (a run may wrap past 2π: start after an end),
            # then k runs a group; each group is averaged into one point
            shift = (int(np.flatnonzero(ends)[-1]) + 1) % phi.size
            Xr, ordr, ends = np.roll(Xo, -shift, axis=0), np.roll(order, -shift), np.roll(ends, -shift)
            group = np.concatenate([[0], np.cumsum(ends[:-1])]) // k
            starts = np.flatnonzero(np.diff(group, prepend=-1))
            counts = np.diff(np.append(starts, phi.size))
            Xo = np.add.reduceat(Xr, starts, axis=0) / counts[:, None]
            order = ordr[starts]
            phi = np.mod(np.arctan2(Xo[:, axes[1]], Xo[:, axes[0]]), 2 * math.pi)
            s = np.argsort(phi, kind="stable")
            phi, Xo, order = phi[s], Xo[s], order[s]
        return order, phi, Xo
    same = np.flatnonzero(np.diff(phi) <= 1e-12)
    if same.size:
        i, j = order[same[0]], order[same[0] + 1]
        raise InputError(f"{points.describe(int(j))}: same polar angle about the cam axis as {points.describe(int(i))}; remove the duplicate")
    return order, phi, Xo


def _check_order(points: MeasuredPoints, order: np.ndarray, theta: np.ndarray) -> None:
    """The cam angles of points in polar order must run one way round, once."""
    d = np.angle(np.exp(1j * (np.roll(theta, -1) - theta)))
    sign = np.sign(np.median(d))
    bad = np.flatnonzero(np.sign(d) != sign)
    if bad.size:
        i = int(bad[0])
        j = (i + 1) % theta.size
        raise GeometryError(
            f"{points.describe(int(order[i]))} and {points.describe(int(order[j]))} come out at cam angles "
            f"{math.degrees(theta[i]):.3f}° and {math.degrees(theta[j]):.3f}°, against the order of the points round "
            "the cam: the points do not fit this follower's geometry"
        )


def reverse_design(points: MeasuredPoints, cam: CamSpec, follower: FollowerSpec,
                   options: ReverseOptions = ReverseOptions()) -> ReverseResult:
    """Recover the follower motion from measured points (module docstring)."""
    if cam.kind == "cylindrical":
        return _reverse_cylindrical(points, cam, follower, options)
    if cam.kind != "disc":
        raise GeometryError(f'cam.kind "{cam.kind}": reverse design handles "disc" and "cylindrical" cams')
    order, phi, P = _polar_order(points, points.xyz[:, :2], (0, 1), options.smoothing)
    r = np.hypot(P[:, 0], P[:, 1])
    fit_r = periodic_fit(phi, r, options.smoothing)
    rr = fit_r(phi)
    Q = np.stack([rr * np.cos(phi), rr * np.sin(phi)], axis=-1)  # the fitted profile at the points
    fol = disc_follower(follower)
    theta, lift = solve_disc(fol, cam.base_radius, cam.rotation, Q, profile_normals(phi, rr, fit_r(phi, 1)))
    _check_order(points, order, theta)
    unit = follower.unit
    if unit == "deg":
        lift = np.degrees(lift)
    k = int(np.argmin(lift))
    if lift[k] < -BASE_TOL:
        raise GeometryError(
            f"the profile dips {-lift[k]:.4f} {unit} of lift inside the base circle at cam angle "
            f"{math.degrees(theta[k]):.2f}° ({points.describe(int(order[k]))}): the points do not fit "
            f"cam.base_radius = {cam.base_radius:g} mm (the points come within {r.min():.4f} mm of the centre)"
        )
    motion = fit_motion(np.degrees(theta), lift, unit, options.fit or "periodic", options.smoothing, options.max_gap_deg)
    return ReverseResult(motion=motion, cam_kind=cam.kind, follower_kind=follower.kind, unit=unit,
                         point_angles_deg=np.degrees(theta), point_lift=lift, point_velocity=None)


def _reverse_cylindrical(points, cam, follower, options) -> ReverseResult:
    if points.dims != 3:
        raise InputError(f"{points.source}: a cylindrical cam needs x, y, z points (cam axis along x); got x, y only")
    if not follower.is_roller:
        raise GeometryError(f'follower.kind "{follower.kind}": a cylindrical cam needs a roller follower')
    if options.flank not in (0, 1):
        raise ValueError(f"flank must be 0 or 1, got {options.flank!r}")
    pivot = follower_kind(follower.kind).barrel_from_spec(follower).pivot_distance  # None: a translating roller
    bf = BarrelFollower(roller_radius=follower.roller_radius, length=cam.length, rotation=cam.rotation,
                        pivot_distance=pivot, flank=options.flank,
                        inner_radius=cam.base_radius - cam.groove_depth, outer_radius=cam.base_radius)
    order, phi, X = _polar_order(points, points.xyz, (1, 2), options.smoothing)
    t = flank_tangents(phi, X[:, 0], np.hypot(X[:, 1], X[:, 2]), options.slopes, options.smoothing)
    sol = solve_cylindrical(bf, X, t, lambda i: points.describe(int(order[i])))
    _check_order(points, order, sol.cam_angle)
    unit = follower.unit
    scale = 180.0 / math.pi if unit == "deg" else 1.0
    lift = sol.q * scale
    vel = sol.dq * scale * math.pi / 180.0  # per degree of cam angle
    motion = fit_motion(np.degrees(sol.cam_angle), lift, unit, options.fit or "bspline", options.smoothing, options.max_gap_deg)
    return ReverseResult(motion=motion, cam_kind=cam.kind, follower_kind=follower.kind, unit=unit,
                         point_angles_deg=np.degrees(sol.cam_angle), point_lift=lift, point_velocity=vel)


def design_motion(program: MotionProgram, cam_kind: str, angles_deg, order: int) -> np.ndarray:
    """The design's lift derivative ``order`` per degree at ``angles_deg``, in the reference
    :func:`reverse_design` recovers (centred on the swing for a cylindrical cam)."""
    theta = np.radians(np.asarray(angles_deg, dtype=float))
    val = program.lift(theta, order) * (math.pi / 180.0) ** order
    if order == 0 and cam_kind == "cylindrical":
        lo, hi = program.extremes(0)
        val = val - 0.5 * (lo.value + hi.value)
    return val
