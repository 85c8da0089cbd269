"""STL export of a cam mesh (binary STL, deterministic bytes), in the NC program's frame."""

from __future__ import annotations

import trimesh

__all__ = ["stl_bytes", "program_frame"]


def program_frame(built) -> trimesh.Trimesh:
    """The cam's mesh where the program cuts it: a disc cam's top face at Z0, the part below.

    The geometry stage builds disc and face-groove cams from z = 0 up to the
    thickness; the program has Z0 on the top face, so the STL is shifted down
    by the thickness (X and Y are the program's already: the cam axis at
    X0 Y0, drawn at cam angle 0).  A cylindrical cam's mesh is in the 4-axis
    frame already (cam axis along X from the left end face, Y = Z = 0 on it).
    """
    if built.spec.kind == "cylindrical":
        return built.mesh
    return built.mesh.copy().apply_translation((0.0, 0.0, -built.spec.thickness))


def stl_bytes(mesh: trimesh.Trimesh) -> bytes:
    """Binary STL of ``mesh`` (mm)."""
    return trimesh.exchange.stl.export_stl(mesh)
