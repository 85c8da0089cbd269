"""The dynamics of one cam over its cycle: the figures a designer checks, each with the cam angle where it occurs.

:func:`analyse_dynamics` takes the built cam (:class:`camcam.geometry.build.BuiltCam`), the cam speed and a
:class:`~camcam.dynamics.train.DynamicsSpec`, and returns a frozen :class:`Dynamics`: the arrays along the
cam angle (:mod:`camcam.dynamics.forces`) and their extremes, the jump speed, the torque's RMS, the power
and the flywheel.

Extremes are found per analytic piece (motion segment), refined to 1e-12 rad, and integrals (RMS torque,
mean power, the flywheel's energy) are Gauss–Legendre per quarter degree (:mod:`camcam.dynamics.cyclewise`).
The flywheel: I = ΔE / (C_s ω²), ΔE the largest swing of ∫(T − T̄) dθ over the cycle and C_s the coefficient
of speed fluctuation (Norton, Design of Machinery, eq. 11.20).

Jump speed: at each cam angle Q(ω) = a ω² + b ω + c is a quadratic in ω (:func:`~camcam.dynamics.forces.first_root`
gives the first speed at which it turns negative, exactly); the jump speed is the least of these over the
cam angle, refined per piece like the other extremes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.dynamics.cyclewise import Sampled, bracket_grid, gauss_span, piece_minimum, section_root
from camcam.dynamics.forces import (cam_pieces, check_friction, coefficients, contact_length_mm, first_root,
                                    follower_lever_m, forces, forces_of, is_grooved, train_terms)
from camcam.geometry.jetcurve import LiftJet, program_breaks
from camcam.dynamics.train import DynamicsSpec, contact_modulus_mpa
from camcam.errors import SpecError

__all__ = ["Dynamics", "analyse_dynamics", "jump_speed", "program_jump_speed", "GRID_STEP_DEG"]

#: The step of the arrays a :class:`Dynamics` holds (the plot's and the table's), degrees.
GRID_STEP_DEG = 0.5

def jump_speed(built, d: DynamicsSpec, grid_coefficients=None) -> tuple[float, float]:
    """(ω in rad/s, cam angle in rad) of the first separation: inf for a grooved cam or one that never jumps.

    ``grid_coefficients``: the coefficients on every piece's :func:`bracket_grid`, when the caller has them."""
    if is_grooved(built):
        return math.inf, math.nan
    sampled = None
    if grid_coefficients is not None:
        sampled = Sampled([k.theta for k in grid_coefficients],
                          [first_root(k.inertia, k.damping, k.static) for k in grid_coefficients])
    return program_jump_speed(built.cam.program, d, follower_lever_m(built, d), cam_pieces(built), sampled)


def program_jump_speed(program, d: DynamicsSpec, lever_m: float, pieces=None, sampled=None) -> tuple[float, float]:
    """:func:`jump_speed` of an open cam from its motion program alone: the separation speed depends on the
    lift, the train and the lever w, not on the cam's size (the contact force is Q times a positive gain).
    ``pieces``: the motion segments in rad (default :func:`~camcam.geometry.jetcurve.program_breaks`); the
    sizing sweep's per-design jump speed (:mod:`camcam.sizing.contact`)."""
    osc = program.unit == "deg"
    jet = LiftJet(program, math.pi / 180.0 if osc else 1e-3)
    if pieces is None:
        br = program_breaks(program)
        pieces = list(zip(br[:-1], br[1:]))

    def w(t, i):
        q = jet(t, 2, i)
        a, b, c, _, _ = train_terms(d, osc, lever_m, t, q.d[0], q.d[1], q.d[2])
        return first_root(a, b, c)

    omega, theta, _ = piece_minimum(w, pieces, sampled)
    return omega, theta


@dataclass(frozen=True, kw_only=True)
class Dynamics:
    """Forces, torque and contact stress of a cam at ``rpm``, with the spring it was given or sized.

    Arrays run along ``cam_angle_deg`` (0 … 360 by :data:`GRID_STEP_DEG`; at a join the segment that
    starts there).  ``follower_force`` is Q: N along the axis for a translating follower, N·m about the
    pivot for an oscillating one (``follower_force_unit``).  ``contact_force_n`` is signed: negative past a
    jump on an open cam (the pull the cam would need), or on a groove's return flank.
    Figures are SI (N, N·m, W, kg·m², MPa); ``*_deg`` are cam angles.
    """

    rpm: float
    spec: DynamicsSpec  # with the spring used (the sized one when sized)
    positive_drive: bool
    spring_sized: bool
    spring_rule: str
    cam_angle_deg: np.ndarray
    follower_force: np.ndarray
    follower_force_unit: str
    contact_force_n: np.ndarray
    torque_nm: np.ndarray
    contact_stress_mpa: np.ndarray
    lift_flank_force_n: np.ndarray
    return_flank_force_n: np.ndarray
    max_contact_force_n: float
    max_contact_force_angle_deg: float
    min_contact_force_n: float
    min_contact_force_angle_deg: float
    jump_rpm: float | None
    jump_angle_deg: float | None
    max_torque_nm: float
    max_torque_angle_deg: float
    rms_torque_nm: float
    mean_power_w: float
    max_power_w: float
    energy_fluctuation_j: float
    flywheel_inertia_kgm2: float
    max_contact_stress_mpa: float
    max_contact_stress_angle_deg: float
    contact_modulus_mpa: float
    contact_length_mm: float

    @property
    def spring_rate_n_per_mm(self) -> float:
        return self.spec.spring_rate_n_per_mm

    @property
    def preload_n(self) -> float:
        return self.spec.preload_n

    def figures(self) -> dict:
        """The report's ``dynamics`` object (JSON-ready: None for what does not apply)."""
        s = self.spec
        out = {
            "rpm": self.rpm,
            "positive_drive": self.positive_drive,
            "max_contact_force_n": self.max_contact_force_n,
            "max_contact_force_angle_deg": self.max_contact_force_angle_deg,
            "min_contact_force_n": self.min_contact_force_n,
            "min_contact_force_angle_deg": self.min_contact_force_angle_deg,
            "jump_rpm": self.jump_rpm,
            "jump_angle_deg": self.jump_angle_deg,
            "overspeed": s.overspeed,
            "max_torque_nm": self.max_torque_nm,
            "max_torque_angle_deg": self.max_torque_angle_deg,
            "rms_torque_nm": self.rms_torque_nm,
            "mean_power_w": self.mean_power_w,
            "max_power_w": self.max_power_w,
            "energy_fluctuation_j": self.energy_fluctuation_j,
            "speed_fluctuation": s.speed_fluctuation,
            "flywheel_inertia_kgm2": self.flywheel_inertia_kgm2,
            "max_contact_stress_mpa": self.max_contact_stress_mpa,
            "max_contact_stress_angle_deg": self.max_contact_stress_angle_deg,
            "allowable_contact_stress_mpa": s.allowable_contact_stress_mpa,
            "contact_modulus_mpa": self.contact_modulus_mpa,
            "contact_length_mm": self.contact_length_mm,
            "materials": {"cam": s.cam_material.describe(), "follower": s.follower_material.describe()},
            "spring_rate_n_per_mm": None if self.positive_drive else s.spring_rate_n_per_mm,
            "preload_n": None if self.positive_drive else s.preload_n,
            "spring_sized": self.spring_sized,
        }
        if self.spring_sized:
            out["spring_rule"] = self.spring_rule
        if self.positive_drive:
            out["max_lift_flank_force_n"] = float(self.lift_flank_force_n.max())
            out["max_return_flank_force_n"] = float(self.return_flank_force_n.max())
        return out


def _deg(t: float) -> float:
    return math.degrees(t) % 360.0


def _check_at_rest(built, d: DynamicsSpec, pieces, grid_coefficients) -> None:
    """A spring that lets go at rest (Q < 0 at ω = 0) is bad input: one line naming the preload it needs."""
    if is_grooved(built):
        return
    sampled = Sampled([k.theta for k in grid_coefficients], [k.static / k.lever_m for k in grid_coefficients])
    scale = max(1.0, abs(d.preload_n), abs(d.external_load_n))
    if min(float(v.min()) for v in sampled.values) > 1e-3 * scale:  # clearly held everywhere: no need to refine
        return
    least, t, i = piece_minimum(lambda ts, j: (lambda k: k.static / k.lever_m)(coefficients(built, d, ts, j, False)), pieces,
                                sampled)
    scale = max(1.0, abs(d.preload_n), abs(d.external_load_n))
    if least < -1e-9 * scale:
        need = d.preload_n - least
        raise SpecError("dynamics.preload_n", f"{d.preload_n:g} N: the spring cannot hold the follower against the "
                        f"external load even at rest (cam angle {_deg(t):.2f}°, {-least:.4g} N short); "
                        f"expected at least {math.ceil(need * 100) / 100:g} N")


def analyse_dynamics(built, rpm: float, d: DynamicsSpec) -> Dynamics:
    """The dynamics of ``built`` at ``rpm`` with the follower train ``d`` (sizing its spring if asked).

    Raises :class:`~camcam.errors.SpecError` (bad input, exit 2) for a spring that cannot hold at rest and
    for guide friction that locks the follower.
    """
    pieces = cam_pieces(built)
    sized = False
    rule = ""
    if d.size_spring and not is_grooved(built):
        from camcam.dynamics.spring import SPRING_RULE, size_spring

        rate, preload = size_spring(built, rpm, d)
        d = d.with_spring(rate, preload)
        sized, rule = True, SPRING_RULE
    deg = np.arange(0.0, 360.0 + 1e-9, GRID_STEP_DEG)
    theta = np.radians(deg)
    k = coefficients(built, d, theta)
    check_friction(built, d, k.cos_phi, k.sin_phi, theta)
    f = forces_of(built, d, rpm, k)
    grids = [bracket_grid(a, b) for a, b in pieces]
    on_grid_k = [coefficients(built, d, ts, i) for i, ts in enumerate(grids)]
    for kk in on_grid_k:
        check_friction(built, d, kk.cos_phi, kk.sin_phi, kk.theta)
    _check_at_rest(built, d, pieces, on_grid_k)
    on_grid = [forces_of(built, d, rpm, kk) for kk in on_grid_k]
    omega = 2.0 * math.pi * rpm / 60.0

    def extreme(name: str, sign: float):
        sampled = Sampled(grids, [sign * getattr(fg, name) for fg in on_grid])
        radii = name == "contact_stress_mpa"  # only the stress needs the curvature
        value, t, _ = piece_minimum(lambda ts, i: sign * getattr(forces(built, d, rpm, ts, i, radii), name), pieces,
                                    sampled)
        return sign * value, t

    hi, hi_t = extreme("contact_force_n", -1.0)
    lo, lo_t = extreme("contact_force_n", 1.0)
    t_hi, t_hi_at = extreme("torque_nm", -1.0)
    t_lo, t_lo_at = extreme("torque_nm", 1.0)
    peak, peak_at = (t_hi, t_hi_at) if t_hi >= -t_lo else (t_lo, t_lo_at)
    p_hi, p_hi_at = extreme("contact_stress_mpa", -1.0)
    mean_t, rms, ek = _torque_integrals(built, d, rpm, pieces, grids, on_grid)
    if is_grooved(built):
        jump, jump_at = None, None
    else:
        w_j, t_j = jump_speed(built, d, on_grid_k)
        jump = w_j * 60.0 / (2 * math.pi) if math.isfinite(w_j) else None
        jump_at = _deg(t_j) if math.isfinite(w_j) else None
    osc = built.cam.program.unit == "deg"
    return Dynamics(
        rpm=rpm, spec=d, positive_drive=is_grooved(built), spring_sized=sized, spring_rule=rule,
        cam_angle_deg=deg, follower_force=f.generalised, follower_force_unit="N·m" if osc else "N",
        contact_force_n=f.contact_force_n, torque_nm=f.torque_nm, contact_stress_mpa=f.contact_stress_mpa,
        lift_flank_force_n=f.lift_flank_force_n, return_flank_force_n=f.return_flank_force_n,
        max_contact_force_n=hi, max_contact_force_angle_deg=_deg(hi_t),
        min_contact_force_n=lo, min_contact_force_angle_deg=_deg(lo_t),
        jump_rpm=jump, jump_angle_deg=jump_at,
        max_torque_nm=abs(peak), max_torque_angle_deg=_deg(peak_at), rms_torque_nm=rms,
        mean_power_w=mean_t * omega, max_power_w=abs(peak) * omega,
        energy_fluctuation_j=ek, flywheel_inertia_kgm2=ek / (d.speed_fluctuation * omega * omega),
        max_contact_stress_mpa=p_hi, max_contact_stress_angle_deg=_deg(p_hi_at),
        contact_modulus_mpa=contact_modulus_mpa(d.cam_material, d.follower_material),
        contact_length_mm=contact_length_mm(built, d),
    )


def _torque_integrals(built, d, rpm, pieces, grids, on_grid) -> tuple[float, float, float]:
    """(mean torque N·m, RMS torque N·m, ΔE J): Gauss–Legendre per grid cell; ΔE = max − min of
    E(θ) = ∫₀^θ (T − T̄), its extremes at roots of T − T̄ next to the grid's best point."""
    cells, squares = [], []
    for i, ts in enumerate(grids):
        nodes, weights = gauss_span(ts[:-1], ts[1:])
        T = forces(built, d, rpm, nodes.ravel(), i, radii=False).torque_nm.reshape(nodes.shape)
        cells.append(np.sum(weights * T, axis=1))
        squares.append(np.sum(weights * T * T, axis=1))
    mean = float(sum(c.sum() for c in cells)) / (2 * math.pi)
    rms = math.sqrt(max(0.0, float(sum(q.sum() for q in squares)) / (2 * math.pi)))
    energies, start = [], 0.0
    for ts, c in zip(grids, cells):
        E = start + np.concatenate([[0.0], np.cumsum(c - mean * np.diff(ts))])
        energies.append(E)
        start = E[-1]

    def g(t, i):
        return forces(built, d, rpm, t, i, radii=False).torque_nm - mean

    def extreme_energy(sign: float) -> float:
        i, j = max(((i, int(np.argmax(sign * E))) for i, E in enumerate(energies)),
                   key=lambda ij: sign * energies[ij[0]][ij[1]])
        ts, E, gv = grids[i], energies[i], on_grid[i].torque_nm - mean
        found = [sign * E[j]]
        for a, b in ((j - 1, j), (j, j + 1)):
            if 0 <= a and b < len(ts) and gv[a] * gv[b] < 0:
                r = section_root(g, ts[a], ts[b], i)
                nodes, weights = gauss_span([ts[a]], [r])
                found.append(sign * (E[a] + float(np.sum(weights * g(nodes.ravel(), i).reshape(nodes.shape)))))
        return sign * max(found)

    return mean, rms, extreme_energy(1.0) - extreme_energy(-1.0)
