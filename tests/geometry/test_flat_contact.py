"""An oscillating flat face that loses contact is told what keeps it: the pivot distance its largest swing needs
(a > R_b / cos ψ_max), or, where the follower swings as fast as the cam turns, the motion segment (campaign case
52:39, tests/geometry/data/flat-face-fast-swing-52-39.toml, was told "use a larger pivot_distance or a slower
swing", and no pivot distance keeps that contact)."""

import math
import re
from pathlib import Path

import pytest

from camcam.errors import GeometryError
from camcam.geometry.build import build_cam
from camcam.spec import load_spec

SPEC = Path(__file__).parent / "data" / "flat-face-fast-swing-52-39.toml"


def _spec(tmp_path, segments: str, base_radius: float, pivot: float):
    text = re.sub(r"segments = \[.*?\n\]", f"segments = [\n{segments}\n]", SPEC.read_text(), flags=re.S)
    text = text.replace("base_radius = 35.7", f"base_radius = {base_radius:g}")
    path = tmp_path / "flat.toml"
    path.write_text(text.replace("pivot_distance = 69.9", f"pivot_distance = {pivot:g}"))
    return load_spec(path)


def _build(spec):
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))


def test_a_swing_as_fast_as_the_cam_names_its_segment():
    with pytest.raises(GeometryError) as err:
        _build(load_spec(SPEC))
    msg = str(err.value)
    assert msg.startswith("motion.segments[1]: the flat face loses contact at cam angle 48.30°")
    # the modified sine's peak dS/dT is 1.7596 (its exact extreme): 25° over 40° swings up to 1.1 × the cam
    assert "up to 1.1 times as fast in its modified-sine from 33° to 73°, rise -25°" in msg
    assert msg.endswith("expected a longer segment or a smaller rise (no pivot distance keeps the contact)")


SLOW = """  { law = "cycloidal", from = 0, to = 120, rise = 30.0 },
  { law = "dwell", from = 120, to = 180 },
  { law = "cycloidal", from = 180, to = 300, rise = -30.0 },
  { law = "dwell", from = 300, to = 360 },"""


def test_a_pivot_too_close_is_told_the_distance_that_keeps_the_contact(tmp_path):
    need = 35.0 / math.cos(math.radians(30.0))  # R_b / cos ψ_max = 40.4145 mm
    with pytest.raises(GeometryError) as err:
        _build(_spec(tmp_path, SLOW, 35.0, 40.0))
    assert str(err.value).startswith("follower.pivot_distance: at 40 mm the flat face loses contact at cam angle ")
    advised = float(re.search(r"expected at least ([0-9.]+) mm$", str(err.value)).group(1))
    assert advised == math.ceil(need * 100) / 100 == 40.42
    # followed, the contact holds (the build goes on to the cusp of this steep motion, a check of its own)
    with pytest.raises(GeometryError, match=r"^motion\.segments\[2\]: cusp at cam angle"):
        _build(_spec(tmp_path, SLOW, 35.0, advised))
    # and a hair under the bound it is still lost: the bound is the check's own (its 0.1° grid: 4e-6 mm)
    with pytest.raises(GeometryError, match=r"^follower\.pivot_distance: "):
        _build(_spec(tmp_path, SLOW, 35.0, 40.41))


def test_a_swing_of_90_degrees_or_more_names_the_motion(tmp_path):
    wide = """  { law = "harmonic", from = 0, to = 180, rise = 95.0 },
  { law = "harmonic", from = 180, to = 360, rise = -95.0 },"""
    with pytest.raises(GeometryError, match=r"^motion\.segments\[[01]\]: the flat face loses contact .*a swing of 95° "
                                            r"turns the face past the pivot at any pivot distance; expected a largest "
                                            r"swing under 90°$"):
        _build(_spec(tmp_path, wide, 35.0, 69.9))
