"""The geometry stage's inputs: what cam and which follower to build (the ``[cam]`` and ``[follower]`` tables).

:mod:`camcam.spec.cam` and :mod:`camcam.spec.follower` read and validate them
from a spec file; :func:`camcam.geometry.build.build_cam` takes them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from camcam.geometry.followers import FOLLOWER_KINDS, follower_kind

__all__ = ["CamSpec", "Keyway", "Dowel", "FollowerSpec", "CAM_KINDS", "FOLLOWER_KINDS"]

CAM_KINDS = ("disc", "disc-groove", "cylindrical")


@dataclass(frozen=True, kw_only=True)
class Keyway:
    """A keyway in a disc cam's bore (mm, degrees): ``width`` across, ``depth`` from the bore's surface on its
    centre line, that centre line at ``angle_deg`` from +X in the drawing (cam angle 0)."""

    width: float
    depth: float
    angle_deg: float = 90.0


@dataclass(frozen=True, kw_only=True)
class Dowel:
    """A dowel hole through a disc cam (mm, degrees): ``diameter``, its centre at ``radius`` from the cam's centre
    on the line at ``angle_deg`` from +X in the drawing (cam angle 0)."""

    diameter: float
    radius: float
    angle_deg: float = 90.0

    @property
    def centre(self) -> tuple[float, float]:
        a = math.radians(self.angle_deg)
        return (self.radius * math.cos(a), self.radius * math.sin(a))


@dataclass(frozen=True, kw_only=True)
class CamSpec:
    """The cam to build (lengths in mm): ``kind`` one of :data:`CAM_KINDS`, rotation "ccw" or "cw"."""

    kind: str
    base_radius: float
    bore: float = 0.0
    rotation: str = "ccw"
    thickness: float | None = None
    groove_depth: float | None = None
    outer_radius: float | None = None
    length: float | None = None
    max_pressure_angle_deg: float | None = None  # design check limit; None: 30° translating, 35° oscillating
    min_curvature_radius_mm: float | None = None  # design check limit; None: half the roller radius (0 for a flat face)
    design_limits: str = "warn"  # "warn": a design limit missed is a warning (WARN); "fail": it fails the run (exit 3)
    material: str | None = None  # the part's material as the shop names it (the setup sheet states it)
    keyway: Keyway | None = None  # a keyway in the bore (disc kinds): the part's angular datum
    dowel: Dowel | None = None  # a dowel hole through a disc cam: the part's angular datum


@dataclass(frozen=True, kw_only=True)
class FollowerSpec:
    """The follower (lengths in mm): ``kind`` one of :data:`camcam.geometry.followers.FOLLOWERS`."""

    kind: str
    roller_radius: float = 0.0
    offset: float = 0.0
    pivot_distance: float | None = None
    arm_length: float | None = None

    @property
    def unit(self) -> str:
        """Motion unit: "deg" for an oscillating follower, else "mm" (the kind's ``unit``)."""
        return follower_kind(self.kind).unit

    @property
    def is_roller(self) -> bool:
        return follower_kind(self.kind).is_roller
