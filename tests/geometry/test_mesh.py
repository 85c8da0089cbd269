"""Disc meshes: watertight, and their volume equals shapely area × thickness minus the bore."""

import math

import pytest
import shapely
import trimesh

from camcam.export.stl import stl_bytes
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import OscillatingRoller, TranslatingFlat, TranslatingRoller
from camcam.geometry.groove import GrooveCam
from camcam.geometry.mesh import disc_mesh, groove_mesh

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
    m = disc_mesh(cam, 12.0, 12.0)
    path = tmp_path / "cam.stl"
    path.write_bytes(stl_bytes(m))
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
