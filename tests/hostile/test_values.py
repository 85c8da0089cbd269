"""Class 2: every number printed into a program is sane, or the spec is refused naming the key."""

from __future__ import annotations

import tomllib

import pytest
import tomli_w

from camcam.errors import InputError
from camcam.post.post import parse_post
from tests.hostile.harness import SAMPLES, assert_clean_error, run_inproc, snapshot

SAMPLE = "disc-translating-roller.toml"

# (table, key, value, the key the one-line message must start with)
CASES = [
    ("machining", "feed", 1e-6, "machining.feed"),          # printed F0
    ("machining", "feed", 1e7, "machining.feed"),
    ("machining", "plunge_feed", 1e-6, "machining.plunge_feed"),
    ("machining", "spindle", 0.4, "machining.spindle"),     # printed S0 M3
    ("machining", "spindle", 1e6, "machining.spindle"),
    ("machining", "depth", 1e4, "machining.depth"),         # printed G1 Z-10000 on a 12 mm cam
    ("machining", "depth", 14.5, "machining.depth"),        # beyond thickness + 2 mm break-through
    ("machining", "depth", 1e-9, "machining.depth"),
    ("machining", "stepdown", 1e-6, "machining.stepdown"),  # 12 million passes
    ("machining", "tool_number", 0, "machining.tool_number"),  # T0 M6
    ("machining", "tool_number", -3, "machining.tool_number"),
    ("machining", "tool_diameter", 1e-9, "machining.tool_diameter"),
    ("machining", "lead_radius", 1e-9, "machining.lead_radius"),
    ("machining", "clearance_z", 1e-9, "machining.clearance_z"),
    ("report", "inspection_step", 1e-6, "report.inspection_step"),
    ("cam", "thickness", 1e-9, "cam.thickness"),
    ("cam", "base_radius", 1e-6, "cam.base_radius"),
    ("cam", "bore", 1e-9, "cam.bore"),
    ("follower", "roller_radius", 1e-9, "follower.roller_radius"),
]


@pytest.mark.parametrize("table,key,value,named", CASES, ids=[f"{t}.{k}={v:g}" for t, k, v, _ in CASES])
def test_bad_numbers_are_refused_naming_the_key(tmp_path, table, key, value, named):
    doc = tomllib.loads((SAMPLES / SAMPLE).read_text())
    doc.setdefault(table, {})[key] = value
    spec = tmp_path / "s.toml"
    spec.write_text(tomli_w.dumps(doc))
    before = snapshot(tmp_path)
    code, _, err = run_inproc(["run", spec, "-o", tmp_path / "out"])
    line = assert_clean_error(code, err)
    assert line.startswith(f"camcam: error: {named}: "), line
    assert snapshot(tmp_path) == before


def _post(**over):
    data = tomllib.loads((SAMPLES.parent / "camcam" / "post" / "data" / "fanuc.toml").read_text())
    data.update(over)
    return data


POST_CASES = [
    ({"line_number_step": 0}, "line_number_step"),
    ({"line_number_step": -10}, "line_number_step"),
    ({"line_number_start": 9223372036854775807}, "line_number_start"),
    ({"max_line_number": 10**12}, "max_line_number"),
    ({"program_number": 0}, "program_number"),
    ({"program_number": -1}, "program_number"),
    ({"program_number": 10000}, "program_number"),  # O{program_number:04d}: 4 digits
    ({"units": "G20"}, "units"),                     # inches: camcam writes mm
    ({"units": "INCH"}, "units"),
    ({"units": "G71"}, "header"),                    # metric, but the header does not print it
    ({"extension": "n\nc"}, "extension"),
    ({"extension": "ñc"}, "extension"),
    # the machine-ready keys (issue 12): rates for the cycle time, and words printed as program lines
    ({"rapid_mm_min": 0}, "rapid_mm_min"),
    ({"rapid_mm_min": -5000.0}, "rapid_mm_min"),
    ({"rapid_mm_min": float("inf")}, "rapid_mm_min"),
    ({"rapid_mm_min": float("nan")}, "rapid_mm_min"),
    ({"rapid_mm_min": True}, "rapid_mm_min"),
    ({"rapid_mm_min": "fast"}, "rapid_mm_min"),
    ({"tool_change_s": -1}, "tool_change_s"),
    ({"tool_change_s": 1e9}, "tool_change_s"),
    ({"coolant_flood": "M8)"}, "coolant_flood"),     # a comment's end outside any comment
    ({"coolant_mist": "M7\nG0 Z-50"}, "coolant_mist"),
    ({"coolant_off": ""}, "coolant_off"),
    ({"coolant_flood": "", "coolant_mist": ""}, "coolant_flood"),
    ({"tool_length_offset": "G43 H{nope}"}, "tool_length_offset"),
    ({"tool_length_offset": "G20 G43 H{tool}"}, "tool_length_offset"),
    ({"work_offsets": ["G54"]}, "work_offsets"),     # six are needed
    ({"work_offsets": ["G54", "G55", "G56", "G57", "G58", ""]}, "work_offsets"),
    ({"work_offsets": ["G54", "G55", "G56", "G57", "G58", "G59 (x"]}, "work_offsets[5]"),
    ({"work_offsets": ["G54", "G55", "G56", "G57", "G58\nG20", "G59"]}, "work_offsets[4:1]"),
]


@pytest.mark.parametrize("over,key", POST_CASES, ids=[k for _, k in POST_CASES])
def test_post_numbers_and_units_are_checked(over, key):
    with pytest.raises(InputError) as e:
        parse_post(_post(**over), "fanuc-x")
    assert str(e.value).startswith(f"post fanuc-x: {key}: "), str(e.value)


def test_block_numbers_past_the_controllers_range_are_refused():
    from camcam.post.gcode import write_program
    from tests.hostile.test_text import _toolpath

    post = parse_post(_post(max_line_number=50), "fanuc-x")  # N10 … N50: five numbered lines
    with pytest.raises(InputError, match="max_line_number = 50"):
        write_program(_toolpath("t"), post, "cam")


@pytest.mark.parametrize("key,value", [("rapid_mm_min", -1.0), ("coolant_flood", "M8 )")])
def test_a_bad_machine_ready_post_key_ends_the_run_in_one_line(tmp_path, key, value):
    post = _post(**{key: value})
    (tmp_path / "mill.toml").write_text(tomli_w.dumps(post))
    doc = tomllib.loads((SAMPLES / SAMPLE).read_text())
    doc["machining"]["post"] = "mill.toml"
    spec = tmp_path / "s.toml"
    spec.write_text(tomli_w.dumps(doc))
    before = snapshot(tmp_path)
    code, _, err = run_inproc(["run", spec, "-o", tmp_path / "out"])
    line = assert_clean_error(code, err)  # exit 2, one line, no traceback
    assert f"post mill: {key}: " in line, line
    assert snapshot(tmp_path) == before  # no output written
