"""Reading a cam's STEP back with OpenCascade, for the tests: the solid, its faces by kind, points on them.

Only the tests import this (OCP is imported here).
"""

from __future__ import annotations

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepAdaptor import BRepAdaptor_Surface
from OCP.BRepCheck import BRepCheck_Analyzer
from OCP.BRepClass import BRepClass_FaceClassifier
from OCP.BRepGProp import BRepGProp
from OCP.BRepTools import BRepTools
from OCP.GeomAbs import GeomAbs_SurfaceType
from OCP.GProp import GProp_GProps
from OCP.gp import gp_Pnt2d
from OCP.TopAbs import TopAbs_ShapeEnum, TopAbs_State
from OCP.TopExp import TopExp_Explorer
from OCP.TopoDS import TopoDS


def sub_shapes(shape, kind: TopAbs_ShapeEnum) -> list:
    e, found = TopExp_Explorer(shape, kind), []
    while e.More():
        found.append(e.Current())
        e.Next()
    return found


def faces(shape, surface: GeomAbs_SurfaceType) -> list:
    """The faces of ``shape`` whose surface is of type ``surface``."""
    out = [TopoDS.Face(f) for f in sub_shapes(shape, TopAbs_ShapeEnum.TopAbs_FACE)]
    return [f for f in out if BRepAdaptor_Surface(f).GetType() == surface]


def is_closed_solid(shape) -> bool:
    """One valid solid (``BRepCheck_Analyzer``) whose every shell is closed."""
    solids = sub_shapes(shape, TopAbs_ShapeEnum.TopAbs_SOLID)
    shells = sub_shapes(shape, TopAbs_ShapeEnum.TopAbs_SHELL)
    return (len(solids) == 1 and BRepCheck_Analyzer(shape).IsValid() and len(shells) >= 1
            and all(BRep_Tool.IsClosed_s(s) for s in shells))


#: The relative accuracy :func:`volume_mm3` asks for (1e-7 takes 17 s on a barrel, 1e-6 3 s).
VOLUME_ACCURACY = 1e-6


def volume_mm3(shape) -> float:
    """OpenCascade's volume by its Gauss–Kronrod integration to :data:`VOLUME_ACCURACY` (its default
    integration was 1e-5 off on the oscillating barrel, its adaptive one 1.5e-4 off on the disc with a
    dowel hole)."""
    g = GProp_GProps()
    BRepGProp.VolumePropertiesGK_s(shape, g, VOLUME_ACCURACY)
    return g.Mass()


def area_mm2(shape) -> float:
    g = GProp_GProps()
    BRepGProp.SurfaceProperties_s(shape, g)
    return g.Mass()


def inside_uv(face, n: int) -> np.ndarray:
    """Up to n × n parameter pairs (u, v) on a grid over the face's bounds that lie inside the trimmed face."""
    u0, u1, v0, v1 = BRepTools.UVBounds_s(face)
    pts = []
    for u in np.linspace(u0, u1, n + 2)[1:-1]:
        for v in np.linspace(v0, v1, n + 2)[1:-1]:
            if BRepClass_FaceClassifier(face, gp_Pnt2d(u, v), 1e-7).State() == TopAbs_State.TopAbs_IN:
                pts.append((u, v))
    return np.array(pts)


def face_points(face, uv: np.ndarray) -> np.ndarray:
    """The face's surface points (k, 3) at the parameters ``uv``."""
    s = BRepAdaptor_Surface(face)
    return np.array([[s.Value(u, v).X(), s.Value(u, v).Y(), s.Value(u, v).Z()] for u, v in uv])
