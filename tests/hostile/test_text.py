"""Class 1: nothing a user or a post file writes can become a program word."""

from __future__ import annotations

import tomllib

import pytest
import tomli_w
from hypothesis import given, settings
from hypothesis import strategies as st

from camcam.errors import InputError
from camcam.nc.settings import ProgramSetup
from camcam.post.gcode import write_program
from camcam.post.post import known_posts, load_post, parse_post
from camcam.post.template import parse_template
from camcam.post.text import encode_comment
from camcam.toolpath.path import ArcMove, Feed, Rapid, Toolpath
from tests.hostile.harness import SAMPLES, assert_clean_error, assert_program_safe, run_inproc, snapshot

HOSTILE_TEXT = [
    "x\nG0 Z-50", "x\rG0 Z-50", "x\r\nG0 Z-50", "x\x85G0 Z-50", "x\u2028G0 Z-50", "x\u2029G0 Z-50", "x\x0bG0 Z-50",
    "x) G0 Z-50 (y", "x; G0 Z-50", "%\nG0 Z-50", "MSG, G0 Z-50", "PROBEOPEN /tmp/x", "LOGOPEN,/tmp/x",
    "x\x00G0 Z-50", "x\tG0 Z-50", "ü (Zone) ±1°", "x" * 5000 + "\nG0 Z-50",
]


def _toolpath(title: str, comments=()) -> Toolpath:
    moves = (Rapid(None, None, 25.0), Rapid(0.0, 10.0, 25.0), Rapid(None, None, 2.0), Feed(None, None, -5.0, 200.0),
             ArcMove(10.0, 0.0, 0.0, 0.0, ccw=False, z=-5.0, feed_mm_min=400.0), Feed(0.0, -10.0, -5.0, 400.0),
             Rapid(None, None, 25.0))
    return Toolpath.of_moves(title, moves, 3000.0, tool_number=1, tool_diameter_mm=16.0, comments=tuple(comments))


@pytest.mark.parametrize("post_name", known_posts())
@pytest.mark.parametrize("text", HOSTILE_TEXT)
def test_hostile_title_and_comments_stay_comments(post_name, text):
    post = load_post(post_name)
    # the spec's file name (the generator line) is as hostile as the title: a file name may hold any of it
    prog = write_program(_toolpath(text, (text, "2 depth passes")), post, "cam", ProgramSetup(source=text))
    assert_program_safe(prog.text, post)
    # the program has exactly the lines the spec asked for: header, generator line, 2 comments, work offset,
    # tool length offset, coolant on and off (G-code; Heidenhain's ride on the first and last L block),
    # 7 moves' lines, footer
    machine_ready = (len(post.work_offset_lines("G54")) + bool(post.tool_length_offset)
                     + (0 if post.dialect == "heidenhain" else 2))
    assert len(prog.text.splitlines()) == len(post.header) + 1 + 2 + machine_ready + len(post.footer) + \
        prog.line_blocks + prog.arc_blocks * (2 if post.dialect == "heidenhain" else 1) + prog.rapid_blocks


@settings(max_examples=150, deadline=None)
@given(text=st.text(max_size=60), comment=st.sampled_from(["parentheses", "semicolon"]))
def test_encoder_keeps_any_text_inside_its_comment(text, comment):
    body = encode_comment(text, comment)
    assert body.isascii() and body.isprintable() and len(body) <= 200  # one printable ASCII line
    if comment == "parentheses":  # LinuxCNC/Fanuc: ")" ends the comment, ";" ends a Fanuc block, "%" the tape
        assert not set(body) & set("();%")
        assert not body.upper().lstrip().startswith(("MSG,", "DEBUG,", "PRINT,", "LOGOPEN", "PROBEOPEN"))


@pytest.mark.parametrize("name", ["x\n", "x\ny", "a b", "../x", "x)", "", "é", "x" * 65, "-x", ".x"])
def test_names_are_matched_whole(tmp_path, name):
    doc = tomllib.loads((SAMPLES / "demo.toml").read_text())
    doc["name"] = name
    spec = tmp_path / "s.toml"
    spec.write_text(tomli_w.dumps(doc))
    before = snapshot(tmp_path)
    code, _, err = run_inproc(["motion", spec, "-o", tmp_path / "out"])
    line = assert_clean_error(code, err)
    assert line.startswith("camcam: error: name: ")
    assert snapshot(tmp_path) == before


BAD_TEMPLATES = {
    "{tool:{title.__class__.__name__}}": "a format may not hold a field",
    "{title.__class__}": "unknown field",
    "{title[0]}": "unknown field",
    "({title!r})": "conversions",
    "{0}": "unknown field",
    "{}": "unknown field",
    "{tool:999999999d}": "format",
    "{tool:>10}": "format",
    "{title:d}": "takes no format",
    "({title:>99999999})": "takes no format",
    "{spindle:,}": "format",
    "G0 Z-50 }": "bad template",
    "{nope}": "unknown field",
    "G21\nG0 Z-50": "not allowed",
    "G21\rG0 Z-50": "not allowed",
    "{title}": "inside a comment",
    "(({title}))": "a comment inside a comment",
    "({title}": "not closed",
    "G21)": "closes no comment",
    "G21; G0 Z-50": "ends a block",
    "G20": "inches",
    # code text that is no G-code words; "0" is the footer a hypothesis draw of
    # test_broken_post_files found printed as a program line (2026-12-01, linuxcnc post)
    "0": "not G-code words",
    "g21": "not G-code words",
    "G21  G17": "not G-code words",
    "#1=5": "not G-code words",
    "/M1": "not G-code words",
    "X": "not G-code words",
    "T{tool}{spindle}M3": "not G-code words",
}


def test_footer_that_is_no_program_line_is_refused():
    # the failing example itself: a footer line "0" used to load and print a bare "0"
    data = tomllib.loads((SAMPLES.parent / "camcam" / "post" / "data" / "linuxcnc.toml").read_text())
    data["footer"] = ["0"]
    with pytest.raises(InputError, match=r"^post mill: footer\[0\]: '0' is not G-code words"):
        parse_post(data, "mill")


@pytest.mark.parametrize("line,why", list(BAD_TEMPLATES.items()))
def test_bad_templates_reject_the_whole_post(line, why):
    data = tomllib.loads((SAMPLES.parent / "camcam" / "post" / "data" / "linuxcnc.toml").read_text())
    data["header"] = data["header"] + [line]
    with pytest.raises(InputError) as e:
        parse_post(data, "mill")
    msg = str(e.value)
    assert msg.startswith("post mill: header[4]: ") and why.lower() in msg.lower(), msg
    assert "\n" not in msg


def test_templates_render_only_their_fields():
    t = parse_template("O{program_number:04d} ({title}) {units}", "parentheses")
    assert t.render({"program_number": 7, "title": "a)\nG0 Z-50", "units": "G21"}) == "O0007 (a] G0 Z-50) G21"


def test_hostile_post_file_name_end_to_end(tmp_path):
    """A post file whose name closes the title comment: the program still has only its own lines."""
    post = tmp_path / "mill) G0 Z-50 (x.toml"
    post.write_bytes((SAMPLES.parent / "camcam" / "post" / "data" / "linuxcnc.toml").read_bytes())
    doc = tomllib.loads((SAMPLES / "disc-translating-roller.toml").read_text())
    doc["machining"]["post"] = str(post)
    doc["machining"]["mode"] = "lines"
    doc["machining"]["tolerance"] = 0.05  # fewer blocks: this test is about the text, not the fit
    spec = tmp_path / "s.toml"
    spec.write_text(tomli_w.dumps(doc))
    code, _, err = run_inproc(["run", spec, "-o", tmp_path / "out"])
    assert code == 0, err
    text = (tmp_path / "out" / "disc-translating-roller.ngc").read_text()
    assert_program_safe(text, load_post(str(post)))
    assert "(disc-translating-roller: " in text.splitlines()[0] and "post mill] G0 Z-50 [x)" in text.splitlines()[0]


@pytest.mark.parametrize("stem", ["mill\nG0 Z-50", "mill\rx", "m\x1bx"])
def test_post_file_names_that_cannot_be_printed_are_refused(tmp_path, stem):
    post = tmp_path / f"{stem}.toml"
    post.write_bytes((SAMPLES.parent / "camcam" / "post" / "data" / "linuxcnc.toml").read_bytes())
    with pytest.raises(InputError) as e:
        load_post(str(post))
    assert "printable" in str(e.value)
