"""From the validated ``[cam]`` and ``[follower]`` tables to a cam, its analysis and its mesh."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from camcam.geometry.analysis import DiscAnalysis, analyse, analyse_cylindrical, check_undercut
from camcam.geometry.cylindrical import CylindricalCam
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import follower_kind
from camcam.geometry.groove import GrooveCam
from camcam.geometry.mesh import MeshParts, cylinder_parts, disc_parts, groove_parts, ring_points
from camcam.motion.program import MotionProgram
from camcam.geometry.params import CamSpec, FollowerSpec

if TYPE_CHECKING:
    import trimesh

__all__ = ["BuiltCam", "build_cam", "disc_follower", "groove_outer_radius"]


@dataclass(frozen=True)
class BuiltCam:
    """The cam value object, its analysis and its watertight mesh.

    ``mesh_parts`` are the triangles (numpy); ``closed_mesh`` the same checked to close a solid and wound
    outward (numpy), and ``mesh`` the watertight trimesh made from them, each the first time it is asked for
    (:class:`GeometryError` if the triangles close no solid; trimesh is imported for ``mesh`` only, which
    `camcam run` does not use: the tests' independent view of the STL).
    """

    cam: DiscCam | GrooveCam | CylindricalCam
    analysis: DiscAnalysis
    mesh_parts: MeshParts
    spec: CamSpec

    @cached_property
    def mesh(self) -> "trimesh.Trimesh":
        return self.mesh_parts.solid()

    @cached_property
    def closed_mesh(self) -> MeshParts:
        """``mesh_parts`` checked to close a solid and wound outward (numpy only: the STL and the report's
        mesh figures, :meth:`~camcam.geometry.mesh.MeshParts.closed`)."""
        return self.mesh_parts.closed()


def disc_follower(f: FollowerSpec):
    """The geometry stage's disc follower for a validated ``[follower]`` table."""
    return follower_kind(f.kind).from_spec(f)


def build_cam(c: CamSpec, f: FollowerSpec, program: MotionProgram) -> BuiltCam:
    """Build, check, analyse and mesh the cam.

    Parameters
    ----------
    c, f : CamSpec, FollowerSpec
        The cam and the follower (lengths in mm).
    program : MotionProgram
        The follower's motion over one revolution.

    Returns
    -------
    BuiltCam
        The cam (exact curves), its analysis and its watertight mesh.

    Raises
    ------
    GeometryError
        An undercut or cusp (with the angle and the smallest base radius that avoids it), a
        follower that cannot reach, a groove that does not fit.

    Examples
    --------
    >>> from camcam.spec import load_spec
    >>> spec = load_spec("samples/disc-translating-roller.toml")
    >>> built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    >>> round(built.analysis.max_pressure_angle_deg.value, 3), built.mesh.is_watertight
    (22.256, True)
    """
    if c.kind == "cylindrical":
        fol = follower_kind(f.kind).barrel_from_spec(f)
        cam = CylindricalCam(fol, program, c.base_radius, length=c.length, groove_depth=c.groove_depth,
                             rotation=c.rotation, bore=c.bore)
        return BuiltCam(cam, analyse_cylindrical(cam), cylinder_parts(cam), c)
    disc = DiscCam(disc_follower(f), program, c.base_radius, c.rotation)
    if c.kind == "disc":
        check_undercut(disc)
        return BuiltCam(disc, analyse(disc), disc_parts(disc, c.thickness, c.bore, keyway=c.keyway, dowel=c.dowel), c)
    cam = GrooveCam(disc, c.groove_depth)
    check_undercut(cam)
    return BuiltCam(cam, analyse(cam), groove_parts(cam, c.thickness, c.bore, groove_outer_radius(cam, c),
                                                     keyway=c.keyway), c)


def groove_outer_radius(cam: GrooveCam, c: CamSpec) -> float:
    """A face-groove cam's outside radius: ``cam.outer_radius``, or the outer flank's reach plus a roller radius of wall."""
    if c.outer_radius is not None:
        return c.outer_radius
    _, pts = ring_points(cam.flanks[1])
    return float(np.ceil(np.hypot(pts[:, 0], pts[:, 1]).max() + cam.roller_radius))
