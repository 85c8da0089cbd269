"""A barrel cam as an OpenCascade solid (OCP): the cylinder, its bore, and the groove between
the exact roller envelope walls.

Each groove wall is the exact surface S(θ, ρ) of
:meth:`~camcam.geometry.cylindrical.CylindricalCam.wall_grid` (the roller's contact line at
cam angle θ, on its cross-section of radius ρ), as bicubic B-spline surfaces, one per analytic
span (:func:`camcam.geometry.bspline_fit.analytic_spans`, :func:`~camcam.geometry.bspline_fit.fit_surface`, within
:data:`~camcam.export.occ_build.FIT_TOLERANCE_MM`), over radii reaching :data:`REACH_MM`
past the groove bottom and the cylinder's surface.  The two walls and two ruled caps
between them (below the bottom, above the surface) close a ring round the cam, the
groove's tool; the cylinder of the groove bottom's radius is taken from it, and what is
left is cut from the bored cylinder.  The groove's floor is that cylinder, as in the mesh
(:func:`camcam.geometry.mesh.cylinder_parts`) and the program.
"""

from __future__ import annotations

import numpy as np
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakeSolid, BRepBuilderAPI_Sewing
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder
from OCP.Geom import Geom_BSplineSurface
from OCP.GeomFill import GeomFill
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt
from OCP.OCP.collections import Array2_gp_Pnt
from OCP.ShapeFix import ShapeFix_Solid
from OCP.TopAbs import TopAbs_ShapeEnum
from OCP.TopoDS import TopoDS, TopoDS_Shape

from camcam.errors import GeometryError
from camcam.export.occ_build import FIT_TOLERANCE_MM, cut, knots_arrays
from camcam.geometry.bspline_fit import SurfacePiece, analytic_spans, fit_surface

__all__ = ["barrel_solid", "wall_fits", "REACH_MM", "RADIUS_NODES"]

#: How far the walls reach past the groove bottom and the cylinder's surface (mm): the booleans trim them there.
REACH_MM = 1.0
#: Interpolation nodes across each wall (roller cross-section radii).
RADIUS_NODES = 7
#: Sewing tolerance of the groove tool's faces (mm): neighbouring pieces share their edge curves to rounding.
_SEW_MM = 1e-6


def _radius_span(cam, rho: float) -> tuple[float, float]:
    """The smallest and largest distance from the axis of both walls' points on the cross-section ``rho``."""
    t = np.linspace(0.0, 2 * np.pi, 2 * 1440 + 1)
    p = np.concatenate([cam.wall_grid(t, [rho], side)[:, 0] for side in (0, 1)])
    r = np.hypot(p[:, 1], p[:, 2])
    return float(r.min()), float(r.max())


def wall_radii(cam) -> np.ndarray:
    """The cross-section radii the walls are interpolated at: from where every wall point is at least
    :data:`REACH_MM` below the groove bottom to where every one is that far above the surface.

    An oscillating arm tilts its roller: a cross-section ρ lies farther from the axis than ρ away from the
    arm's middle position, so the walls reach further down than the bottom's radius.
    """
    lo, hi = cam.bottom_radius - REACH_MM, cam.base_radius + REACH_MM
    for _ in range(60):
        top, bottom = _radius_span(cam, lo)[1], _radius_span(cam, hi)[0]
        if top <= cam.bottom_radius - REACH_MM and bottom >= cam.base_radius + REACH_MM:
            return np.linspace(lo, hi, RADIUS_NODES)
        lo -= max(0.0, top - (cam.bottom_radius - REACH_MM)) + 0.1 * REACH_MM
        hi += max(0.0, cam.base_radius + REACH_MM - bottom) + 0.1 * REACH_MM
    raise GeometryError("the barrel cam's groove walls do not reach past its bottom and surface")


def wall_fits(cam):
    """The two walls' :class:`~camcam.geometry.bspline_fit.SurfaceFit` (flank 0, flank 1)."""
    rho = wall_radii(cam)
    fits = []
    for side in (0, 1):
        def point(t, r, side=side):
            return cam.wall_grid(t, r, side)

        def tangent(t, r, piece, side=side):
            return cam.wall_grid(t, r, side, 1, piece)

        fits.append(fit_surface(point, tangent, analytic_spans(cam.breaks, cam.program), rho, FIT_TOLERANCE_MM))
    return tuple(fits)


def _surface(piece: SurfacePiece) -> Geom_BSplineSurface:
    mu, mv = piece.poles.shape[:2]
    arr = Array2_gp_Pnt(1, mu, 1, mv)
    for i in range(mu):
        for j in range(mv):
            x, y, z = piece.poles[i, j]
            arr.SetValue(i + 1, j + 1, gp_Pnt(float(x), float(y), float(z)))
    uk, um = knots_arrays(piece.knots_u)
    vk, vm = knots_arrays(piece.knots_v)
    return Geom_BSplineSurface(arr, uk, vk, um, vm, 3, 3)


def _groove_tool(cam) -> TopoDS_Shape:
    """The closed ring between the two walls and their caps (a solid)."""
    fits = wall_fits(cam)
    sew = BRepBuilderAPI_Sewing(_SEW_MM)
    for p0, p1 in zip(fits[0].pieces, fits[1].pieces):
        s0, s1 = _surface(p0), _surface(p1)
        for s in (s0, s1):
            sew.Add(BRepBuilderAPI_MakeFace(s, 1e-7).Face())
        lo, hi = p0.knots_v[0], p0.knots_v[-1]
        for v in (lo, hi):
            cap = GeomFill.Surface_s(s0.VIso(v), s1.VIso(v))
            sew.Add(BRepBuilderAPI_MakeFace(cap, 1e-7).Face())
    sew.Perform()
    shell = sew.SewedShape()
    if shell.ShapeType() != TopAbs_ShapeEnum.TopAbs_SHELL:
        raise GeometryError("the barrel cam's groove walls do not close a shell")
    fix = ShapeFix_Solid(BRepBuilderAPI_MakeSolid(TopoDS.Shell(shell)).Solid())
    fix.Perform()  # orients the shell outwards
    return fix.Solid()


def _cylinder_x(radius: float, x0: float, x1: float) -> TopoDS_Shape:
    return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x0, 0.0, 0.0), gp_Dir(1, 0, 0)), radius, x1 - x0).Shape()


def barrel_solid(cam) -> TopoDS_Shape:
    """The :class:`~camcam.geometry.cylindrical.CylindricalCam`'s solid: axis X, x ∈ [0, length], the bore and
    the groove cut."""
    L = cam.length
    body = _cylinder_x(cam.base_radius, 0.0, L)
    if cam.bore > 0:
        body = cut(body, _cylinder_x(cam.bore / 2, -REACH_MM, L + REACH_MM))
    groove = cut(_groove_tool(cam), _cylinder_x(cam.bottom_radius, -REACH_MM, L + REACH_MM))
    return cut(body, groove)
