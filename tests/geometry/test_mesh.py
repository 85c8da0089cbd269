"""Disc meshes: watertight, and their volume equals shapely area × thickness minus the bore; camcam's own
closed-solid check, volume and STL writer (numpy) against trimesh's."""

import io
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
import shapely
import trimesh

from camcam.errors import GeometryError
from camcam.export.stl import stl_bytes
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import OscillatingRoller, TranslatingFlat, TranslatingRoller
from camcam.geometry.groove import GrooveCam
from camcam.geometry.mesh import MeshParts, disc_parts, groove_mesh, groove_parts

from tests.geometry.cam_programs import program


def _area(curve, n=4000):
    return shapely.Polygon(curve.polyline(n)).area  # dense independent view


@pytest.mark.parametrize(
    "cam",
    [
        DiscCam(TranslatingRoller(10.0, 5.0), program("mm"), 40.0),
        DiscCam(OscillatingRoller(10.0, 110.0, 85.0), program("deg", 15.0), 40.0),
        DiscCam(TranslatingFlat(0.0), program("mm"), 40.0),
    ],
    ids=lambda c: c.kind,
)
def test_disc_stl_watertight_volume(cam, tmp_path):
    path = tmp_path / "cam.stl"
    path.write_bytes(stl_bytes(disc_parts(cam, 12.0, 12.0).closed()))
    back = trimesh.load(path)
    assert back.is_watertight
    expect = (_area(cam.profile) - math.pi * 6.0**2) * 12.0
    assert back.volume == pytest.approx(expect, rel=1e-3)  # the 0.1 %


def test_groove_volume():
    g = GrooveCam(DiscCam(TranslatingRoller(10.0, 5.0), program("mm"), 40.0), 8.0)
    m = groove_mesh(g, 16.0, 12.0, 90.0)
    assert m.is_watertight
    blank = (math.pi * 90.0**2 - math.pi * 36.0) * 16.0
    groove = (_area(g.flanks[1]) - _area(g.flanks[0])) * 8.0
    assert m.volume == pytest.approx(blank - groove, rel=1e-3)  # 0.1 %, as for the disc


_CAMS = {"disc": lambda: disc_parts(DiscCam(OscillatingRoller(10.0, 110.0, 85.0), program("deg", 15.0), 40.0), 12.0, 12.0),
         "groove": lambda: groove_parts(GrooveCam(DiscCam(TranslatingRoller(10.0, 5.0), program("mm"), 40.0), 8.0),
                                        16.0, 0.0, 90.0)}


@pytest.mark.parametrize("kind", sorted(_CAMS))
def test_closed_mesh_is_trimeshs_solid(kind):
    """camcam's numpy check and STL writer against trimesh (the independent reader): the same winding, volume
    and bytes as trimesh's own solid and writer, for a mesh built wound inward (the disc) and outward."""
    parts = _CAMS[kind]()
    solid, mine = parts.solid(), parts.closed()
    assert np.array_equal(np.asarray(solid.faces), mine.faces)
    # the same sum over the same faces (trimesh's mass integral): equal to rounding, 1e-9 relative
    assert mine.volume_mm3() == pytest.approx(solid.volume, rel=1e-9)
    assert stl_bytes(mine) == trimesh.exchange.stl.export_stl(solid)
    back = trimesh.load(io.BytesIO(stl_bytes(mine)), file_type="stl")
    assert back.is_watertight and back.is_winding_consistent and len(back.faces) == len(parts.faces)
    # float32 corners in the file: 1e-6 relative of the volume
    assert back.volume == pytest.approx(mine.volume_mm3(), rel=1e-6)


def test_closed_mesh_refuses_an_open_or_miswound_mesh():
    parts = _CAMS["groove"]()
    open_mesh = MeshParts(parts.vertices, parts.faces[1:])
    miswound = MeshParts(parts.vertices, np.concatenate([parts.faces[:1, ::-1], parts.faces[1:]]))
    for bad in (open_mesh, miswound):
        with pytest.raises(GeometryError, match="not a closed solid"):
            bad.closed()
        with pytest.raises(GeometryError, match="not a closed solid"):
            bad.solid()  # trimesh agrees


def test_closed_mesh_merges_vertices_as_trimesh_does():
    """Every vertex stored twice and every other face using the copies: still one closed solid, as trimesh sees
    it (trimesh merges vertices that agree to 8 decimals)."""
    parts = _CAMS["groove"]()
    v = np.concatenate([parts.vertices, parts.vertices])
    f = parts.faces.copy()
    f[::2] += len(parts.vertices)  # every other face uses the copy
    split = MeshParts(v, f)
    assert split.closed().volume_mm3() == pytest.approx(parts.closed().volume_mm3(), rel=1e-9)  # rounding
    assert split.solid().is_watertight


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), inward=st.booleans(), shift=st.floats(-500.0, 500.0))
def test_closed_mesh_does_not_depend_on_vertex_order_winding_or_place(seed, inward, shift):
    """The same solid with its vertices relabelled at random, wound either way and moved anywhere: closed() winds
    it outward (the relabelled outward faces) and finds the same volume."""
    parts = _CAMS["groove"]().closed()
    rng = np.random.default_rng(seed)
    new = rng.permutation(len(parts.vertices))  # vertex i becomes new[i]
    v = np.empty_like(parts.vertices)
    v[new] = parts.vertices
    f = new[parts.faces]
    shaken = MeshParts(v + np.array([shift, -shift, 0.5 * shift]), f[:, ::-1] if inward else f).closed()
    assert np.array_equal(shaken.faces, f)
    # the same faces summed in the same order, their corners moved: rounding of ~1e-12 relative at 500 mm away
    assert shaken.volume_mm3() == pytest.approx(parts.volume_mm3(), rel=1e-9)
