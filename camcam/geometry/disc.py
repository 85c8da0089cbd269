"""Disc cams: pitch curve, profile and its offsets as exact curves of the cam angle.

The cam turns about +Z in direction ``rotation`` ("ccw" default, σ = +1; "cw",
σ = −1).  The cam-frame point of a fixed-frame point P at program angle θ is
R(−σθ)·P: the drawing shows the cam at cam angle 0.  Because the follower
visits the cam against its rotation, the pitch curve and profile of a "ccw"
cam run **clockwise** as θ increases (counter-clockwise for "cw").

Outward normal (away from the cam material): n = σ·J·T̂ for the roller pitch
curve (J turns +90°, T̂ the unit tangent); the face normal for a flat face.

Examples
--------
>>> from camcam.motion.catalog import make_law
>>> from camcam.motion.program import MotionProgram, Segment
>>> p = MotionProgram((Segment(make_law("cycloidal"), 0, 180, 10.0),
...                    Segment(make_law("cycloidal"), 180, 360, -10.0, base=10.0)), rpm=60)
>>> cam = DiscCam(TranslatingRoller(roller_radius=5.0), p, base_radius=30.0)
>>> [round(float(v), 9) for v in cam.profile.evaluate([0.0])[0]]
[0.0, 30.0]
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.followers import Element, FollowerKind, TranslatingRoller
from camcam.geometry.jet import Jet, hypot
from camcam.geometry.jetcurve import JetCurve, LiftJet, program_breaks, program_inner_breaks
from camcam.motion.program import MotionProgram

__all__ = ["DiscCam", "CamBasics", "Follower", "SIGMA"]

Follower = FollowerKind  # any kind of camcam.geometry.followers.FOLLOWERS

SIGMA = {"ccw": 1, "cw": -1}


class CamBasics:
    """What every cam says of its follower, rotation and program (needs ``follower``, ``rotation`` and
    ``program``)."""

    @property
    def breaks(self) -> np.ndarray:
        """The motion segments' boundaries (rad, 0 and 2π included): the cam's analytic pieces."""
        return program_breaks(self.program)

    @property
    def inner_breaks(self) -> tuple[np.ndarray, ...]:
        """Per piece (segment), the angles inside it where its law changes piece (:func:`program_inner_breaks`)."""
        return program_inner_breaks(self.program)

    @property
    def sigma(self) -> int:
        """+1 for a counter-clockwise cam, −1 for a clockwise one."""
        return SIGMA[self.rotation]

    @property
    def kind(self) -> str:
        """The follower kind."""
        return self.follower.kind

    @property
    def roller_radius(self) -> float:
        """The roller radius (0 for a flat face), mm."""
        return float(self.follower.roller_radius)


def rotate(x: Jet, y: Jet, angle: Jet) -> tuple[Jet, Jet]:
    """(x, y) turned by ``angle`` (a jet)."""
    c, s = angle.cos(), angle.sin()
    return c * x - s * y, s * x + c * y


@dataclass(frozen=True)
class DiscCam(CamBasics):
    """A disc cam driving ``follower`` through ``program``.

    Attributes
    ----------
    follower : Follower
    program : MotionProgram
        Lift in mm (translating) or degrees (oscillating).
    base_radius : float
        Base circle radius of the profile, mm.
    rotation : {"ccw", "cw"}
    pitch : JetCurve or None
        Roller-centre path in the cam frame (``None`` for flat faces).
    profile : JetCurve
        The surface the follower touches.
    """

    follower: Follower
    program: MotionProgram
    base_radius: float
    rotation: str = "ccw"
    lift: LiftJet = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        if self.rotation not in SIGMA:
            raise GeometryError(f'cam.rotation must be "ccw" or "cw", got {self.rotation!r}')
        if not self.base_radius > 0:
            raise GeometryError(f"cam.base_radius must be > 0 mm, got {self.base_radius:g}")
        if self.program.unit != self.follower.unit:
            raise GeometryError(f"a {self.follower.kind} follower needs a program in {self.follower.unit}, got {self.program.unit}")
        self.follower.check(self.base_radius)
        scale = math.pi / 180.0 if self.follower.unit == "deg" else 1.0
        object.__setattr__(self, "lift", LiftJet(self.program, scale))
        self.follower.check_cam(self)

    # -- basics (sigma, kind, roller_radius: CamBasics) ----------------------
    @property
    def is_roller(self) -> bool:
        return self.follower.is_roller

    def element(self, theta, K: int, piece: int | None = None) -> Element:
        """Fixed-frame jets (order K) of the follower element at program angles θ."""
        s = self.lift(theta, K + self.follower.lift_order_extra, piece)
        return self.follower.element(s, self.base_radius, self.sigma)

    def _to_cam(self, theta, x: Jet, y: Jet) -> tuple[Jet, Jet]:
        return rotate(x, y, Jet.variable(theta, x.K) * (-self.sigma))

    # -- curves -------------------------------------------------------------
    def _pitch_jets(self, theta, K, piece=None):
        e = self.element(theta, K, piece)
        return self._to_cam(theta, e.x, e.y)

    def _normal_jets(self, theta, K, piece=None):
        """Cam-frame unit normal away from the material, order K."""
        if self.is_roller:
            return self._roller_normal(*self._pitch_jets(theta, K + 1, piece))
        e = self.element(theta, K, piece)
        return self._to_cam(theta, e.nx, e.ny)

    def _roller_normal(self, x: Jet, y: Jet) -> tuple[Jet, Jet]:
        """The unit normal (order K − 1) of the pitch curve given as jets of order K."""
        tx, ty = x.derivative(), y.derivative()
        v = hypot(tx, ty)
        return (-ty) * self.sigma / v, tx * self.sigma / v

    def _offset_jets(self, theta, K, piece=None, *, distance):
        # The curve and its normal from one evaluation of the follower: every row of a jet is independent of
        # the order it is carried to, so the pitch curve of order K + 1 cut to K is the pitch curve of order K
        # (bit for bit), and the flat face's point and normal come from the same element.
        if self.is_roller:
            d = distance - self.roller_radius
            if d == 0.0:
                return self._pitch_jets(theta, K, piece)
            x, y = self._pitch_jets(theta, K + 1, piece)
            nx, ny = self._roller_normal(x, y)
            x, y = x.truncate(K), y.truncate(K)
        else:
            e = self.element(theta, K, piece)
            x, y = self._to_cam(theta, e.x, e.y)
            d = distance
            if d == 0.0:
                return x, y
            nx, ny = self._to_cam(theta, e.nx, e.ny)
        return x + nx * d, y + ny * d

    @property
    def pitch(self) -> JetCurve | None:
        if not self.is_roller:
            return None
        return JetCurve(self._pitch_jets, self.breaks)

    @property
    def profile(self) -> JetCurve:
        return self.offset_profile(0.0)

    def offset_profile(self, distance_mm: float) -> JetCurve:
        """The profile offset by ``distance_mm`` away from the cam material (+ = outside), exact.

        For a roller follower this is the pitch curve offset by ``distance_mm − roller_radius``.
        """
        # a partial of a bound method, not a lambda: the curve pickles with its cam (a MachiningResult
        # goes to the run's child processes pickled)
        return JetCurve(functools.partial(self._offset_jets, distance=float(distance_mm)), self.breaks)

    def normal(self, theta) -> np.ndarray:
        """Unit normal away from the material at program angles θ, shape (n, 2)."""
        nx, ny = self._normal_jets(np.atleast_1d(np.asarray(theta, float)), 0)
        return np.stack([nx.value, ny.value], axis=-1)

    # -- pressure angle -----------------------------------------------------
    def pressure_angle(self, theta, K: int = 0, piece: int | None = None) -> Jet:
        """Signed pressure angle (rad) and its derivatives: angle between the contact
        normal and the follower element's direction of motion, positive when the
        cam pushes the follower along increasing lift.  Zero for flat faces.
        """
        theta = np.atleast_1d(np.asarray(theta, dtype=float))
        if not self.is_roller:
            return Jet.constant(0.0, theta.size, K)
        e = self.element(theta, K + 1, piece)
        sg = self.sigma
        px, py = e.x.truncate(K), e.y.truncate(K)
        tx = e.x.derivative() + py * sg  # T = P′ − σJP, the fixed-frame tangent of the cam-frame curve
        ty = e.y.derivative() - px * sg
        ux, uy = e.ux.truncate(K), e.uy.truncate(K)
        a = tx * ux + ty * uy
        b = (tx * uy - ty * ux) * sg
        return Jet.atan2(a, b)

    def face_position(self, theta, K: int = 0, piece: int | None = None) -> Jet:
        """Flat faces: the contact's position along the face, mm (from the stem axis, or from the pivot)."""
        if self.is_roller:
            raise GeometryError("a roller follower has no face")
        return self.element(theta, K, piece).along
