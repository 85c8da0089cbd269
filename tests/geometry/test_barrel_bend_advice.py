"""A barrel whose groove bends tighter than the roller is refused with advice that names a value, and following it
works (issue 43: "Advice is tested by following it"; the line said only "use a larger cam.base_radius").

The specs are the design-space campaign's (tests/designspace.py, seed 43): a translating barrel (case 21) and an
oscillating one (case 5), whose pivot must move out with the cylinder for the arm to stay in the groove."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from camcam.errors import GeometryError
from camcam.geometry.analysis import analyse_cylindrical
from camcam.geometry.build import build_cam
from camcam.spec.document import parse_spec

DATA = Path(__file__).with_name("data")


def _build(doc: dict):
    spec = parse_spec(doc, DATA / "barrel.toml")
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))


@pytest.mark.parametrize("case", ["barrel-bend-43-21.toml", "barrel-bend-43-5.toml"])
def test_the_advice_names_a_base_radius_that_avoids_the_bend(case):
    doc = tomllib.loads((DATA / case).read_text())
    with pytest.raises(GeometryError) as e:
        _build(doc)
    line = str(e.value)
    assert "bends with radius" in line and "\n" not in line
    radius = float(re.search(r"cam\.base_radius >= ([0-9.]+) mm", line).group(1))
    pivot = re.search(r"follower\.pivot_distance = ([0-9.]+) mm", line)
    assert (pivot is not None) == (doc["follower"]["kind"] == "oscillating-roller")
    doc["cam"]["base_radius"] = radius
    if pivot is not None:
        doc["follower"]["pivot_distance"] = float(pivot.group(1))
    built = _build(doc)  # followed: the cam builds
    a = analyse_cylindrical(built.cam)
    # the groove centre now bends no tighter than the roller: the flanks' convex radius is positive
    assert a.profile.min_radius_mm > 0
    # and the radius is the smallest that does, to the advice's 0.1 mm step
    doc["cam"]["base_radius"] = radius - 0.1
    if pivot is not None:
        doc["follower"]["pivot_distance"] = float(pivot.group(1)) - 0.1
    with pytest.raises(GeometryError, match="bends with radius"):
        _build(doc)
