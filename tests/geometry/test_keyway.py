"""Issue 47: a disc cam's [cam] keyway or dowel is its angular datum: drawn in the DXF (layers KEYWAY, DOWEL),
cut into the STL (still watertight), and named on the setup sheet relative to the cam-angle-0 line."""

import html
import math
import re
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import trimesh

from camcam.cli import main
from camcam.errors import SpecError
from camcam.geometry.build import build_cam
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]


def _spec(tmp_path: Path, keyway: str, sample: str = "disc-translating-roller") -> Path:
    text = (ROOT / "samples" / f"{sample}.toml").read_text()
    path = tmp_path / f"{sample}.toml"
    path.write_text(text.replace("[cam]\n", f"[cam]\nkeyway = {keyway}\n", 1))
    return path


def _keyway_area(bore_r, width, depth):
    """The keyway's area beyond the bore circle: the slot up to its bottom less the circle's segment in it."""
    h = width / 2
    segment = h * math.sqrt(bore_r ** 2 - h ** 2) + bore_r ** 2 * math.asin(h / bore_r)
    return width * (bore_r + depth) - segment


@pytest.mark.parametrize("sample", ["disc-translating-roller", "disc-groove"])
def test_keyway_is_cut_into_a_watertight_mesh(tmp_path, sample):
    plain = load_spec(ROOT / "samples" / f"{sample}.toml")
    spec = load_spec(_spec(tmp_path, "{ width = 4.0, depth = 1.8, angle = 30.0 }", sample))
    m0 = build_cam(plain.cam, plain.follower, plain.motion.program(plain.unit)).mesh
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    m = built.mesh
    assert m.is_watertight and m.is_winding_consistent and m.volume > 0
    # the material removed is the keyway's area times the thickness; the bore ring is a polygon of ~1000 points
    # whose chords lose 1e-4 of the small segment, so 0.5 % of the keyway's volume covers it
    removed = _keyway_area(spec.cam.bore / 2, 4.0, 1.8) * spec.cam.thickness
    assert m0.volume - m.volume == pytest.approx(removed, rel=5e-3)
    # the keyway's bottom lies on its centre line at 30°: vertices at bore radius + depth along that direction
    v = built.mesh_parts.vertices[:, :2]
    along = v @ np.array([math.cos(math.radians(30)), math.sin(math.radians(30))])
    assert along.max() > 0 and np.isclose(np.hypot(*v.T), math.hypot(2.0, spec.cam.bore / 2 + 1.8), atol=1e-9).sum() >= 4


def test_keyway_in_the_drawing_the_stl_and_the_setup_sheet(tmp_path):
    out = tmp_path / "out"
    assert main(["run", str(_spec(tmp_path, "{ width = 4.0, depth = 1.8 }")), "-o", str(out)]) == 0
    doc = ezdxf.readfile(out / "disc-translating-roller.dxf")  # strict reader
    assert not doc.audit().has_errors
    lines = [e for e in doc.modelspace() if e.dxf.layer == "KEYWAY" and e.dxftype() in ("LWPOLYLINE", "POLYLINE")]
    assert len(lines) == 1
    pts = np.array([p[:2] for p in lines[0].get_points()]) if lines[0].dxftype() == "LWPOLYLINE" else None
    # the four corners: walls from the Ø12 bore at x = ±2 up to the bottom at y = 6 + 1.8 (angle 90: +Y)
    expected = [(2.0, math.sqrt(32.0)), (2.0, 7.8), (-2.0, 7.8), (-2.0, math.sqrt(32.0))]
    assert pts is not None and np.allclose(pts, expected, atol=1e-9)  # written as doubles
    stl = trimesh.load(out / "disc-translating-roller.stl")
    assert stl.is_watertight
    page = html.unescape((out / "disc-translating-roller-report.html").read_text())
    assert re.search(r"Clamp the part by its keyway, 4 mm wide and 1\.8 mm deep in the Ø12 mm bore, its centre line "
                     r"at 90° from \+X, [\d.]+° counter-clockwise from the cam-angle-0 line \(DXF layer KEYWAY\)", page)


def test_keyway_needs_a_disc_with_a_bore(tmp_path):
    with pytest.raises(SpecError, match=r"cam\.keyway: needs a bore"):
        load_spec(_nobore(tmp_path))
    with pytest.raises(SpecError, match=r"cam\.keyway\.width: 14 mm must be narrower than the bore"):
        load_spec(_spec(tmp_path, "{ width = 14.0, depth = 1.8 }"))


def _nobore(tmp_path: Path) -> Path:
    path = _spec(tmp_path, "{ width = 4.0, depth = 1.8 }")
    path.write_text(path.read_text().replace("bore = 12.0\n", ""))
    return path


def test_dowel_hole_through_a_watertight_mesh_the_drawing_and_the_sheet(tmp_path):
    path = tmp_path / "dowel.toml"
    text = (ROOT / "samples" / "disc-translating-roller.toml").read_text()
    path.write_text(text.replace("[cam]\n", "[cam]\ndowel = { diameter = 6.0, radius = 22.0, angle = 60.0 }\n"
                                 "keyway = { width = 4.0, depth = 1.8 }\n", 1))
    spec = load_spec(path)
    m = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit)).mesh
    assert m.is_watertight and m.is_winding_consistent and m.euler_number == -2  # two holes: bore, dowel
    out = tmp_path / "out"
    assert main(["run", str(path), "-o", str(out)]) == 0
    doc = ezdxf.readfile(out / "disc-translating-roller.dxf")
    assert not doc.audit().has_errors
    (circle,) = [e for e in doc.modelspace() if e.dxf.layer == "DOWEL" and e.dxftype() == "CIRCLE"]
    # written as doubles: 22·(cos 60°, sin 60°) to 1e-9
    assert circle.dxf.radius == 3.0 and np.allclose(tuple(circle.dxf.center)[:2], (11.0, 22 * math.sqrt(3) / 2),
                                                     atol=1e-9)
    stl = trimesh.load(out / "disc-translating-roller.stl")
    assert stl.is_watertight and stl.euler_number == -2
    page = html.unescape((out / "disc-translating-roller-report.html").read_text())
    assert "Clamp the part by its keyway" in page
    assert re.search(r"Locate the part on its dowel hole, Ø6 mm through the cam, its centre at radius 22 mm, 60° "
                     r"from \+X, [\d.]+° counter-clockwise from the cam-angle-0 line \(DXF layer DOWEL\)", page)


def test_dowel_must_fit_between_the_bore_and_the_base_circle(tmp_path):
    path = tmp_path / "dowel.toml"
    text = (ROOT / "samples" / "disc-translating-roller.toml").read_text()
    path.write_text(text.replace("[cam]\n", "[cam]\ndowel = { diameter = 6.0, radius = 8.0 }\n", 1))
    with pytest.raises(SpecError, match=r"cam\.dowel\.radius: 8 mm puts the Ø6 mm hole into the bore"):
        load_spec(path)
