"""Cylindrical (barrel) cams: a roller runs in a groove around a cylinder.

Frame (DESIGN.md): cam axis along +X, the cylinder spans x ∈ [0, length];
the cam turns about +X in direction ``rotation`` (σ = +1 "ccw" seen from +X).
The follower sits above the cam (+Z); its roller axis is radial at the
follower's start position, so a radial end mill of the roller's radius cuts
the groove the roller needs.  Cam-frame point of a fixed point p at program
angle θ: p turned by −σθ about X.

Followers (their classes live with their kinds in :mod:`camcam.geometry.followers`,
each kind's ``barrel``; the cam asks them for the roller axis, :meth:`axis_point`):

* :class:`BarrelTranslatingRoller` – roller axis along Z at x = x₀ + s(θ),
  the lift centred on the cylinder's length.
* :class:`BarrelOscillatingRoller` – seed 002: the arm pivots about an axis
  parallel to Y at (length/2, 0, d), d = ``pivot_distance``; the follower
  angle is θf = s(θ) − (s_max + s_min)/2 (swing centred on the perpendicular);
  the roller axis lies along the arm.  The roller cross-section at arm distance
  ℓ is at distance d − ℓ cos θf from the cam axis; "radius ρ" below means the
  cross-section ℓ = d − ρ (radius ρ at θf = 0).  Seed 002's r is such an ℓ.

Contact (any depth).  A roller cross-section with centre C, normal to the
roller axis, spanned by the motion direction n and e_Y: the contact is
p = C ± r_r·m, m = cos α·n + sin α·e_Y, where m must be normal to the
relative velocity of cam and follower.  That gives

    tan α = −σ·v / R,   v = s′ (translating) or θf′·ℓ (oscillating),
                        R = ρ or d − ℓ cos θf (distance of C from the axis),

and the pressure angle is φ = atan2(σv, R) (the angle between m and n).
This is seed 002's eq. 17 (tan φz = r ω_f / v_c, v_c from eq. 16).  Seed
002's eqs. 10–12 give the same point in its frame (cam axis Z, pivot on +Y,
so its (x, y, z) is our (Y, Z, X) up to the pivot position), with one error:
eq. 11 has (d − r)·cos θf where the arm geometry (and the paper's own eq. 16,
v_c = (d − r cos θf)·ω_c) require d − r·cos θf; both agree only at θf = 0.
We use d − r·cos θf.

Flank 0 is the groove wall on the −X side, flank 1 on the +X side.  Each
flank curve "at radius ρ" is the contact line on the roller cross-section ρ
(what a radial cutter's cross-section at that depth cuts); its true distance
from the axis is √(R² + (r_r sin α)²) ≥ R for the translating roller.
:meth:`CylindricalCam.flank_on_surface` gives the points on the cylinder
r = ρ exactly (solved per point), used for the mesh.

The developed (unrolled) groove at radius ρ maps a point at cam-frame polar
angle φ (about X, from +Y) and axial x to (u, x), u = ρ·σ·(π/2 − φ): the
groove centre line is u = ρθ.
"""

from __future__ import annotations

import functools
import math
from dataclasses import KW_ONLY, dataclass, field

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.disc import SIGMA, CamBasics
from camcam.geometry.followers import BarrelOscillatingRoller, BarrelTranslatingRoller
from camcam.geometry.jet import Jet
from camcam.geometry.jetcurve import JetCurve, LiftJet, SpaceCurve
from camcam.motion.program import MotionProgram

__all__ = ["BarrelTranslatingRoller", "BarrelOscillatingRoller", "CylindricalCam"]


@dataclass(frozen=True)
class CylindricalCam(CamBasics):
    """A barrel cam: cylinder of radius ``base_radius`` and ``length``, groove ``groove_depth`` deep."""

    follower: BarrelTranslatingRoller | BarrelOscillatingRoller  # a kind's ``barrel`` follower
    program: MotionProgram
    base_radius: float
    _: KW_ONLY
    length: float
    groove_depth: float
    rotation: str = "ccw"
    bore: float = 0.0
    lift: LiftJet = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        f, R, h = self.follower, self.base_radius, self.groove_depth
        if self.rotation not in SIGMA:
            raise GeometryError(f'cam.rotation must be "ccw" or "cw", got {self.rotation!r}')
        if self.program.unit != f.unit:
            raise GeometryError(f"a {f.kind} follower needs a program in {f.unit}, got {self.program.unit}")
        if not 0 < h < R:
            raise GeometryError(f"cam.groove_depth {h:g} mm must be > 0 and smaller than the cylinder radius {R:g} mm")
        if not 0 <= self.bore / 2 < R - h:
            raise GeometryError(f"cam.bore {self.bore:g} mm must leave material under the groove bottom (radius {R - h:g} mm)")
        lo, hi = self.program.extremes(0)
        mid = 0.5 * (lo.value + hi.value)
        scale = math.pi / 180 if f.unit == "deg" else 1.0
        object.__setattr__(self, "lift", LiftJet(self.program, scale, mid))
        f.check_barrel(R, h)
        span = self.axial_extent()
        if span[0] < 0 or span[1] > self.length:
            raise GeometryError(
                f"cam.length {self.length:g} mm is too short: the groove spans x = {span[0]:.3f} … {span[1]:.3f} mm"
            )

    # -- basics (sigma, kind, roller_radius: CamBasics) ----------------------
    @property
    def bottom_radius(self) -> float:
        return self.base_radius - self.groove_depth

    @property
    def reference_radius(self) -> float:
        """Radius of seed 002's cross-section (d − r), or mid-depth."""
        own = self.follower.reference_radius(self.base_radius, self.groove_depth)
        return own if own is not None else self.base_radius - 0.5 * self.groove_depth

    def axial_extent(self) -> tuple[float, float]:
        """Smallest and largest x the groove reaches (both flanks, all depths), mm, from a dense view."""
        t = np.linspace(0, 2 * math.pi, 1441)
        xs = []
        for rho in (self.bottom_radius, self.base_radius):
            for side in (0, 1):
                xs.append(self._contact(t, 0, None, rho, side)[0].value)
        xs = np.concatenate(xs)
        return float(xs.min()), float(xs.max())

    # -- fixed-frame pieces -------------------------------------------------
    def _axis_point(self, theta, K, piece, rho, lift=None):
        """Roller-axis point C, motion direction n, speed v along n, distance R of C from the axis.

        ``lift`` is ``self.lift(theta, K + 1, piece)`` when the caller has it already."""
        s = self.lift(theta, K + 1, piece) if lift is None else lift
        n = s.d.shape[1]
        one = Jet.constant(1.0, n, K)
        rho = np.broadcast_to(np.asarray(rho, float), (n,))
        return self.follower.axis_point(s, K, rho, self.length, one)

    def _contact(self, theta, K, piece, rho, side, lift=None):
        """Fixed-frame contact point jets on flank ``side`` (0: −X wall, 1: +X wall) at radius ρ."""
        C, nvec, v, R = self._axis_point(theta, K, piece, rho, lift)
        alpha = Jet.atan2(v * (-self.sigma), R)
        ca, sa = alpha.cos(), alpha.sin()
        m = (nvec[0] * ca, sa, nvec[2] * ca)
        plus_side = self.follower.plus_side
        sign = self.roller_radius * (1.0 if side == plus_side else -1.0)
        return tuple(C[i] + m[i] * sign for i in range(3))

    def _to_cam(self, theta, p):
        x, y, z = p
        a = Jet.variable(theta, x.K) * (-self.sigma)
        c, s = a.cos(), a.sin()
        return x, c * y - s * z, s * y + c * z

    # -- curves -------------------------------------------------------------
    # (each curve's jets are a partial of one of these methods, not a lambda: the curves pickle with
    # their cam, and a MachiningResult goes to the run's child processes pickled)
    def _centre_jets(self, theta, K, piece=None, *, rho):
        return self._to_cam(theta, self._axis_point(theta, K, piece, rho)[0])

    def _flank_jets(self, theta, K, piece=None, *, rho, index):
        return self._to_cam(theta, self._contact(theta, K, piece, rho, index))

    def _developed_centre_jets(self, theta, K, piece=None, *, rho):
        return self._developed(theta, K, piece, rho, self._axis_point(theta, K, piece, rho)[0])

    def _developed_flank_jets(self, theta, K, piece=None, *, rho, index):
        return self._developed(theta, K, piece, rho, self._contact(theta, K, piece, rho, index))

    def _check_radius(self, rho: float) -> float:
        if not self.bottom_radius - 1e-9 <= rho <= self.base_radius + 1e-9:
            raise GeometryError(f"radius {rho:g} mm is outside the groove ({self.bottom_radius:g} … {self.base_radius:g} mm)")
        return float(rho)

    def centre(self, radius_mm: float) -> SpaceCurve:
        """Groove centre curve (the roller axis) at radius ρ, cam frame."""
        rho = self._check_radius(radius_mm)
        return SpaceCurve(functools.partial(self._centre_jets, rho=rho), self.breaks)

    def flank(self, index: int, radius_mm: float) -> SpaceCurve:
        """Flank ``index`` (0: −X wall, 1: +X wall) on the roller cross-section at radius ρ, cam frame."""
        rho = self._check_radius(radius_mm)
        if index not in (0, 1):
            raise ValueError(f"flank index must be 0 or 1, got {index!r}")
        return SpaceCurve(functools.partial(self._flank_jets, rho=rho, index=index), self.breaks)

    def contact_point(self, theta, radius_mm: float, index: int) -> np.ndarray:
        """Fixed-frame contact point(s) (n, 3): seed 002's eqs. 10–12 (corrected) at θc = 0."""
        p = self._contact(np.atleast_1d(np.asarray(theta, float)), 0, None, self._check_radius(radius_mm), index)
        return np.stack([j.value for j in p], axis=-1)

    def wall_point(self, theta, radius_mm, index: int) -> np.ndarray:
        """Cam-frame points (n, 3) of flank ``index`` at program angles θ, each on its own roller
        cross-section ``radius_mm`` (an array like θ, not checked against the groove): the wall as an
        exact surface of (θ, ρ), for finding the nearest wall point of a measured one."""
        theta = np.atleast_1d(np.asarray(theta, float))
        rho = np.broadcast_to(np.asarray(radius_mm, float), theta.shape)
        p = self._to_cam(theta, self._contact(theta, 0, None, rho, index))
        return np.stack([j.value for j in p], axis=-1)

    def wall_grid(self, theta, radii_mm, index: int, order: int = 0, piece: int | None = None) -> np.ndarray:
        """Flank ``index``'s wall as an exact surface of (θ, ρ) on a grid: the cam-frame points (``order`` 0) or
        their derivative along θ (``order`` 1), shape (len(θ), len(radii_mm), 3); ``piece`` evaluates one
        segment's law (one-sided at its ends), as :class:`~camcam.geometry.jetcurve.LiftJet` does."""
        theta = np.atleast_1d(np.asarray(theta, float))
        radii = np.atleast_1d(np.asarray(radii_mm, float))
        th, rho = np.repeat(theta, len(radii)), np.tile(radii, len(theta))
        # the lift depends on θ alone: evaluated once per θ, then taken for each radius
        lift = Jet(np.repeat(self.lift(theta, order + 1, piece).d, len(radii), axis=1))
        p = self._to_cam(th, self._contact(th, order, piece, rho, index, lift))
        return np.stack([j.d[order] for j in p], axis=-1).reshape(len(theta), len(radii), 3)

    def _developed(self, theta, K, piece, rho, p):
        delta = Jet.atan2(p[1], p[2])
        u = (Jet.variable(theta, K) + delta * self.sigma) * rho
        return u, p[0]

    def developed_centre(self, radius_mm: float) -> JetCurve:
        """The unrolled groove centre line at radius ρ: (u, x), u = ρθ."""
        rho = self._check_radius(radius_mm)
        return JetCurve(functools.partial(self._developed_centre_jets, rho=rho), self.breaks, closed=False,
                        inner=np.concatenate(self.inner_breaks))

    def developed_flank(self, index: int, radius_mm: float) -> JetCurve:
        """The unrolled flank ``index`` at radius ρ: (u, x)."""
        rho = self._check_radius(radius_mm)
        return JetCurve(functools.partial(self._developed_flank_jets, rho=rho, index=index), self.breaks, closed=False,
                        inner=np.concatenate(self.inner_breaks))

    def pressure_angle(self, theta, K: int = 0, piece: int | None = None, radius_mm: float | None = None) -> Jet:
        """Signed pressure angle (rad) at radius ρ (default: the groove bottom, where it is largest)."""
        rho = self.bottom_radius if radius_mm is None else self._check_radius(radius_mm)
        _, _, v, R = self._axis_point(np.atleast_1d(np.asarray(theta, float)), K, piece, rho)
        return Jet.atan2(v * self.sigma, R)

    def flank_on_surface(self, theta, index: int, radius_mm: float | None = None, iterations: int = 60) -> np.ndarray:
        """Cam-frame points (n, 3) of flank ``index`` lying exactly on the cylinder r = ρ (default the surface).

        Solved per point for the roller cross-section ρ′ whose contact point lies at r = ρ: secant steps kept
        inside a bracket [ρ − 2 r_r, ρ + 2 r_r] that holds the root (a step leaving it bisects instead), until
        the point is within 4 ulp of ρ or the bracket is that narrow; at most ``iterations`` steps.  The
        contact's radius grows with ρ′ about as fast as ρ′ does (√(ρ′² + (r_r sin α)²)), so 5 to 7 steps
        do what 60 of bisection did, to the same ~1e-14 mm (issue 49: the mesh's 14 rings took 0.15 s).
        """
        rho = self.base_radius if radius_mm is None else float(radius_mm)
        theta = np.atleast_1d(np.asarray(theta, float))
        lift = self.lift(theta, 1, None)  # the same at every step: only the cross-section's radius is solved for

        def excess(m):
            p = self._contact(theta, 0, None, m, index, lift)
            return np.hypot(p[1].value, p[2].value) - rho

        a = np.full(theta.shape, rho - 2 * self.roller_radius)
        b = np.full(theta.shape, rho + 2 * self.roller_radius)
        fa, fb = excess(a), excess(b)  # fa < 0 < fb
        x0, f0, x1, f1 = a, fa, b, fb
        close = 4 * np.spacing(rho)
        done = np.zeros(theta.shape, bool)
        for _ in range(iterations):
            with np.errstate(divide="ignore", invalid="ignore"):
                x = x1 - f1 * (x1 - x0) / (f1 - f0)
            x = np.where((x > a) & (x < b), x, 0.5 * (a + b))  # NaN (f1 = f0) or outside: bisect
            x = np.where(done, x1, x)
            fx = excess(x)
            over = fx > 0
            a, fa = np.where(over, a, x), np.where(over, fa, fx)
            b, fb = np.where(over, x, b), np.where(over, fx, fb)
            x0, f0, x1, f1 = x1, f1, x, fx
            done |= (np.abs(fx) <= close) | (b - a <= close)
            if done.all():
                break
        p = self._to_cam(theta, self._contact(theta, 0, None, x1, index, lift))
        return np.stack([j.value for j in p], axis=-1)
