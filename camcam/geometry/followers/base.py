"""What every follower kind declares, and the pieces the kinds share.

A follower kind is one class (one module of :mod:`camcam.geometry.followers`,
listed in its registry :data:`~camcam.geometry.followers.FOLLOWERS`).  An
instance is the follower in the disc frame; the class declares what the other
stages ask of the kind, so that none of them compares kind strings:

* the spec: ``kind``, ``spec_keys`` (the ``[follower]`` keys it takes, read by
  :mod:`camcam.spec.follower`), ``barrel_optional_keys``;
* the motion: ``unit`` of its lift ("mm" or "deg"), ``is_roller``,
  ``lift_order_extra`` (derivatives of the lift its contact needs);
* the design checks: ``default_max_pressure_angle_deg``;
* the disc frame: :meth:`~FollowerKind.from_spec`, :meth:`~FollowerKind.check`,
  :meth:`~FollowerKind.check_cam`, ``element`` (the jets of its cam-touching
  element, module notes below);
* the barrel frame: ``barrel``, its follower class for a cylindrical cam (None:
  it runs on disc cams only), made by :meth:`~FollowerKind.barrel_from_spec`;
  ``barrel_axes`` the machining axes its groove can be cut with (the first is
  the default);
* sizing (``camcam size``): ``size_axes`` (None: not sized), the closed-form
  kernel :meth:`~FollowerKind.size_figures` and the design
  :meth:`~FollowerKind.from_params`;
* reverse design: :meth:`~FollowerKind.invert` (profile points → cam angle and
  lift) and, on the barrel class, ``pivot_distance`` (None: translating);
* the setup sheet: :meth:`~FollowerKind.datum_note`.

Fixed frame (DESIGN.md): cam centre at the origin, drawing in the XY plane seen
from +Z.  A translating follower moves along +Y, its axis offset ``offset`` mm
along +X.  An oscillating follower pivots at (``pivot_distance``, 0) on the +X
axis; a lift turns it clockwise about the pivot, away from the cam.  At lift 0
the roller centre sits on the base pitch circle (radius R_b + r_r) above the
X axis, or the flat face is tangent to the base circle above the X axis.

Each follower turns the lift jet ``s`` (mm, or radians for an oscillating
follower) into the jets of its cam-touching element in the fixed frame for a
cam turning in direction σ (+1 counter-clockwise, −1 clockwise):

* roller followers: the roller centre ``P`` and the unit direction ``u`` in
  which it moves for increasing lift (for the pressure angle);
* flat-faced followers: the contact point ``Q`` on the face, the face's unit
  normal pointing away from the cam, and the contact's position along the face
  (from the stem axis or from the pivot), which sizes the face.

The flat-face contact follows from the envelope condition: the cam-frame
profile tangent Q′ − σJQ (J = +90° turn) is parallel to the face.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import KW_ONLY, dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.jet import Jet

if TYPE_CHECKING:
    from camcam.geometry.params import FollowerSpec

__all__ = ["Element", "FollowerKind", "reject"]


@dataclass(frozen=True)
class Element:
    """Fixed-frame jets of a follower's cam-touching element."""

    x: Jet
    y: Jet
    ux: Jet | None = None  # roller: direction of motion for increasing lift
    uy: Jet | None = None
    _: KW_ONLY
    nx: Jet | None = None  # flat face: unit normal away from the cam
    ny: Jet | None = None
    along: Jet | None = None  # flat face: contact position along the face, mm


class FollowerKind(ABC):
    """The declarations every follower kind makes (module notes); subclasses are frozen dataclasses.

    A kind must give :meth:`from_spec`, :meth:`element`, :meth:`invert` and :meth:`datum_note` (abstract: a
    class without one cannot be made); sizing (:meth:`size_figures`, :meth:`from_params`) and the barrel
    frame (:meth:`barrel_from_spec`) are optional and refuse with one line where a kind has none."""

    kind: ClassVar[str]
    unit: ClassVar[str]
    is_roller: ClassVar[bool]
    lift_order_extra: ClassVar[int]
    #: The ``[follower]`` keys the kind takes, of roller_radius, offset, pivot_distance, arm_length.
    spec_keys: ClassVar[tuple[str, ...]]
    #: Keys a cylindrical cam's follower of this kind may leave out.
    barrel_optional_keys: ClassVar[tuple[str, ...]] = ()
    default_max_pressure_angle_deg: ClassVar[float]
    #: The follower class in the barrel frame (:mod:`camcam.geometry.cylindrical`); None: disc cams only.
    barrel: ClassVar[type | None] = None
    #: ``[machining] axes`` a barrel cam's groove may be cut with, the default first.
    barrel_axes: ClassVar[tuple[int, ...]] = (4,)
    #: The swept axes of ``camcam size`` in table order (base_radius first); None: not sized.
    size_axes: ClassVar[tuple[str, ...] | None] = None

    @classmethod
    @abstractmethod
    def from_spec(cls, f: "FollowerSpec") -> "FollowerKind":
        """The disc follower of a validated ``[follower]`` table."""

    @abstractmethod
    def element(self, s: Jet, base_radius: float, sigma: int) -> Element:
        """The fixed-frame jets of the cam-touching element for the lift jet ``s`` (module notes)."""

    @classmethod
    def barrel_from_spec(cls, f: "FollowerSpec"):
        """The barrel follower of a validated ``[follower]`` table."""
        raise GeometryError(f"a {cls.kind} follower runs on disc cams only")

    @classmethod
    def from_params(cls, params: dict[str, float]) -> "FollowerKind":
        """The disc follower of one sized design (``params``: the :attr:`size_axes` values)."""
        raise ValueError(f"no sizing for a {cls.kind} follower")

    @staticmethod
    def size_figures(ps, sigma: int, params: dict, contact=None) -> dict:
        """Closed-form figures of a block of designs (:mod:`camcam.sizing.kernels`; ``contact``: the sweep's
        dynamics, :class:`camcam.sizing.contact.SweepDynamics`, adds ``max_contact_stress_mpa``); a kind without
        :attr:`size_axes` is never sized, and refuses."""
        raise ValueError("no closed-form sizing kernel for this follower kind")

    def check(self, base_radius: float) -> None:
        """Raise :class:`GeometryError` when the follower cannot touch a base circle of ``base_radius``."""

    def check_cam(self, cam) -> None:
        """Raise :class:`GeometryError` when the follower loses the built disc ``cam`` (default: never)."""

    @abstractmethod
    def invert(self, P: np.ndarray, n: np.ndarray, base_radius: float, sg: int) -> tuple[np.ndarray, np.ndarray]:
        """Cam angle θ (rad, not reduced) and lift (mm or rad) of cam-frame profile points ``P`` with outward normals ``n``."""

    @classmethod
    @abstractmethod
    def datum_note(cls, offset: float) -> str:
        """Where the follower sits at cam angle 0, for the setup sheet (``offset``: the stem's, mm)."""


def reject(mask, points, what: str) -> None:
    """Raise :class:`GeometryError` naming the first of ``points`` (n, 2) where ``mask`` holds."""
    if np.any(mask):
        i = int(np.flatnonzero(mask)[0])
        raise GeometryError(f"point ({points[i, 0]:.4f}, {points[i, 1]:.4f}) does not fit the follower: {what}")
