"""Follower force, contact force, camshaft torque and Hertz stress along the cam angle (single degree of freedom).

The model is the standard lumped one (Norton, *Cam Design and Manufacturing Handbook*, ch. 10 and
*Design of Machinery*, §15.4 and §15.6; Rothbart, *Cam Design Handbook*, ch. 8): the follower train is one
rigid mass (or inertia about the pivot), one linear spring, one viscous damper and an external load.

Generalised coordinate q: the lift in m (translating follower) or the swing ψ in rad (oscillating), with
q′ = dq/dθ, q″ = d²q/dθ² (θ the cam angle, rad) and q̇ = ω q′, q̈ = ω² q″ at constant cam speed ω.  The
generalised force the cam must supply along increasing lift (N along the axis, or N·m about the pivot) is

    Q(θ, ω) = M q″ ω² + c_g q′ ω + w·(P + k·x(θ) + F_ext(θ))

M the mass or inertia, c_g the damping (c, or c·a² for a damper at arm a), w the lever of the spring and the
load (1 for a translating follower, a = ``load_arm_mm`` in m for an oscillating one), x the spring's deflection
(the lift in mm, or the arc a·ψ), P the preload, k the rate.  Q is a quadratic in ω (affine in ω² without
damping) at each angle: that makes the jump speed a root per angle (:func:`first_root`), not a grid search.

Contact force along the contact normal (N), with φ the pressure angle and μ the guide friction:

* translating roller: F_n = Q / (cos φ − μ·sgn(q′)·|sin φ|): the lateral force F_n·|sin φ| presses the stem
  against its guide, whose friction opposes the motion (Norton, Design of Machinery §15.6 without friction;
  the friction term as in Rothbart §8.4's single-guide model);
* translating flat face: F_n = Q (the normal is the follower's axis; the face's own sliding friction is not
  modelled);
* oscillating roller: F_n = Q / (L·cos φ), L the arm (the normal's moment arm about the pivot is L·cos φ);
* oscillating flat face: F_n = Q / ℓ, ℓ the contact's distance along the face from the pivot (the face
  passes through the pivot, so the normal is perpendicular to it).

Camshaft torque: T = σ·F_n·(P × n)_z, P a point of the contact normal line (the roller centre, or the
contact point of a flat face) and n the unit normal along which the cam pushes, both in the fixed frame, σ
the rotation sign; a barrel's normal has the tangential part F_n·sin φ at the contact radius R: T = σ F_n sin φ R.
Without friction the power balance gives T = Q·q′ (T ω = Q q̇): the tests hold the two to 1e-9.

Hertz line contact (Johnson, *Contact Mechanics*, eq. 4.45; Norton, *Machine Design*, §7.10): p_max =
√(F_n E* / (π L R′)) with E* from both materials (:func:`~camcam.dynamics.train.contact_modulus_mpa`),
L the contact length (roller width; a flat face: the cam's thickness) and 1/R′ = 1/r_roller + 1/ρ_profile,
ρ the profile's radius of curvature, negative where concave.  In terms of the pitch curve's convex-positive
curvature κ (ρ_profile = 1/κ − r): R′ = r·(1 − r·κ) on the flank the roller touches from the convex side, and
r·(1 + r·κ) on the opposite flank of a groove.  A flat face on a curve: R′ = ρ_profile.

Grooved cams (face groove, barrel) drive the follower both ways (positive drive): no spring, no jump; a
positive Q loads the flank that lifts the follower, a negative one the other flank.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.dynamics.train import DynamicsSpec, contact_modulus_mpa
from camcam.errors import SpecError
from camcam.geometry.analysis import convex_curvature, flat_radius
from camcam.geometry.jetcurve import LiftJet

__all__ = ["Coefficients", "coefficients", "Forces", "forces", "forces_of", "hertz_line_mpa", "check_friction", "first_root", "is_grooved", "cam_pieces",
           "external_load", "damping_coefficient", "damping_of", "train_terms", "follower_lever_m", "contact_length_mm", "lift_flank"]


def is_grooved(built) -> bool:
    """A face-groove or barrel cam: positive drive, no spring."""
    return built.spec.kind != "disc"


def _is_barrel(built) -> bool:
    return built.spec.kind == "cylindrical"


def _disc(built):
    """The open disc cam under a face groove, or the disc cam itself."""
    return built.cam.cam if built.spec.kind == "disc-groove" else built.cam


def _oscillating(built) -> bool:
    return built.cam.program.unit == "deg"


def cam_pieces(built) -> list[tuple[float, float]]:
    """The analytic pieces (θ from, θ to) in rad: the motion segments."""
    br = built.cam.breaks
    return list(zip(br[:-1], br[1:]))


def lift_flank(built) -> int:
    """The flank (index) that pushes the follower along increasing lift: a face groove's inner flank 0; a
    barrel's flank on the other side of the roller from its ``plus_side``."""
    if _is_barrel(built):
        return 1 - built.cam.follower.plus_side
    return 0


def follower_lever_m(built, d: DynamicsSpec) -> float:
    """w: 1 for a translating follower, the load arm in m for an oscillating one."""
    if not _oscillating(built):
        return 1.0
    follower = built.cam.follower if _is_barrel(built) else _disc(built).follower
    arm = d.load_arm_mm if d.load_arm_mm is not None else getattr(follower, "arm_length", None)
    if arm is None:  # a barrel's oscillating roller without arm_length: the reference cross-section's arm
        arm = built.cam.follower.pivot_distance - built.cam.reference_radius
    return arm / 1000.0


def damping_coefficient(built, d: DynamicsSpec) -> float:
    """c_g: N·s/m (translating) or N·m·s/rad (oscillating, a damper c at the load arm: c·a²)."""
    return damping_of(d, _oscillating(built), follower_lever_m(built, d))


def damping_of(d: DynamicsSpec, oscillating: bool, lever_m):
    """:func:`damping_coefficient` for the lever w (a number, or an array: one per design of a sizing sweep)."""
    w = lever_m
    if d.damping_n_s_per_m is not None:
        return d.damping_n_s_per_m * w * w
    if d.damping_ratio is not None:
        k = d.spring_rate_n_per_mm * 1000.0 * w * w  # N/m, or N·m/rad at the pivot
        mass = d.inertia_kgm2 if oscillating else d.mass_kg
        return 2.0 * d.damping_ratio * np.sqrt(k * mass)
    return 0.0


def train_terms(d: DynamicsSpec, oscillating: bool, lever_m, theta, q0, q1, q2):
    """(inertia, damping, static, x mm, F_ext) of Q = inertia·ω² + damping·ω + static at cam angles θ (rad),
    from the lift q, q′, q″ (m or rad, per rad of cam angle); ``lever_m`` w a number, or an array that
    broadcasts against q (one per design: the sizing sweep, :mod:`camcam.sizing.contact`)."""
    w = lever_m
    if oscillating:
        x = q0 * w * 1000.0  # the arc at the load arm, mm
        mass = d.inertia_kgm2
    else:
        x = q0 * 1000.0
        mass = d.mass_kg
    ext = external_load(d, theta)
    static = w * (d.preload_n + d.spring_rate_n_per_mm * x + ext)
    return mass * q2, damping_of(d, oscillating, w) * q1, static, x, ext


def external_load(d: DynamicsSpec, theta) -> np.ndarray:
    """F_ext at cam angles θ (rad), N: the constant, or the table linear between its rows, periodic."""
    theta = np.asarray(theta, float)
    if d.external_load_table is None:
        return np.full(theta.shape, d.external_load_n)
    ang = np.array([a for a, _ in d.external_load_table])
    val = np.array([v for _, v in d.external_load_table])
    return np.interp(np.mod(np.degrees(theta), 360.0), ang, val, period=360.0)


def contact_length_mm(built, d: DynamicsSpec) -> float:
    """L: the roller width, or a flat face's contact across the cam's thickness."""
    if built.cam.roller_radius > 0:
        return float(d.roller_width_mm)
    return float(built.spec.thickness)


@dataclass(frozen=True, kw_only=True)
class Coefficients:
    """Per cam angle: Q(ω) = inertia·ω² + damping·ω + static, the gains from Q to F_n, the torque arm, R′.

    ``static`` = w·(P + k·x + F_ext); ``deflection_mm`` x and ``external_n`` F_ext let the spring sizing
    rebuild it for another spring.  ``gain_lift`` (Q ≥ 0) and ``gain_return`` (Q < 0, grooves) turn |Q|
    into the contact force (N); ``torque_arm_m``: T = F_n(signed)·torque_arm.  ``radius_lift_mm`` and
    ``radius_return_mm`` are R′ on the lift and the return flank (NaN for an open cam's return).
    """

    theta: np.ndarray
    inertia: np.ndarray
    damping: np.ndarray
    static: np.ndarray
    lever_m: float
    deflection_mm: np.ndarray
    external_n: np.ndarray
    rate: np.ndarray
    gain_lift: np.ndarray
    gain_return: np.ndarray
    torque_arm_m: np.ndarray
    radius_lift_mm: np.ndarray
    radius_return_mm: np.ndarray
    cos_phi: np.ndarray
    sin_phi: np.ndarray

    def generalised_force(self, omega: float) -> np.ndarray:
        """Q at cam speed ω (rad/s): N (translating) or N·m (oscillating)."""
        return self.inertia * omega * omega + self.damping * omega + self.static


def coefficients(built, d: DynamicsSpec, theta, piece: int | None = None, radii: bool = True) -> Coefficients:
    """The :class:`Coefficients` at cam angles θ (rad); ``piece`` evaluates one motion segment one-sided;
    ``radii=False`` leaves R′ out (NaN: the spring sizing needs no curvature)."""
    theta = np.atleast_1d(np.asarray(theta, float))
    cam = built.cam
    osc = _oscillating(built)
    program = cam.program
    # the program's own lift (the spring's deflection is counted from lift 0), q in m or rad
    q = LiftJet(program, math.pi / 180.0 if osc else 1e-3)(theta, 2, piece)
    w = follower_lever_m(built, d)
    inertia, damping, static, x, ext = train_terms(d, osc, w, theta, q.d[0], q.d[1], q.d[2])
    sg = cam.sigma
    r = cam.roller_radius
    mu = d.friction
    direction = np.sign(q.d[1])
    nan = np.full(theta.shape, np.nan)
    if _is_barrel(built):
        rho = cam.reference_radius
        phi = cam.pressure_angle(theta, 0, piece, radius_mm=rho).value
        c, s = np.cos(phi), np.sin(phi)
        if osc:
            ell = cam.follower.pivot_distance - rho
            theta_f = cam.lift(theta, 0, piece).value  # the swing from the centred position, rad
            R_mm = cam.follower.pivot_distance - ell * np.cos(theta_f)
            arm = ell / 1000.0
        else:
            R_mm = np.full(theta.shape, rho)
            arm = 1.0
        gain_lift = 1.0 / (arm * (c - mu * direction * np.abs(s)))
        gain_return = 1.0 / (arm * (c + mu * direction * np.abs(s)))
        torque_arm = sg * s * R_mm / 1000.0
        kc = convex_curvature(cam.developed_centre(rho), 1, theta, piece)[0] if radii else nan
        # flank 1 lies on the side of the developed centre line's centre of curvature where κc < 0
        r1, r0 = r * (1.0 + r * kc), r * (1.0 - r * kc)
        up = lift_flank(built)
        radius_lift, radius_return = (r0, r1) if up == 0 else (r1, r0)
        return Coefficients(theta=theta, inertia=inertia, damping=damping, static=static, lever_m=w, deflection_mm=x,
                            external_n=ext, rate=q.d[1], gain_lift=gain_lift, gain_return=gain_return,
                            torque_arm_m=torque_arm,
                            radius_lift_mm=radius_lift, radius_return_mm=radius_return, cos_phi=c, sin_phi=s)
    disc = _disc(built)
    if disc.is_roller:
        e = disc.element(theta, 1, piece)
        px, py = e.x.value, e.y.value
        tx = e.x.d[1] + sg * py  # the cam-frame tangent in the fixed frame: P′ − σJP
        ty = e.y.d[1] - sg * px
        norm = np.hypot(tx, ty)
        nx, ny = -sg * ty / norm, sg * tx / norm  # outward normal σ·J·T̂ (the cam pushes along it)
        c = nx * e.ux.value + ny * e.uy.value
        s = nx * e.uy.value - ny * e.ux.value
        arm = disc.follower.arm_length / 1000.0 if osc else 1.0
        fr = 0.0 if osc else mu
        gain_lift = 1.0 / (arm * (c - fr * direction * np.abs(s)))
        gain_return = 1.0 / (arm * (c + fr * direction * np.abs(s)))
        kc = convex_curvature(disc.pitch, sg, theta, piece)[0] if radii else nan
        radius_lift = r * (1.0 - r * kc)
        radius_return = r * (1.0 + r * kc) if is_grooved(built) else nan
    else:
        e = disc.element(theta, 0, piece)
        px, py, nx, ny = e.x.value, e.y.value, e.nx.value, e.ny.value
        c, s = np.ones(theta.shape), np.zeros(theta.shape)
        gain_lift = 1.0 / (e.along.value / 1000.0) if osc else np.ones(theta.shape)
        gain_return = gain_lift
        radius_lift = flat_radius(disc, theta, piece)[0] if radii else nan
        radius_return = nan
    torque_arm = sg * (px * ny - py * nx) / 1000.0
    return Coefficients(theta=theta, inertia=inertia, damping=damping, static=static, lever_m=w, deflection_mm=x,
                        external_n=ext, rate=q.d[1], gain_lift=gain_lift, gain_return=gain_return,
                        torque_arm_m=torque_arm,
                        radius_lift_mm=radius_lift, radius_return_mm=radius_return, cos_phi=c, sin_phi=s)


def first_root(a, b, c) -> np.ndarray:
    """The smallest ω ≥ 0 past which a·ω² + b·ω + c turns negative (inf where it never does; 0 where c < 0),
    element-wise.

    Each case in the form free of cancellation (Numerical Recipes §5.6)."""
    a, b, c = (np.asarray(v, float) for v in (a, b, c))
    a, b, c = np.broadcast_arrays(a, b, c)
    out = np.full(a.shape, np.inf)
    disc = b * b - 4.0 * a * c
    root = np.sqrt(np.maximum(disc, 0.0))
    with np.errstate(divide="ignore", invalid="ignore"):
        neg = a < 0  # one positive root
        out = np.where(neg & (b >= 0), (b + root) / (-2.0 * a), out)
        out = np.where(neg & (b < 0), 2.0 * c / (root - b), out)
        two = (a > 0) & (b < 0) & (disc >= 0)  # two positive roots: the smaller
        out = np.where(two, 2.0 * c / (root - b), out)
        lin = (a == 0) & (b < 0)
        out = np.where(lin, -c / b, out)
    # no force at rest: Q = ω(aω + b) goes negative at once if b < 0 (or b = 0 and a < 0), at ω = −b/a if
    # a < 0 < b, never otherwise (a dwell with neither spring nor load touches with zero force at any speed)
    with np.errstate(divide="ignore", invalid="ignore"):
        at_rest = np.where((b < 0) | ((b == 0) & (a < 0)), 0.0, np.where((a < 0) & (b > 0), -b / a, np.inf))
    return np.where(c > 0, out, np.where(c == 0, at_rest, 0.0))


@dataclass(frozen=True, kw_only=True)
class Forces:
    """Arrays along the cam angle at one speed (``contact_force_n`` signed: > 0 on the lift flank)."""

    theta: np.ndarray
    generalised: np.ndarray  # Q: N (translating) or N·m about the pivot (oscillating)
    contact_force_n: np.ndarray
    torque_nm: np.ndarray
    torque_power_balance_nm: np.ndarray  # Q·q′: the torque without friction, by the power balance
    contact_stress_mpa: np.ndarray
    lift_flank_force_n: np.ndarray
    return_flank_force_n: np.ndarray


def forces(built, d: DynamicsSpec, rpm: float, theta, piece: int | None = None, radii: bool = True) -> Forces:
    """Every figure along the cam angles θ (rad) at ``rpm``; open cams' contact force is negative past a jump
    (the pull the cam would need), with no stress there.  ``radii=False``: no curvature, stress NaN (faster)."""
    return forces_of(built, d, rpm, coefficients(built, d, theta, piece, radii))


def forces_of(built, d: DynamicsSpec, rpm: float, k: Coefficients) -> Forces:
    """:func:`forces` from the coefficients at its angles (computed once for several uses)."""
    omega = 2.0 * math.pi * rpm / 60.0
    Q = k.generalised_force(omega)
    fn = np.where(Q >= 0, Q * k.gain_lift, Q * k.gain_return)
    up = np.maximum(fn, 0.0)
    down = np.maximum(-fn, 0.0) if is_grooved(built) else np.zeros_like(fn)
    e = contact_modulus_mpa(d.cam_material, d.follower_material)
    L = contact_length_mm(built, d)
    with np.errstate(invalid="ignore", divide="ignore"):
        p_up = np.sqrt(up * e / (math.pi * L * k.radius_lift_mm))
        p_down = np.sqrt(down * e / (math.pi * L * k.radius_return_mm)) if is_grooved(built) else np.zeros_like(fn)
    stress = np.where(fn >= 0, p_up, p_down)
    return Forces(theta=k.theta, generalised=Q, contact_force_n=fn, torque_nm=fn * k.torque_arm_m,
                  torque_power_balance_nm=Q * k.rate, contact_stress_mpa=stress, lift_flank_force_n=up,
                  return_flank_force_n=down)


def hertz_line_mpa(force_n, modulus_mpa, length_mm, radius_mm):
    """p_max = √(F E* / (π L R′)), MPa (force N, modulus MPa, lengths mm)."""
    return np.sqrt(np.asarray(force_n, float) * modulus_mpa / (math.pi * length_mm * np.asarray(radius_mm, float)))


def check_friction(built, d: DynamicsSpec, cos_phi, sin_phi, theta) -> None:
    """Raise :class:`SpecError` where the guide friction locks the follower (cos φ ≤ μ|sin φ|)."""
    if d.friction <= 0:
        return
    bad = cos_phi - d.friction * np.abs(sin_phi) <= 0
    if np.any(bad):
        i = int(np.flatnonzero(bad)[0])
        phi = math.degrees(math.atan2(abs(sin_phi[i]), cos_phi[i]))
        raise SpecError("dynamics.friction", f"{d.friction:g} locks the follower in its guide at cam angle "
                        f"{math.degrees(theta[i]) % 360:.2f}° (pressure angle {phi:.2f}°); expected less than "
                        f"cot φ = {1 / math.tan(math.radians(phi)):.4g}")
