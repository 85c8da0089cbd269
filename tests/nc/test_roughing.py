"""Every disc sample, interpreted by rs274 and checked 2.5-D against its blank: from the stated stock to the
design profile within tolerance, no plunge into material, no engagement over the stepover."""

from dataclasses import replace

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from camcam.errors import SpecError
from camcam.verify import checked
from camcam.nc.roughing import ROUGH_FIT_MM, polyline_elements
from camcam.spec.stock import StockSpec
from camcam.toolpath.elements import element_distance
from camcam.verify.removal import check_moves, design_keep
from camcam.verify.rs274 import print_margin_mm, rs274_available, run_rs274

from tests.nc.test_job import built_and_result

DISC_SAMPLES = ["disc-translating-roller", "disc-translating-flat", "disc-oscillating-flat", "disc-oscillating-roller",
                "disc-groove", "post-linuxcnc", "post-fanuc", "post-haas", "post-grbl"]
needs_rs274 = pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")


@needs_rs274
@pytest.mark.parametrize("sample", DISC_SAMPLES)
def test_sample_cuts_the_profile_from_the_stock(tmp_path, sample):
    spec, built, result = built_and_result(sample)
    f = tmp_path / result.program_filename
    f.write_text(result.program.text)
    events = run_rs274(f, comments=True)
    m, blank = spec.machining, result.blank
    if spec.stock.stated:  # the blank is the one the spec states
        assert blank.diameter_mm == spec.stock.diameter_mm and blank.allowance_mm == spec.stock.allowance_mm
    keep, boundary, _ = design_keep(blank, built, m.tolerance_mm)
    allowance = 0.0 if blank.groove else m.finish_allowance_mm
    r = check_moves(events, blank.region, blank.top_z_mm, keep, boundary, m.tool_diameter_mm / 2, m.stepover_mm,
                    m.ramp_angle_deg, m.tolerance_mm, allowance, m.post.decimals)
    margin = print_margin_mm(m.post.decimals)  # 0 for ≤ 4 decimals: rs274 prints the program's own numbers
    assert r.plunges == 0 and r.rapid_touches == 0
    assert r.max_engagement_mm <= m.stepover_mm
    assert r.material_left_mm <= m.tolerance_mm + margin
    assert r.overcut_mm <= m.tolerance_mm + margin
    if not blank.groove:
        assert r.rough_clearance_mm >= allowance  # the roughing stays the allowance off the part
        assert r.max_engagement_mm > 0.5 * m.stepover_mm  # the spiral really cuts the stock, at about the step
    else:
        assert r.max_slot_engagement_mm == pytest.approx(m.tool_diameter_mm, abs=0.02)  # the stated slot
    # the in-process reading of the printed program gives the same figures (same numbers, second reader)
    own = result.removal
    for a, b in [(r.max_engagement_mm, own.max_engagement_mm), (r.material_left_mm, own.material_left_mm),
                 (r.overcut_mm, own.overcut_mm)]:
        assert a == pytest.approx(b, abs=1e-9 + margin)
    assert all(c.ok for c in result.checks)


def test_default_blank_is_two_mm_over_the_cam():
    spec, built, result = built_and_result("post-linuxcnc")  # no [stock] table
    assert not spec.stock.stated
    # the largest radius from the roots of d|p|²/dθ: 59.928 mm at the end of the rise (120°)
    assert result.blank.cam_radius_mm == pytest.approx(59.928, abs=5e-4)
    assert result.blank.diameter_mm == pytest.approx(2 * (result.blank.cam_radius_mm + 2.0), abs=1e-12)
    assert "default" in result.blank.describe()


def _variant(sample, **machining):
    spec, built, _ = built_and_result(sample)
    return spec, built, replace(spec.machining, **machining)


def test_blank_smaller_than_the_cam_is_refused():
    spec, built, m = _variant("disc-translating-roller")
    with pytest.raises(SpecError, match=r"^stock.diameter: 110 mm is smaller than the cam: its largest radius is 59.928"):
        checked(built, m, "small",
                StockSpec(kind="round", diameter_mm=110.0, allowance_mm=None, top_allowance_mm=0.0, stated=True))


def test_bore_larger_than_base_minus_roller_is_refused():
    spec, built, m = _variant("disc-translating-roller")
    big = replace(built, spec=replace(built.spec, bore=62.0))  # radius 31 > 40 − 10
    with pytest.raises(SpecError, match=r"^cam.bore: Ø62 mm is larger than the base circle minus the roller"):
        checked(big, m, "bore", spec.stock)


def test_helical_bore_tool_must_fit():
    spec, built, m = _variant("disc-translating-roller", bore=True)
    with pytest.raises(SpecError, match=r"^machining.bore: the tool Ø16 mm does not fit the bore Ø12 mm"):
        checked(built, m, "bore", spec.stock)


def test_offset_blank_face_stock_and_helical_bore():
    """A pre-profiled blank with face stock and a Ø30 bore cut by the Ø16 tool: all checks hold, the bore too."""
    spec, built, m = _variant("disc-translating-roller", bore=True)
    bored = replace(built, spec=replace(built.spec, bore=30.0))
    r = checked(bored, m, "offset",
                StockSpec(kind="offset", diameter_mm=None, allowance_mm=6.0, top_allowance_mm=0.5, stated=True))
    rem = r.removal
    assert [p.kind for p in r.passes] == ["rough", "rough", "finish", "spring", "bore"]
    assert rem.plunges == 0 and rem.rapid_touches == 0
    assert rem.max_engagement_mm <= m.stepover_mm
    # the bore's circle is exact in the program (centre 0/0, ends rounded to 1e-4): within the tolerance both ways
    assert rem.material_left_mm <= m.tolerance_mm and rem.overcut_mm <= m.tolerance_mm
    assert rem.max_slot_engagement_mm > 0.9 * m.tool_diameter_mm  # the helix into solid: a stated slot
    assert r.program.text.count("pass ") == 5
    assert "G0 Z2.5" in r.program.text  # clearance above the face stock (top at Z0.5)
    assert all(c.ok for c in r.checks)


@settings(max_examples=25, deadline=None)
@given(st.floats(5.0, 200.0), st.floats(0.2, 3.0), st.floats(0.0, 0.3), st.integers(50, 400))
def test_polyline_fit_stays_within_tolerance(radius, sweep, wobble, n):
    """Lines and arcs through a wobbly arc stay within the fit tolerance of every point they replace."""
    a = np.linspace(0.0, sweep, n)
    r = radius * (1 + wobble * 0.05 * np.sin(7 * a))
    pts = np.column_stack([r * np.cos(a), r * np.sin(a)])
    els = polyline_elements(pts, ROUGH_FIT_MM, 120.0)
    assert els[0].start == tuple(pts[0]) and els[-1].end == tuple(pts[-1])
    d = np.min([element_distance(e, pts) for e in els], axis=0)
    assert d.max() <= ROUGH_FIT_MM + 1e-9  # the fit's own bound (float rounding only)


def test_narrow_groove_tool_roughs_between_centre_and_flanks():
    """A Ø8 tool in the 20 mm groove: centre slot, rough offsets at 2 and 4 mm, flanks at 6 mm from the centre."""
    spec, built, m = _variant("disc-groove", tool_diameter_mm=8.0)
    r = checked(built, m, "narrow", spec.stock)
    assert [c.label for c in r.contours] == ["groove centre (rough)", "groove rough inner 1", "groove rough inner 2",
                                             "groove rough outer 1", "groove rough outer 2", "inner flank",
                                             "outer flank"]
    rem = r.removal
    assert rem.plunges == 0 and rem.rapid_touches == 0
    # offsets 2 mm apart (≤ 0.9 × 3.2 mm): each meets a band of about 2 mm, more on the groove's curved walls
    assert 2.0 <= rem.max_engagement_mm <= m.stepover_mm
    # the last rough offset's tool edge is 10 − 4 − 4 = 2 mm from its flank (both within the 0.01 mm fit)
    assert rem.rough_clearance_mm == pytest.approx(2.0, abs=0.011)
    assert rem.material_left_mm <= m.tolerance_mm and rem.overcut_mm <= m.tolerance_mm
    assert all(c.ok for c in r.checks)


@settings(max_examples=60, deadline=None)
@given(centres=st.lists(st.tuples(st.floats(-20, 20), st.floats(-20, 20)), min_size=1, max_size=6),
       radius=st.floats(1.0, 15.0), hole=st.booleans(), multi=st.booleans(),
       probes=st.lists(st.tuples(st.floats(-60, 135), st.floats(-60, 60)), min_size=1, max_size=40))
# found by hypothesis in the suite (2026-12-07): the tree's nearest edge gave 37.4234375, GEOS 37.42343749999999
@example(centres=[(0.0, 0.0), (1e-15, 0.0)], radius=1.1, hole=False, multi=False,
         probes=[(1.306373291039457e-140, 38.5234375)])
def test_polygon_distance_is_shapelys(centres, radius, hole, multi, probes):
    """The R-tree distance is GEOS's polygon distance, inside (0), outside and in holes, of a polygon or of a
    multipolygon (the material check's part may be one), to within an ulp."""
    import shapely

    from camcam.nc.roughing import polygon_distance

    poly = shapely.union_all([shapely.Point(c).buffer(radius, quad_segs=16) for c in centres])
    if poly.geom_type != "Polygon" and not multi:
        poly = max(poly.geoms, key=lambda g: g.area)
    if hole and poly.geom_type == "Polygon":
        inner = poly.buffer(-0.3 * radius)
        if inner.geom_type == "Polygon" and not inner.is_empty:
            poly = shapely.Polygon(poly.exterior, [inner.exterior])
    if multi and poly.geom_type == "Polygon":  # two parts: the polygon and a copy 75 mm along x
        poly = shapely.MultiPolygon([poly, shapely.affinity.translate(poly, 75.0, 0.0)])
    xy = np.array(probes, float)
    with np.errstate(divide="ignore", invalid="ignore"):  # GEOS's own call warns on degenerate slivers; its values stand
        want = shapely.distance(poly, shapely.points(xy))
    # rtol 2.3e-16 (one ulp, 2^-52): edges meeting at the nearest vertex each give its distance to within one, and
    # the tree may return one above GEOS's least (the example above); anything else is the same number
    np.testing.assert_allclose(polygon_distance(poly, xy), want, rtol=2.3e-16, atol=0.0)


def test_the_stock_size_advised_is_taken():
    """Campaign case 45:2 (tests/nc/data/stock-advice-45-2.toml): a round stock smaller than the cam is refused
    with the smallest diameter that holds it, rounded up to the 0.001 mm it prints, so that a stock of exactly
    that size is taken.  It read "expected at least 337.880 mm" for a radius of 168.94002 mm, and 337.88 was
    refused in turn."""
    import re
    from pathlib import Path

    from camcam.flow import load_job_spec
    from camcam.geometry.build import build_cam
    from camcam.nc.stock import blank_for

    spec = load_job_spec(Path(__file__).resolve().parent / "data" / "stock-advice-45-2.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    with pytest.raises(SpecError) as info:
        blank_for(built, spec.stock, spec.machining.tool_diameter_mm)
    least = float(re.search(r"expected at least ([0-9.]+) mm$", str(info.value)).group(1))
    assert least == 337.881
    blank = blank_for(built, replace(spec.stock, diameter_mm=least), spec.machining.tool_diameter_mm)
    assert blank.diameter_mm / 2 >= blank.cam_radius_mm
