"""One design's figures from the full geometry: :class:`~camcam.geometry.disc.DiscCam` and
:func:`~camcam.geometry.analysis.analyse` (root-found extremes), the reference the sweep's
closed forms are checked against and the best design's figures come from.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from camcam.errors import GeometryError
from camcam.geometry.analysis import analyse, max_pressure_angle, undercut_margin
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import follower_kind
from camcam.motion.program import MotionProgram

__all__ = ["ExactFigures", "exact_figures", "design_cam", "outer_radius"]


@dataclass(frozen=True, kw_only=True)
class ExactFigures:
    """A design's figures by the full geometry; ``problem`` says why it cannot be built ("" if it can)."""

    max_pressure_angle_deg: float
    max_pressure_angle_at_deg: float
    min_curvature_radius_mm: float
    min_curvature_radius_at_deg: float
    min_concave_radius_mm: float
    undercut: bool
    outer_radius_mm: float
    problem: str = ""
    # with the [size] dynamics constraints: the figures of `camcam run`'s dynamics stage (analyse_dynamics)
    max_contact_stress_mpa: float = math.nan
    jump_rpm: float = math.nan  # inf: never separates
    dynamics_problem: str = ""  # the one line `camcam run` would stop with (a locked guide, a spring too weak)

    @property
    def valid(self) -> bool:
        return not self.problem


def design_cam(kind: str, program: MotionProgram, params: dict[str, float], rotation: str) -> DiscCam:
    """The disc cam of one design (raises :class:`GeometryError` when it cannot be built)."""
    return DiscCam(follower_kind(kind).from_params(params), program, params["base_radius"], rotation)


def outer_radius(cam: DiscCam, per_piece: int = 720) -> float:
    """Largest distance of the profile from the cam centre, mm (dense samples, then bounded Brent on each piece's best)."""
    best = 0.0
    for i, (a, b) in enumerate(zip(cam.breaks, cam.breaks[1:])):
        t = np.linspace(a, b, per_piece + 1)
        p = cam.profile.evaluate(t, 0, i)
        r = np.hypot(p[:, 0], p[:, 1])
        k = int(np.argmax(r))
        lo, hi = t[max(k - 1, 0)], t[min(k + 1, t.size - 1)]

        def neg(x, i=i):
            q = cam.profile.evaluate(np.array([x]), 0, i)[0]
            return -math.hypot(q[0], q[1])

        res = minimize_scalar(neg, bounds=(lo, hi), method="bounded", options={"xatol": 1e-12})
        best = max(best, float(r[k]), -float(res.fun))
    return best


def exact_figures(kind: str, program: MotionProgram, params: dict[str, float], rotation: str,
                  dynamics=None) -> ExactFigures:
    """Figures of one design by the full geometry; ``dynamics`` (a
    (:class:`~camcam.sizing.contact.SweepDynamics`, ``[cam]`` spec) pair) adds the contact stress and the
    jump speed by :func:`camcam.dynamics.cycle.analyse_dynamics`, as `camcam run` computes them.

    Examples
    --------
    >>> from camcam.motion.catalog import make_law
    >>> from camcam.motion.program import MotionProgram, Segment
    >>> p = MotionProgram((Segment(make_law("cycloidal"), 0, 180, 10.0),
    ...                    Segment(make_law("cycloidal"), 180, 360, -10.0, base=10.0)), rpm=60)
    >>> f = exact_figures("translating-roller", p, {"base_radius": 30.0, "offset": 0.0, "roller_radius": 5.0}, "ccw")
    >>> round(f.outer_radius_mm, 9), f.undercut
    (40.0, False)
    """
    nan = math.nan
    try:
        cam = design_cam(kind, program, params, rotation)
    except GeometryError as err:
        return ExactFigures(max_pressure_angle_deg=nan, max_pressure_angle_at_deg=nan, min_curvature_radius_mm=nan,
                            min_curvature_radius_at_deg=nan, min_concave_radius_mm=nan, undercut=False,
                            outer_radius_mm=nan, problem=str(err))
    margin, _ = undercut_margin(cam)
    if margin <= 0:
        pa = max_pressure_angle(cam)
        return ExactFigures(max_pressure_angle_deg=pa.value, max_pressure_angle_at_deg=pa.angle_deg,
                            min_curvature_radius_mm=nan, min_curvature_radius_at_deg=nan, min_concave_radius_mm=nan,
                            undercut=True, outer_radius_mm=nan)
    an = analyse(cam)
    concave = an.profile.min_concave_radius.value if an.profile.min_concave_radius is not None else math.inf
    extra = _dynamics_figures(cam, an, params, dynamics) if dynamics is not None else {}
    return ExactFigures(**extra,max_pressure_angle_deg=an.max_pressure_angle_deg.value,
                        max_pressure_angle_at_deg=an.max_pressure_angle_deg.angle_deg,
                        min_curvature_radius_mm=an.profile.min_radius_mm,
                        min_curvature_radius_at_deg=an.profile.angle_deg, min_concave_radius_mm=concave, undercut=False,
                        outer_radius_mm=outer_radius(cam))


def _dynamics_figures(cam: DiscCam, an, params: dict[str, float], dynamics) -> dict:
    """The contact stress and jump speed of one design, by the dynamics stage of `camcam run`."""
    from dataclasses import replace

    from camcam.dynamics.cycle import analyse_dynamics
    from camcam.errors import SpecError
    from camcam.geometry.build import BuiltCam

    contact, cam_spec = dynamics
    built = BuiltCam(cam=cam, analysis=an, mesh_parts=None, spec=replace(cam_spec, base_radius=params["base_radius"]))
    try:
        dyn = analyse_dynamics(built, contact.rpm, contact.spec)
    except SpecError as err:
        return {"max_contact_stress_mpa": math.inf, "jump_rpm": 0.0, "dynamics_problem": str(err)}
    return {"max_contact_stress_mpa": dyn.max_contact_stress_mpa,
            "jump_rpm": math.inf if dyn.jump_rpm is None else dyn.jump_rpm}
