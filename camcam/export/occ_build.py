"""What the OCP solid builders share: the surfaces' tolerance, B-spline knots as OCP arrays, a checked cut.

OCP (``pip install 'camcam[cad]'``) is imported by this module: import it only to write a STEP.
"""

from __future__ import annotations

import numpy as np
from OCP.BRepAlgoAPI import BRepAlgoAPI_Cut
from OCP.OCP.collections import Array1_double, Array1_int
from OCP.TopoDS import TopoDS_Shape

from camcam.errors import GeometryError

__all__ = ["SURFACE_TOLERANCE_MM", "FIT_TOLERANCE_MM", "PAST_MM", "knots_arrays", "cut"]

#: How far the STEP's profile, flank and groove-wall surfaces may be from the exact ones, mm.
SURFACE_TOLERANCE_MM = 1e-4
#: What the B-spline fits aim for: half of it, so that the deviation between the measured parameters stays under it.
FIT_TOLERANCE_MM = 0.5 * SURFACE_TOLERANCE_MM
#: How far a cutting tool reaches past the faces it cuts through, mm (no coincident faces for the booleans).
PAST_MM = 1.0


def knots_arrays(knots: np.ndarray) -> tuple[Array1_double, Array1_int]:
    """Distinct knots and their multiplicities (OCP arrays, from 1) of a knot vector with its repeats."""
    u, m = np.unique(knots, return_counts=True)
    k, mult = Array1_double(1, len(u)), Array1_int(1, len(u))
    for i, (a, b) in enumerate(zip(u, m)):
        k.SetValue(i + 1, float(a))
        mult.SetValue(i + 1, int(b))
    return k, mult


def cut(shape: TopoDS_Shape, tool: TopoDS_Shape) -> TopoDS_Shape:
    """``shape`` less ``tool`` (OpenCascade's boolean).

    Raises
    ------
    GeometryError
        The boolean failed.
    """
    op = BRepAlgoAPI_Cut(shape, tool)
    if not op.IsDone():
        raise GeometryError("OpenCascade could not cut the cam's solid")
    return op.Shape()
