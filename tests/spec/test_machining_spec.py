from pathlib import Path

import pytest

from camcam.errors import SpecError
from camcam.spec import parse_spec

MOTION = {"rpm": 60, "segments": [{"law": "cycloidal", "from": 0, "to": 180, "rise": 10.0},
                                  {"law": "cycloidal", "from": 180, "to": 360, "rise": -10.0}]}
MACH = {"post": "linuxcnc", "tool_diameter": 16.0, "tolerance": 0.01, "mode": "arcs", "feed": 400.0,
        "spindle": 3000, "depth": 12.0, "stepdown": 4.0}


def spec(**over):
    return parse_spec({"motion": MOTION, "machining": {**MACH, **over}}, Path("x.toml"))


def test_issue_table_reads():
    m = spec().machining
    assert m.post.name == "linuxcnc" and m.tolerance_mm == 0.01 and m.mode == "arcs"
    cs = m.cut_settings("left")
    assert cs.stepdown_mm == 4.0 and cs.plunge_feed_mm_min == 200.0 and cs.lead_radius_mm == 8.0


@pytest.mark.parametrize("over, message", [
    ({"post": "mach3"}, "machining.post: unknown post 'mach3'; known: fanuc"),
    ({"mode": "splines"}, 'machining.mode: expected one of "arcs", "lines"'),
    ({"tolerance": 0.001, "post": "fanuc"}, "machining.tolerance: 0.001 mm is too fine for post fanuc's 3 decimals"),
    ({"feed": -1}, "machining.feed: expected a number >= 1 and <= 100000 mm/min"),  # F must not print as F0
    ({"depht": 3}, "machining.depht: unknown key"),
])
def test_bad_values_name_the_key(over, message):
    with pytest.raises(SpecError) as err:
        spec(**over)
    assert str(err.value).startswith(message)


def test_user_post_relative_to_spec(tmp_path):
    from camcam.post.post import _post_dir

    (tmp_path / "mymill.toml").write_text((_post_dir() / "grbl.toml").read_text())
    s = parse_spec({"motion": MOTION, "machining": {**MACH, "post": "./mymill.toml"}}, tmp_path / "s.toml")
    assert s.machining.post.name == "mymill" and not s.machining.post.tool_change
