"""Issue 47: the setup sheet's first picture shows the part on the machine (blank, datum, Z0) from the job's own
geometry: the lengths drawn, read back from the SVG at the scale its caption states, are the part's."""

import math
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from camcam.flow import load_job_spec, run_job
from camcam.report.setup_picture import setup_picture

ROOT = Path(__file__).resolve().parents[2]
NS = {"s": "http://www.w3.org/2000/svg"}
#: coordinates are printed with 2 decimals (±0.005 px): read back at ≥ 1 px/mm that is ±0.01 mm a length
PX_ROUNDING_MM = 0.02


def _picture(sample: str):
    spec = load_job_spec(ROOT / "samples" / f"{sample}.toml")
    job = run_job(spec)
    picture = setup_picture(job.cam, job.machining, spec.machining)
    svg = ET.fromstring(picture.svg)
    px_per_mm = float(svg.get("data-px-per-mm"))
    # the caption states it for the reader, to 3 digits
    stated = float(re.search(r"scale 1 : ([0-9.]+)", picture.caption).group(1))
    assert 96 / 25.4 / px_per_mm == pytest.approx(stated, rel=5e-3)  # 3 significant digits
    return job, spec, picture, svg, px_per_mm


def _points(el) -> np.ndarray:
    if el.tag.endswith("path"):
        return np.array([[float(v) for v in p.split(",")] for p in re.findall(r"-?[\d.]+,-?[\d.]+", el.get("d"))])
    return np.array([[float(v) for v in p.split(",")] for p in el.get("points").split()])


def _shapes(svg, kind: str) -> list[np.ndarray]:
    return [_points(el) for el in svg.iter() if el.get("class") == kind and el.tag.split("}")[1] != "text"]


def test_disc_picture_draws_the_part_blank_bore_and_zero_at_one_scale():
    job, spec, picture, svg, k = _picture("disc-translating-roller")
    assert picture.svg in job.files["disc-translating-roller-report.html"].decode()  # the sheet shows this picture
    built, r = job.cam, job.machining
    profile = built.cam.profile.polyline()
    top_part, side_part = _shapes(svg, "part")
    # the top view's part is the profile, at the scale stated: its width and height in mm
    for axis in (0, 1):
        drawn = np.ptp(top_part[:, axis]) / k
        assert drawn == pytest.approx(np.ptp(profile[:, axis]), abs=PX_ROUNDING_MM), axis
    # the blank (region of the stock) round the part, and the bore: a circle of the spec's diameter
    blank_top, blank_side = _shapes(svg, "blank")
    lo, hi = np.array(r.blank.region.bounds).reshape(2, 2)
    assert np.ptp(blank_top[:, 0]) / k == pytest.approx(hi[0] - lo[0], abs=PX_ROUNDING_MM)
    bore = [s for s in _shapes(svg, "cut") if len(s) == 360][0]
    assert np.ptp(bore[:, 0]) / k == pytest.approx(spec.cam.bore, abs=PX_ROUNDING_MM)
    # bore centred on X0 Y0: the origin arrows start at the bore's centre
    origin = _shapes(svg, "datum")[1][0]  # [0] is the cam-angle-0 line, then the X and Y arrows
    assert origin == pytest.approx(bore.mean(axis=0), abs=0.01)  # 360 evenly spaced points: the mean is the centre
    # side view: the part is the thickness tall and its top is the Z0 line; the blank reaches the blank's top
    assert np.ptp(side_part[:, 1]) / k == pytest.approx(spec.cam.thickness, abs=PX_ROUNDING_MM)
    z0 = [s for s in _shapes(svg, "zero")][0]
    assert z0[:, 1] == pytest.approx(side_part[:, 1].min(), abs=0.01)  # same rounding of the same y
    assert np.ptp(blank_side[:, 1]) / k == pytest.approx(spec.cam.thickness + r.blank.top_z_mm, abs=PX_ROUNDING_MM)
    # the tool's bottom at the deepest pass (Z of the pass in the program)
    tool = _shapes(svg, "tool")[0]
    deepest = min(p.z for p in r.toolpath.passes)
    assert (tool[:, 1].max() - z0[0, 1]) / k == pytest.approx(-deepest, abs=PX_ROUNDING_MM)
    assert np.ptp(tool[:, 0]) / k == pytest.approx(r.tool_diameter_mm, abs=PX_ROUNDING_MM)
    # the cam-angle-0 line points where the contact point at cam angle 0 is
    line = _shapes(svg, "datum")[0]
    p0 = built.cam.profile.evaluate(np.array([built.cam.profile.t_start]))[0]
    ang = math.degrees(math.atan2(-(line[1, 1] - line[0, 1]), line[1, 0] - line[0, 0]))  # SVG's y points down
    assert ang == pytest.approx(math.degrees(math.atan2(p0[1], p0[0])), abs=0.1)  # 0.01 px over ≥ 50 px


def test_barrel_picture_draws_the_cylinder_from_x0_and_a0_at_the_top():
    job, spec, picture, svg, k = _picture("cylindrical-translating")
    cam = job.cam.cam
    side, end = _shapes(svg, "part")
    assert np.ptp(side[:, 0]) / k == pytest.approx(cam.length, abs=PX_ROUNDING_MM)
    assert np.ptp(side[:, 1]) / k == pytest.approx(2 * cam.base_radius, abs=PX_ROUNDING_MM)
    chuck = _shapes(svg, "chuck")[0]
    assert chuck[:, 0].max() == pytest.approx(side[:, 0].min(), abs=0.01)  # the chuck holds the left end face, X0
    # the groove's flanks lie on the cylinder's silhouette, between its end faces
    for flank in _shapes(svg, "groove"):
        assert side[:, 0].min() - 0.01 <= flank[:, 0].min() and flank[:, 0].max() <= side[:, 0].max() + 0.01
    assert len(_shapes(svg, "groove")) >= 2
    # A0: from the end view's centre straight up to the cylinder (cam angle 0 at +Z)
    a0 = _shapes(svg, "datum")
    mark = [s for s in a0 if s[0, 0] == pytest.approx(s[1, 0]) and
            (s[0, 1] - s[1, 1]) / k == pytest.approx(cam.base_radius, abs=PX_ROUNDING_MM)]
    assert mark, "no A0 mark of the cylinder's radius"
    # the groove centre at cam angle 0 is at +Z in the program's frame (what the mark says)
    p = cam.centre(cam.base_radius).evaluate(np.array([0.0]))[0]
    assert p[2] == pytest.approx(cam.base_radius, abs=1e-9) and abs(p[1]) < 1e-9  # exact curve
