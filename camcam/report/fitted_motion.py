"""The follower motion the fitted NC program will actually produce (disc cams).

The machined cam is the envelope of the tool along the printed tool-centre
path T (lines and arcs).  Every contact of the follower with it is a contact
with one element of T, continued analytically: an arc is a circle, a line a
line, and a corner a circle of radius 0.  For each cam angle θ we find the
element in contact and solve the follower kinematics exactly against it
(Newton on the lift s, vectorised):

* roller follower (radius r_r, tool radius r_t): the roller centre q(s) lies
  at signed distance r_r − r_t outside T;
* flat face (normal n(s) away from the cam, a point Q(s) on it): the face
  touches T's support in direction n less r_t: h_T(n) − r_t = Q·n.  Concave
  arcs and lines can only be touched at their ends, so they count as corners.

V, A, J are one-sided derivatives of that contact, taken by 5-point central
differences at step ``h`` on the same element (so a stencil never straddles a
join): the acceleration of an arc spline jumps at every join (curvature jumps),
so J is reported inside the contact pieces and the jumps are counted.

Solved to |g| < 1e-12 mm; the stencils then carry rounding errors of about
1e-12/h^k: with h = 2e-3 rad that is < 2e-4 mm/rad³ in J, far below any
cam's jerk; truncation is O(h⁴·s⁽⁵⁾/30) for V and A, O(h²·s⁽⁵⁾/4) for J.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import CamcamFault, GeometryError
from camcam.geometry.curve import left_normal
from camcam.geometry.disc import DiscCam
from camcam.geometry.jet import Jet
from camcam.toolpath.elements import Arc, element_distance

__all__ = ["FittedMotion", "fitted_motion"]

#: 5-point stencil step in cam angle (rad); see the module docstring for the error budget.
STENCIL_STEP_RAD = 2e-3


@dataclass(frozen=True, kw_only=True)
class FittedMotion:
    """Design and as-machined follower motion on a grid of cam angles.

    ``design`` and ``fitted`` have shape (4, n): lift, velocity, acceleration,
    jerk in the program's physical units (:data:`camcam.motion.program.PHYSICAL_UNITS`).
    ``element`` is the index of the tool-path element in contact at each angle.
    """

    angles_deg: np.ndarray
    design: np.ndarray
    fitted: np.ndarray
    element: np.ndarray
    units: tuple[str, str, str, str]

    def max_error(self, order: int) -> tuple[float, float]:
        """Largest |fitted − design| of derivative ``order`` and the cam angle (deg) where it occurs."""
        err = np.abs(self.fitted[order] - self.design[order])
        i = int(np.argmax(err))
        return float(err[i]), float(self.angles_deg[i])

    @property
    def contact_changes(self) -> int:
        """How many times the contact moves to another element over the grid (each a jump of A)."""
        return int(np.count_nonzero(np.diff(self.element)))


def _contacts(cam: DiscCam, tool_curve, nominal: np.ndarray, elements, theta: np.ndarray):
    """Per angle: the index of the element in contact (nearest to the exact tool-centre point
    ``nominal``), and o, the side of travel the material is not on."""
    dists = np.array([element_distance(e, nominal) for e in elements])
    idx = np.argmin(dists, axis=0)
    # outward (away from material) = o · left normal of the direction of travel
    o = float(np.sign(np.sum(left_normal(tool_curve, theta[:1]) * cam.normal(theta[:1]))))
    return idx, o


def _element_geometry(e, o: float, flat: bool, q_nominal: np.ndarray):
    """('circle', centre, radius, sign) or ('line', point, outward normal); sign +1 = convex."""
    if isinstance(e, Arc):
        sign = -o if e.ccw else o  # +1 when outward points away from the centre
        if not flat or sign > 0:
            return "circle", np.asarray(e.centre, float), e.radius, sign
    elif not flat:
        p0, p1 = np.asarray(e.start, float), np.asarray(e.end, float)
        t = (p1 - p0) / np.linalg.norm(p1 - p0)
        return "line", p0, o * np.array([-t[1], t[0]]), 1.0
    # a flat face touches a line or a concave arc only at an end: the nearer corner
    ends = np.array([e.start, e.end], float)
    k = int(np.argmin(np.hypot(*(ends - q_nominal).T)))
    return "circle", ends[k], 0.0, 1.0


def fitted_motion(cam: DiscCam, elements, tool_radius: float, angles_deg: np.ndarray) -> FittedMotion:
    """Follower motion produced by the fitted tool-centre path ``elements`` (cam frame, mm).

    Parameters
    ----------
    cam : DiscCam
        The designed cam (its follower, rotation and program).
    elements : sequence of Line | Arc
        The printed tool-centre path (one closed contour), as fitted.
    tool_radius : float
        Tool radius in mm.
    angles_deg : ndarray, shape (n,)
        Cam angles at which to evaluate.
    """
    theta = np.radians(np.asarray(angles_deg, dtype=float))
    program = cam.program
    scale = math.pi / 180.0 if cam.follower.unit == "deg" else 1.0
    flat = not cam.is_roller
    tool_curve = cam.offset_profile(tool_radius)
    nominal_tool = tool_curve.evaluate(theta, 0)
    idx, o = _contacts(cam, tool_curve, nominal_tool, elements, theta)
    geo = [_element_geometry(elements[i], o, flat, nominal_tool[j]) for j, i in enumerate(idx)]
    s_design = [program.lift(theta, k) * scale for k in range(4)]
    h = STENCIL_STEP_RAD
    offsets = np.array([-2, -1, 0, 1, 2]) * h
    th = (theta[:, None] + offsets[None, :]).ravel()
    rep = np.repeat(np.arange(theta.size), offsets.size)
    s = program.lift(th) * scale  # start from the design lift (mm or rad)
    gap = tool_radius if flat else cam.roller_radius - tool_radius

    kinds = np.array([g[0] == "circle" for g in geo])[rep]
    a = np.array([g[1] for g in geo])[rep]
    rad = np.array([g[2] if g[0] == "circle" else 0.0 for g in geo])[rep]
    nrm = np.array([g[2] if g[0] == "line" else (0.0, 0.0) for g in geo])[rep]
    sgn = np.array([g[3] for g in geo])[rep]
    c, sn = np.cos(-cam.sigma * th), np.sin(-cam.sigma * th)

    def residual(s_val: np.ndarray) -> np.ndarray:
        jet = Jet(np.array([s_val, np.zeros_like(s_val)]))  # derivative 0: only the element's pose is used
        el = cam.follower.element(jet, cam.base_radius, cam.sigma)
        x, y = el.x.value, el.y.value
        qx, qy = c * x - sn * y, sn * x + c * y  # fixed → cam frame
        if flat:
            nx, ny = el.nx.value, el.ny.value
            mx, my = c * nx - sn * ny, sn * nx + c * ny
            support = a[:, 0] * mx + a[:, 1] * my + rad
            return support - gap - (qx * mx + qy * my)
        circle = (np.hypot(qx - a[:, 0], qy - a[:, 1]) - rad) * sgn
        line = (qx - a[:, 0]) * nrm[:, 0] + (qy - a[:, 1]) * nrm[:, 1]
        return np.where(kinds, circle, line) - gap

    # converged when the residual is at rounding level for the lengths it is computed from (1e-12 mm at
    # 100 mm): the cam's and the contour's, and the follower's own — an oscillating follower's element is
    # placed from its pivot, pivot_distance + arm_length away (5000 mm: the residual rounds to 2.2e-12 mm)
    follower = sum(abs(float(getattr(cam.follower, k, 0.0) or 0.0)) for k in ("pivot_distance", "arm_length", "offset"))
    size = (cam.base_radius + getattr(cam, "roller_radius", 0.0) + float(np.max(np.abs(a))) + float(np.max(rad))
            + follower)
    tol = 1e-12 * max(1.0, size / 100.0)
    for _ in range(60):
        g = residual(s)
        eps = 1e-7
        dg = (residual(s + eps) - g) / eps
        if np.any(dg == 0):
            raise GeometryError("the follower does not meet the machined contour (flat residual)")
        step = g / dg
        s = s - step
        if np.max(np.abs(g)) < tol:
            break
    else:
        # ours, not the spec's: the contour was fitted and measured; only this analysis of it failed (exit 1)
        raise CamcamFault(f"the as-machined follower motion did not converge (residual {np.max(np.abs(g)):.2e} mm, "
                          f"{tol:.1e} mm needed)")
    S = s.reshape(theta.size, offsets.size)
    fitted_rad = np.array(
        [
            S[:, 2],
            (-S[:, 4] + 8 * S[:, 3] - 8 * S[:, 1] + S[:, 0]) / (12 * h),
            (-S[:, 4] + 16 * S[:, 3] - 30 * S[:, 2] + 16 * S[:, 1] - S[:, 0]) / (12 * h * h),
            (S[:, 4] - 2 * S[:, 3] + 2 * S[:, 1] - S[:, 0]) / (2 * h**3),
        ]
    )
    design = np.array([program.to_physical(s_design[k] / scale, k) for k in range(4)])
    fitted = np.array([program.to_physical(fitted_rad[k] / scale, k) for k in range(4)])
    return FittedMotion(angles_deg=np.asarray(angles_deg, float), design=design, fitted=fitted, element=idx,
                        units=program.units)
