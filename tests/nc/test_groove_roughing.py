"""A face groove's rough rings hold the engagement limit by construction (issue 43 E), as the disc spiral does.

Campaign case 43:140 (``data/groove-rough-bend-43-140.toml``): a Ø16 tool in a 38.6 mm groove, stepover 0.4
(6.4 mm).  The rings used to be span/step apart alone: one ring 5.65 mm from the centre pass, which round the
pitch curve's 22.9 mm bend (the ring's 28.5 mm) met a band 6.687 mm wide, exit 3 with "lower [machining]
stepover (the roughing should have held it: please report this spec)".
"""

import math
from pathlib import Path

import numpy as np
import pytest

from camcam.geometry.build import build_cam
from camcam.geometry.curve import FunctionCurve
from camcam.verify import checked
from camcam.nc.roughing import RING_STEP_FRACTION, band_width, groove_rings
from camcam.report.setup_sheet import setup_blocks
from camcam.spec import load_spec

SPEC = Path(__file__).parent / "data" / "groove-rough-bend-43-140.toml"


def _built(spec):
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))


@pytest.fixture(scope="module")
def case():
    spec = load_spec(SPEC)
    return spec, checked(_built(spec), spec.machining, spec.name, spec.stock, workers=2)


def test_campaign_case_140_holds_the_stepover(case):
    spec, result = case
    r = result.removal
    assert r.stepover_mm == 6.4
    assert r.max_engagement_mm <= r.stepover_mm  # was 6.687 mm (groove rough outer 1)
    assert all(c.ok for c in result.checks)  # exit 0: every check of the verdict within its limit
    # the planned widest band, the rings 11.3/3 mm apart round the 22.9 mm bend: the sweep reads it within
    # 0.03 mm (its probes ±0.01 mm, each of the two rings fitted within the 0.027 mm tolerance, a ring's
    # error changing the band by at most that)
    assert r.max_engagement_mm == pytest.approx(4.63, abs=0.03)
    assert "groove rough outer" in r.engagement_where


def test_the_pass_table_and_comments_say_how_the_rings_are_planned(case):
    spec, result = case
    rough = [p for p in result.passes if p.kind == "rough"]
    labels = [result.contours[p.contour].label for p in rough]
    assert labels == ["groove rough inner 1", "groove rough inner 2", "groove rough outer 1", "groove rough outer 2"]
    assert [p.note for p in rough] == [f"ring {j} of 2, 3.77 mm apart, 1 more where the path is concave"
                                       for j in (1, 2, 1, 2)]
    assert f"rough, groove rough outer 1, Z{rough[2].z:g}, climb, {rough[2].note})" in result.program.text
    table = setup_blocks(_built(spec), result, spec.machining)[2]
    plan = table.header.index("plan")
    assert [row[plan] for row in table.rows if row[1] == "rough"] == [p.note for p in rough]


def _circle_ring(radius):
    """A ring curve: a clockwise circle, so the centre of curvature lies right of travel."""
    def f(t, k):
        c, s = np.cos(-t), np.sin(-t)
        return radius * np.stack([[c, s], [s, -c], [-c, -s], [-s, c]][k], axis=-1)
    return FunctionCurve(f, 0.0, 2 * math.pi, closed=True)


def test_rings_round_a_bend_away_from_the_material():
    # the rings of a groove round a circle of radius 22.9 mm, the material outside (left of clockwise travel):
    # the ring at o bends away from it with radius 22.9 + o, as the case's outer rings do
    span, r_t, step = 11.3, 8.0, RING_STEP_FRACTION * 6.4
    rings = groove_rings(lambda o: _circle_ring(22.9 + o), lambda c, t: np.ones(len(t)), span, r_t, step)
    assert rings.plain == 1 and len(rings.offsets) == 2  # the step alone: 1 ring; round the bend: 2
    assert rings.offsets == pytest.approx([span / 3, 2 * span / 3], abs=1e-12)
    # each band within the step, the first (the tightest bend) the widest: the closed form
    ae = span / 3
    assert rings.widest_mm == pytest.approx(band_width(ae, 1 / (22.9 + ae), r_t), rel=1e-6)  # sampled curvature
    assert rings.widest_mm <= step
    # one ring would meet 5.65 mm·(1 + 10.35/57) = 6.676 mm (the sweep read 6.687 on the case)
    assert band_width(span / 2, 1 / (22.9 + span / 2), r_t) > 6.4
    # bending toward the material (the inner side of that bend) needs nothing more than the step
    inner = groove_rings(lambda o: _circle_ring(22.9 + o), lambda c, t: -np.ones(len(t)), span, r_t, step)
    assert len(inner.offsets) == inner.plain == 1 and inner.widest_mm == pytest.approx(span / 2, abs=1e-12)
