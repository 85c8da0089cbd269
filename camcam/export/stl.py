"""STL export of a cam mesh (binary STL, deterministic bytes)."""

from __future__ import annotations

import trimesh

__all__ = ["stl_bytes"]


def stl_bytes(mesh: trimesh.Trimesh) -> bytes:
    """Binary STL of ``mesh`` (mm)."""
    return trimesh.exchange.stl.export_stl(mesh)
