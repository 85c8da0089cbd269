"""A bore is judged against the material round it, and a bore that does not fit is told the largest that does
(campaign cases 50:38 and 52:46: face grooves whose bores fit inside the inner flank, refused by the spec reader
because it took the groove's axial depth from the radius, with "leaves no material around the bore" and no
value)."""

import math
import re
from pathlib import Path

import numpy as np
import pytest

from camcam.errors import CamcamError, GeometryError
from camcam.geometry.build import build_cam
from camcam.geometry.build import groove_outer_radius
from camcam.geometry.mesh import POINTS_PER_PIECE, disc_parts, groove_parts, ring_points
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
CASE = Path(__file__).parent / "data" / "groove-bore-axial-depth-52-46.toml"


def _with(tmp_path, source: Path, **cam):
    text = source.read_text()
    for key, value in cam.items():  # the [cam] table's line (it comes before [machining]'s of the same name)
        text, n = re.subn(rf"(?m)^{key} = .*$", f"{key} = {value}", text, count=1)
        assert n == 1, key
    path = tmp_path / "spec.toml"
    path.write_text(text)
    return load_spec(path)


def _build(spec):
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))


def _advised(err) -> float:
    return float(re.search(r"expected at most ([0-9.]+) mm", str(err.value)).group(1))


def test_a_face_grooves_bore_inside_its_inner_flank_is_cut():
    spec = load_spec(CASE)  # refused before: 21.6 / 2 ≥ 19.3 − 10.4
    built = _build(spec)
    _, inner = ring_points(built.cam.flanks[0], 64)
    # the inner flank is the base circle at zero lift (the base radius is the profile's): 19.3 mm, float sums
    assert np.hypot(*inner.T).min() == pytest.approx(19.3, abs=1e-9)
    assert spec.cam.bore / 2 < np.hypot(*inner.T).min()


def test_a_face_grooves_bore_past_the_base_circle_is_told_the_largest_that_fits(tmp_path):
    with pytest.raises(CamcamError, match=r"^cam\.bore: 40 mm leaves no material around the bore; expected at most "
                                          r"38\.59 mm \(under twice the base radius\)$"):
        _with(tmp_path, CASE, bore="40.0")
    _build(_with(tmp_path, CASE, bore="38.59"))  # followed: it fits (by 0.005 mm)


@pytest.mark.parametrize("sample", ["disc-translating-roller", "disc-groove"])
def test_the_meshs_own_bore_check_names_the_largest_that_fits(sample):
    """Behind the reader's check, the mesh measures the ring the bore must fit in (a profile or inner flank that
    dips under the base circle, as a negative lift would make it): its error names the largest bore that fits."""
    spec = load_spec(ROOT / "samples" / f"{sample}.toml")
    built = _build(spec)
    c = spec.cam
    ring = built.cam.flanks[0] if sample == "disc-groove" else built.cam.profile
    _, pts = ring_points(ring, POINTS_PER_PIECE)
    r_min = float(np.hypot(*pts.T).min())

    def parts(bore):
        if sample == "disc-groove":
            return groove_parts(built.cam, c.thickness, bore, groove_outer_radius(built.cam, c))
        return disc_parts(built.cam, c.thickness, bore)

    with pytest.raises(GeometryError) as err:
        parts(2 * r_min + 1.0)
    assert f", which comes within {r_min:.3f} mm of the axis; expected at most " in str(err.value)
    assert str(err.value).startswith("cam.bore: ")
    advised = _advised(err)
    assert 2 * r_min - 0.01 <= advised < 2 * r_min  # the 0.01 mm grid, strictly inside
    assert parts(advised).vertices.shape[1] == 3  # followed: it fits


def test_a_barrels_bore_stays_under_its_groove(tmp_path):
    sample = ROOT / "samples" / "cylindrical-translating.toml"
    spec = load_spec(sample)
    floor = spec.cam.base_radius - spec.cam.groove_depth  # the groove's bottom (radial depth)
    with pytest.raises(CamcamError, match=rf"^cam\.bore: {2 * floor:g} mm leaves no material under the groove, "
                                          rf"whose bottom is at radius {floor:g} mm; expected at most "
                                          rf"{math.floor(2 * floor * 100 - 1e-6) / 100:g} mm$"):
        _with(tmp_path, sample, bore=f"{2 * floor:g}")
