"""The cams as OpenCascade solids (OCP), in the NC program's frame, for the STEP file.

* disc cam: the exact profile as B-spline curves (:func:`fit_curve`, one per analytic span,
  within :data:`~camcam.export.occ_build.SURFACE_TOLERANCE_MM` of the exact curve) extruded
  through the thickness (faces that are B-spline curves swept along Z), the top face at
  Z0 and the part below it, as the program cuts it; the bore, its keyway and the dowel hole
  cut through;
* face-groove cam: a disc of the outside radius with the groove between the two exact
  flanks (B-splines as above) cut ``groove_depth`` deep into the top face, and the bore;
* barrel cam: the cylinder (axis X, x ∈ [0, length]) with the bore, and the groove cut
  between the two exact roller envelope walls (bicubic B-spline surfaces of the cam angle
  and the roller cross-section's radius, :func:`camcam.geometry.bspline_fit.fit_surface`),
  down to the groove bottom's cylinder.

OCP (``pip install 'camcam[cad]'``) is imported by this module: import it only to write a
STEP (:mod:`camcam.export.step`).
"""

from __future__ import annotations

import math

import numpy as np
from OCP.BRepBuilderAPI import (BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace, BRepBuilderAPI_MakePolygon,
                                BRepBuilderAPI_MakeWire)
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepPrimAPI import BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakePrism
from OCP.Geom import Geom_BSplineCurve
from OCP.gp import gp_Ax2, gp_Dir, gp_Pnt, gp_Vec
from OCP.GeomAPI import GeomAPI_Interpolate
from OCP.OCP.collections import HArray1_double, HArray1_gp_Pnt
from OCP.ShapeFix import ShapeFix_Face
from OCP.TopoDS import TopoDS_Shape

from camcam.errors import GeometryError
from camcam.export.occ_build import FIT_TOLERANCE_MM, PAST_MM, cut
from camcam.geometry.bspline_fit import analytic_spans, check_params, end_parameters, refined
from camcam.geometry.mesh import keyway_corners

__all__ = ["cam_solid", "disc_solid", "groove_solid", "fit_curve"]


def _interpolate(curve, a: float, b: float, n: int, piece: int | None, z: float) -> Geom_BSplineCurve:
    """The clamped cubic B-spline through ``curve``'s points at n + 1 even parameters of [a, b] (its own
    parameters), with the exact end derivatives: motion segment ``piece``'s, a hair inside the span."""
    t = np.linspace(a, b, n + 1)
    at = (lambda u, k: curve.evaluate(u, k, piece)) if piece is not None else curve.evaluate
    p, d = at(t, 0), at(end_parameters(a, b), 1)
    pts, params = HArray1_gp_Pnt(1, n + 1), HArray1_double(1, n + 1)
    for i, (x, y) in enumerate(p):
        pts.SetValue(i + 1, gp_Pnt(float(x), float(y), z))
        params.SetValue(i + 1, float(t[i]))
    interp = GeomAPI_Interpolate(pts, params, False, 1e-9)
    interp.Load(gp_Vec(float(d[0, 0]), float(d[0, 1]), 0.0), gp_Vec(float(d[1, 0]), float(d[1, 1]), 0.0), False)
    interp.Perform()
    if not interp.IsDone():
        raise GeometryError("OpenCascade could not interpolate the cam's profile")
    return interp.Curve()


def fit_curve(curve, tolerance_mm: float, z: float = 0.0, program=None) -> tuple[list[Geom_BSplineCurve], float]:
    """Per-span cubic B-splines (OpenCascade's, in the plane at ``z``) of the closed exact planar ``curve``, each
    within ``tolerance_mm`` of it at every measured parameter (:func:`camcam.geometry.bspline_fit.refined`), and
    the largest deviation measured (mm).  With the cam's motion ``program`` the spans are its segments split at
    their laws' breaks, each evaluated on its segment (a JetCurve's one-sided values); without it, the curve's
    ``breaks``.  Neighbouring spans share their end point exactly."""
    spans = analytic_spans(curve.breaks, program)

    def make(piece, a, b, n):
        return _interpolate(curve, a, b, n, piece, z)

    def deviation(piece, c):
        u = check_params(np.array([c.Knot(k) for k in range(1, c.NbKnots() + 1)]))
        exact = curve.evaluate(u, 0, piece) if piece is not None else curve.evaluate(u, 0)
        got = np.array([[(p := c.Value(float(x))).X(), p.Y()] for x in u])
        return float(np.max(np.hypot(*(got - exact).T)))

    def join(c, nxt):
        c.SetPole(c.NbPoles(), nxt.Pole(1))

    return refined(spans, make, deviation, join, tolerance_mm, "curve")


def _wire(curve, z: float, program):
    w = BRepBuilderAPI_MakeWire()
    for piece in fit_curve(curve, FIT_TOLERANCE_MM, z, program)[0]:
        w.Add(BRepBuilderAPI_MakeEdge(piece).Edge())
    if not w.IsDone():
        raise GeometryError("the cam profile's B-spline pieces do not close a wire")
    return w.Wire()


def _prism(wire, z0: float, z1: float, hole=None) -> TopoDS_Shape:
    """The planar face inside ``wire`` (at z0; outside ``hole``, a wire inside it) swept to z1."""
    make = BRepBuilderAPI_MakeFace(wire, True)
    face = make.Face()
    if hole is not None:
        make.Add(hole)
        fix = ShapeFix_Face(make.Face())
        fix.FixOrientation()  # the hole's wire the other way round: the face is the ring between them
        face = fix.Face()
    return BRepPrimAPI_MakePrism(face, gp_Vec(0.0, 0.0, z1 - z0)).Shape()


def _curve_prism(curve, z0: float, z1: float, program) -> TopoDS_Shape:
    return _prism(_wire(curve, z0, program), z0, z1)


def _cylinder_z(centre: tuple[float, float], radius: float, z0: float, z1: float) -> TopoDS_Shape:
    return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(centre[0], centre[1], z0), gp_Dir(0, 0, 1)), radius, z1 - z0).Shape()


def _bore_cuts(shape: TopoDS_Shape, bore: float, keyway, z0: float, z1: float) -> TopoDS_Shape:
    """``shape`` with the bore of diameter ``bore`` and its keyway cut from z0 to z1."""
    if bore <= 0:
        return shape
    shape = cut(shape, _cylinder_z((0.0, 0.0), bore / 2, z0, z1))
    if keyway is None:
        return shape
    c = keyway_corners(bore / 2, keyway)
    a = math.radians(keyway.angle_deg)
    back = -keyway.width / 2 * np.array([-math.sin(a), math.cos(a)])  # the keyway's walls from the centre out
    outline = [back, c[1], c[2], -back]
    poly = BRepBuilderAPI_MakePolygon()
    for x, y in outline:
        poly.Add(gp_Pnt(float(x), float(y), z0))
    poly.Close()
    return cut(shape, _prism(poly.Wire(), z0, z1))


def disc_solid(cam, thickness: float, bore: float, keyway=None, dowel=None) -> TopoDS_Shape:
    """The disc cam's solid: the exact profile from z = −thickness to 0, the bore, keyway and dowel hole cut."""
    solid = _curve_prism(cam.profile, -thickness, 0.0, cam.program)
    lo, hi = -thickness - PAST_MM, PAST_MM
    solid = _bore_cuts(solid, bore, keyway, lo, hi)
    if dowel is not None:
        solid = cut(solid, _cylinder_z(dowel.centre, dowel.diameter / 2, lo, hi))
    return solid


def groove_solid(cam, thickness: float, bore: float, outer_radius: float, keyway=None) -> TopoDS_Shape:
    """The face-groove cam's solid: a disc of ``outer_radius`` from z = −thickness to 0, the groove between the
    flanks ``cam.groove_depth`` deep from the top face, the bore and keyway cut."""
    h = cam.groove_depth
    solid = _cylinder_z((0.0, 0.0), outer_radius, -thickness, 0.0)
    # the groove's tool is the ring between the flanks swept from its bottom to the top face exactly: where it
    # reached past the top face, the boolean would put intersection curves (approximations) in the top face
    outer, inner = (_wire(f, -h, cam.program) for f in (cam.flanks[1], cam.flanks[0]))
    solid = cut(solid, _prism(outer, -h, 0.0, hole=inner))
    return _bore_cuts(solid, bore, keyway, -thickness - PAST_MM, PAST_MM)


def cam_solid(built) -> TopoDS_Shape:
    """The solid of a :class:`~camcam.geometry.build.BuiltCam` in the program's frame.

    Raises
    ------
    GeometryError
        OpenCascade's solid is not valid (:class:`BRepCheck_Analyzer`).
    """
    from camcam.geometry.build import groove_outer_radius

    c = built.spec
    if c.kind == "disc":
        solid = disc_solid(built.cam, c.thickness, c.bore, c.keyway, c.dowel)
    elif c.kind == "disc-groove":
        solid = groove_solid(built.cam, c.thickness, c.bore, groove_outer_radius(built.cam, c), c.keyway)
    else:
        from camcam.export.barrel_solid import barrel_solid

        solid = barrel_solid(built.cam)
    if not BRepCheck_Analyzer(solid).IsValid():
        raise GeometryError(f"the {c.kind} cam's OpenCascade solid is not valid")
    return solid
