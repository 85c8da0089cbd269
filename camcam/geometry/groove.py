"""The face-groove (grooved disc) cam: a roller runs in a groove cut into a disc face.

The groove's centre line is the roller's pitch curve (the same as for an open
roller cam with the same base radius); its two flanks are the pitch curve
offset by ∓ the roller radius:

* flank 0, **inner** flank: pitch − r_r·n (n the pitch curve's outward normal);
  cam material on its inside (the island).  It is also ``profile``, so
  ``base_radius`` is the base circle of the inner flank as for an open cam.
* flank 1, **outer** flank: pitch + r_r·n; cam material on its outside.

Both flanks run the same way as the pitch curve (clockwise for a "ccw" cam).
``offset_flank(i, d)`` offsets flank i by d away from the material, into the
groove: the inner flank outward, the outer flank inward.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError
from camcam.geometry.disc import DiscCam
from camcam.geometry.jetcurve import JetCurve

__all__ = ["GrooveCam"]


@dataclass(frozen=True)
class GrooveCam:
    """A grooved disc cam around a roller follower ``cam`` (a roller :class:`DiscCam`).

    ``groove_depth`` (mm) is how deep the groove is cut into the top face.
    """

    cam: DiscCam
    groove_depth: float

    def __post_init__(self) -> None:
        if not self.cam.is_roller:
            raise GeometryError(f"a grooved cam needs a roller follower, not {self.cam.kind}")
        if not self.groove_depth > 0:
            raise GeometryError(f"cam.groove_depth must be > 0 mm, got {self.groove_depth:g}")

    # the shared attributes of every disc cam value object
    @property
    def kind(self) -> str:
        return self.cam.kind

    @property
    def program(self):
        return self.cam.program

    @property
    def base_radius(self) -> float:
        return self.cam.base_radius

    @property
    def roller_radius(self) -> float:
        return self.cam.roller_radius

    @property
    def rotation(self) -> str:
        return self.cam.rotation

    @property
    def sigma(self) -> int:
        return self.cam.sigma

    @property
    def breaks(self) -> np.ndarray:
        return self.cam.breaks

    @property
    def inner_breaks(self) -> tuple[np.ndarray, ...]:
        return self.cam.inner_breaks

    @property
    def pitch(self) -> JetCurve:
        return self.cam.pitch

    @property
    def flanks(self) -> tuple[JetCurve, JetCurve]:
        """(inner, outer) flank."""
        return self.offset_flank(0, 0.0), self.offset_flank(1, 0.0)

    def offset_flank(self, index: int, distance_mm: float) -> JetCurve:
        """Flank ``index`` (0 inner, 1 outer) offset by ``distance_mm`` away from the material."""
        if index == 0:
            return self.cam.offset_profile(distance_mm)
        if index == 1:
            return self.cam.offset_profile(2 * self.cam.roller_radius - distance_mm)
        raise ValueError(f"flank index must be 0 (inner) or 1 (outer), got {index!r}")

    @property
    def profile(self) -> JetCurve:
        """The inner flank (flank 0)."""
        return self.offset_flank(0, 0.0)

    def offset_profile(self, distance_mm: float) -> JetCurve:
        """Same as ``offset_flank(0, distance_mm)``."""
        return self.offset_flank(0, distance_mm)

    def pressure_angle(self, theta, K: int = 0, piece: int | None = None):
        return self.cam.pressure_angle(theta, K, piece)

    def normal(self, theta) -> np.ndarray:
        """Outward normal of the pitch curve (away from the island)."""
        return self.cam.normal(theta)
