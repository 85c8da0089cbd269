"""STL export of a cam mesh (binary STL, deterministic bytes), in the NC program's frame.

numpy only: a binary STL is an 80-byte header, a face count and one 50-byte record a face (normal,
three corners, float32, and a 2-byte attribute), the layout ``trimesh.exchange.stl`` writes; `camcam run`
makes it without importing trimesh (about 0.2 CPU s), which the tests use to read it back.
"""

from __future__ import annotations

import numpy as np

from camcam.geometry.mesh import MeshParts

__all__ = ["stl_bytes", "program_frame", "face_normals"]

#: One face of a binary STL.
STL_RECORD = np.dtype([("normals", "<f4", (3,)), ("vertices", "<f4", (3, 3)), ("attributes", "<u2")])
#: The header: 80 bytes (zeros) and the face count.
STL_HEADER = np.dtype([("header", np.void, 80), ("face_count", "<u4")])
#: Cross products shorter than this give a face a zero normal (a degenerate face; trimesh's ``TOL_ZERO``).
ZERO_CROSS = float(np.finfo(np.float64).resolution * 100)


def program_frame(built) -> MeshParts:
    """The cam's closed mesh (:meth:`~camcam.geometry.mesh.MeshParts.closed`) where the program cuts it: a
    disc cam's top face at Z0, the part below.

    The geometry stage builds disc and face-groove cams from z = 0 up to the
    thickness; the program has Z0 on the top face, so the STL is shifted down
    by the thickness (X and Y are the program's already: the cam axis at
    X0 Y0, drawn at cam angle 0).  A cylindrical cam's mesh is in the 4-axis
    frame already (cam axis along X from the left end face, Y = Z = 0 on it).
    """
    if built.spec.kind == "cylindrical":
        return built.closed_mesh
    return built.closed_mesh.moved((0.0, 0.0, -built.spec.thickness))


def face_normals(parts: MeshParts) -> np.ndarray:
    """(m, 3) unit normals of the faces (zero for a degenerate face)."""
    c = parts.crosses()
    norm = np.sqrt(np.dot(c * c, [1.0, 1.0, 1.0]))
    out = np.zeros_like(c)
    ok = norm > ZERO_CROSS
    out[ok] = c[ok] * (1.0 / norm[ok]).reshape(-1, 1)
    return out


def stl_bytes(parts: MeshParts) -> bytes:
    """Binary STL of ``parts`` (mm), faces as wound."""
    header = np.zeros(1, dtype=STL_HEADER)
    header["face_count"] = len(parts.faces)
    records = np.zeros(len(parts.faces), dtype=STL_RECORD)
    records["normals"] = face_normals(parts)
    records["vertices"] = parts.triangles
    return header.tobytes() + records.tobytes()
