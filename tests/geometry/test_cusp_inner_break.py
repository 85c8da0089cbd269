"""A cusp where a law's acceleration jumps inside its segment is found, and the base radius its advice names builds.

Campaign case 45:59 (tests/geometry/data/cusp-mid-rise-45-59.toml, seed 45): the parabolic law's acceleration
jumps at mid-rise, and an oscillating flat face's radius of curvature with it.  The extremes were searched
among segment ends and roots of the derivative only, which a jump inside a segment is neither of: the cusp
check reported the cusp at 161.31° (-14.730 mm) and named 170.73 mm, where the profile still folded at 37.5°
(+354 mm before it, -1.08 mm after) and the mesh refused it."""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from camcam.errors import GeometryError
from camcam.geometry.analysis import flat_radius
from camcam.geometry.build import build_cam
from camcam.spec.document import parse_spec

CASE = Path(__file__).with_name("data") / "cusp-mid-rise-45-59.toml"


def _build(doc: dict):
    spec = parse_spec(doc, CASE)
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))


def test_the_cusp_at_a_jump_inside_a_law_is_found_and_its_advice_builds():
    doc = tomllib.loads(CASE.read_text())
    with pytest.raises(GeometryError) as e:
        _build(doc)
    line = str(e.value)
    # the worst of the jump's two sides: -15.681 mm just after 37.5° (the parabolic law's mid-rise, 18° + 39°/2)
    m = re.search(r"cusp at cam angle ([0-9.]+)°: .* radius of curvature there is (-?[0-9.]+) mm.*"
                  r"cam\.base_radius >= ([0-9.]+) mm avoids it", line)
    assert m is not None, line
    assert float(m.group(1)) == pytest.approx(37.5, abs=0.005)  # printed to 0.01°
    assert float(m.group(2)) == pytest.approx(-15.681, abs=5e-4)  # printed to 0.001 mm
    doc["cam"]["base_radius"] = float(m.group(3))
    built = _build(doc)  # no cusp left, and the mesh takes the profile (it refused it at 170.73 mm)
    assert built.mesh.is_watertight
    # independent of the extreme search: the signed radius on a 0.01° grid of every segment stays positive
    cam = built.cam
    for i, (a, b) in enumerate(zip(cam.breaks, cam.breaks[1:])):
        t = np.linspace(a, b, max(2, int(math.degrees(b - a) * 100)))
        assert float(flat_radius(cam, t, i)[0].min()) > 0.0
