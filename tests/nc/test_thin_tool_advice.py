"""A barrel tool below a third of its groove: the advice names a tool that the later checks keep (campaign case
47:1, tests/nc/data/thin-barrel-tool-advice-47-1.toml)."""

import re
from pathlib import Path

import pytest

from camcam.errors import GeometryError
from camcam.geometry.build import build_cam
from camcam.nc.flank import flank_error_mm
from camcam.nc.rotary import _plan
from camcam.nc.tools import groove_passes
from camcam.spec import load_spec
from camcam.toolpath.budget import GrooveBudget

SPEC = Path(__file__).parent / "data" / "thin-barrel-tool-advice-47-1.toml"


def test_a_thin_barrel_tool_is_told_the_tool_whose_flanks_hold():
    spec = load_spec(SPEC)
    cam = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit)).cam
    m = spec.machining
    with pytest.raises(GeometryError) as err:
        _plan(cam, m.tool_diameter_mm / 2, cam.base_radius, m.tolerance_mm, GrooveBudget())
    advised = float(re.search(r"expected at least ([0-9.]+) mm", str(err.value)).group(1))
    assert str(err.value).startswith("machining.tool_diameter: 6 mm is below a third of the groove width 24 mm")
    assert advised == 19.09  # the 3-D check's "thinnest tool" at this tolerance, 0.01 mm up (was the third, 8)
    half = GrooveBudget().flank_tool_mm(m.tolerance_mm)
    # the rule the advice answers, judged by the flank error itself: the advised tool holds half the tolerance,
    # the third of the groove (the old advice) is far from it
    assert flank_error_mm(cam, advised / 2, cam.base_radius) <= half
    assert flank_error_mm(cam, 8.0 / 2, cam.base_radius) > 2 * half


def test_without_a_rule_of_its_own_the_advice_is_the_third():
    # a face groove (offset flank passes, no flank error): a third of the width, 0.01 mm up
    with pytest.raises(GeometryError, match=r"expected at least 8 mm \(up to the roller's 24 mm\)$"):
        groove_passes(3.0, 12.0)
    # a caller's thinnest tool below the third changes nothing
    with pytest.raises(GeometryError, match=r"expected at least 8 mm \(up to the roller's 24 mm\)$"):
        groove_passes(3.0, 12.0, lambda: 5.0)
