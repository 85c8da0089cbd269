"""Programs checked by LinuxCNC's own interpreter (rs274), both ways against the exact curve."""

import functools
import math

import numpy as np
import pytest

from camcam.post.gcode import write_program
from camcam.post.post import load_post
from camcam.toolpath.quantizer import Quantizer
from camcam.toolpath.arcfit import fit_contour
from camcam.toolpath.deviation import measure_deviation
from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.path import CutSettings, contour_toolpath, rotary_toolpath
from camcam.verify.rs274 import feed_passes, print_margin_mm, rs274_available, run_rs274
from tests.nc_curves import developed_groove, polar_cam, wavy

pytestmark = pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")

TOL = 0.01
CUT = CutSettings(depth_mm=8, stepdown_mm=4, feed_mm_min=400, spindle_rpm=3000, stock_side="left")


@functools.lru_cache(maxsize=None)
def cam_fit(decimals, max_sweep, mode="arcs"):
    curve = polar_cam()
    return curve, fit_contour(curve, TOL, mode=mode, quantizer=Quantizer(decimals), max_sweep_deg=max_sweep)


def interpreted_contour(path):
    passes = feed_passes(run_rs274(path))
    z, elements = passes[-1]
    return elements[1:-1], passes  # drop the lead-in and lead-out arcs


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas", "grbl"])
def test_program_through_rs274_within_tolerance(tmp_path, name):
    post = load_post(name)
    curve, fit = cam_fit(post.decimals, post.max_arc_sweep_deg)
    prog = write_program(contour_toolpath(fit.elements, CUT, "cam"), post, "cam")
    f = tmp_path / f"cam.{prog.extension}"
    f.write_text(prog.text)
    elements, passes = interpreted_contour(f)
    assert len(passes) == 2  # two depth passes of 4 mm
    assert len(elements) == len(fit.elements)
    # rs274 prints 4 decimals: exact for programs printed with ≤ 4 decimals
    dev = measure_deviation(curve, elements, margin_mm=0.02 * TOL)
    assert dev.max_deviation_mm <= TOL + print_margin_mm(post.decimals)
    for e in elements:
        if isinstance(e, Arc):
            # parsed start/end radii agree within GRBL's 0.005 mm check and our 0.002 mm bound
            assert abs(e.radius - e.end_radius) < 0.002


def test_lines_mode_through_rs274(tmp_path):
    post = load_post("linuxcnc")
    curve, fit = cam_fit(4, 120.0, "lines")
    prog = write_program(contour_toolpath(fit.elements, CUT, "cam"), post)
    f = tmp_path / "cam.ngc"
    f.write_text(prog.text)
    elements, _ = interpreted_contour(f)
    assert all(isinstance(e, Line) for e in elements)
    dev = measure_deviation(curve, elements, margin_mm=0.02 * TOL)
    assert dev.max_deviation_mm <= TOL


def test_open_curve_with_inflections(tmp_path):
    curve = wavy()
    fit = fit_contour(curve, TOL)
    f = tmp_path / "w.ngc"
    f.write_text(write_program(contour_toolpath(fit.elements, CUT, "wavy"), load_post("linuxcnc")).text)
    elements, _ = interpreted_contour(f)
    assert measure_deviation(curve, elements, margin_mm=0.02 * TOL).max_deviation_mm <= TOL


def test_four_axis_inverse_time(tmp_path):
    radius = 30.0
    curve = developed_groove(radius_mm=radius)
    fit = fit_contour(curve, TOL, mode="lines")
    pts = np.array([fit.elements[0].start] + [e.end for e in fit.elements])
    tp = rotary_toolpath(pts, radius, CutSettings(depth_mm=6, stepdown_mm=6, feed_mm_min=300, spindle_rpm=2000))
    prog = write_program(tp, load_post("linuxcnc"))
    assert "G93" in prog.text
    f = tmp_path / "groove.ngc"
    f.write_text(prog.text)
    moves = [m for m in run_rs274(f) if m.kind == "line" and m.z == radius - 6]
    developed = np.array([(m.x, math.radians(m.a) * radius) for m in moves])
    path = [Line(tuple(p), tuple(q)) for p, q in zip(developed[:-1], developed[1:])]
    # A is printed with 4 decimals of a degree: 0.5e-4° at R30 is 2.6e-5 mm, inside the rounding budget
    dev = measure_deviation(curve, path, margin_mm=0.02 * TOL)
    assert dev.max_deviation_mm <= TOL


def test_r_format_user_post(tmp_path):
    from camcam.post.gcode import printed_elements
    from camcam.post.post import _post_dir

    text = (_post_dir() / "linuxcnc.toml").read_text().replace('arc_format = "ij_incremental"', 'arc_format = "r"')
    (tmp_path / "rmill.toml").write_text(text)
    post = load_post(str(tmp_path / "rmill.toml"))
    curve, fit = cam_fit(post.decimals, post.max_arc_sweep_deg)
    printed = printed_elements(fit.elements, post)
    # the centres rebuilt from the rounded R still keep the program within tolerance
    assert measure_deviation(curve, printed, margin_mm=0.02 * TOL).max_deviation_mm <= TOL
    prog = write_program(contour_toolpath(fit.elements, CUT, "cam"), post)
    assert " R" in prog.text and " I" not in prog.text
    f = tmp_path / "r.ngc"
    f.write_text(prog.text)
    elements, _ = interpreted_contour(f)
    # rs274's centres agree with ours (4-decimal printing of a centre it computed: ≤ 0.71e-4 mm)
    for a, b in zip(elements, printed):
        if isinstance(b, Arc):
            assert math.dist(a.centre, b.centre) < 1e-4
    assert measure_deviation(curve, elements, margin_mm=0.02 * TOL).max_deviation_mm <= TOL + 3 * 0.71e-4
