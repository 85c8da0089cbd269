"""Machine-ready programs: tool length offset, work offset, coolant, program number, generator line;
LinuxCNC's interpreter (rs274) reads every program it can and shows the offset applied."""

import re

import pytest

from camcam import __version__
from camcam.errors import InputError
from camcam.nc.settings import ProgramSetup
from camcam.post.gcode import write_program
from camcam.post.post import load_post
from camcam.toolpath.elements import Arc
from camcam.toolpath.path import CutSettings, contour_toolpath
from camcam.verify.rs274 import rs274_available

QUARTERS = [(10.0, 0.0), (0.0, 10.0), (-10.0, 0.0), (0.0, -10.0), (10.0, 0.0)]
CIRCLE = tuple(Arc(a, b, (0.0, 0.0), True) for a, b in zip(QUARTERS, QUARTERS[1:]))
CUT = CutSettings(depth_mm=9, stepdown_mm=3, feed_mm_min=400, spindle_rpm=3000, finish_allowance_mm=0.3,
                  spring_pass=True, tool_number=3, tool_diameter_mm=8.0)
SETUP = ProgramSetup("G55", "flood", None, "demo.toml")

#: What each controller must say, from its manual: tool length offset, work offset G55, coolant on, off.
EXPECTED = {
    "linuxcnc": (r"^G43 H3$", r"^G55$", r"^M8$", r"^M9$"),
    "fanuc": (r"^N\d+ G43 H3$", r"^N\d+ G55$", r"^N\d+ M8$", r"^N\d+ M9$"),
    "haas": (r"^N\d+ G43 H03$", r"^N\d+ G55$", r"^N\d+ M8$", r"^N\d+ M9$"),
    # Sinumerik: D1 with the tool call activates the length offset
    "sinumerik": (r"^N\d+ T3 D1$", r"^N\d+ G55$", r"^N\d+ M8$", r"^N\d+ M9$"),
    # Heidenhain: TOOL CALL applies the length; cycle 247 selects preset 2; M8/M9 ride on L blocks
    "heidenhain": (r"^\d+ TOOL CALL 3 Z S3000$", r"^\d+ CYCL DEF 247 DATUM SETTING ~\n  Q339=\+2 ;DATUM NUMBER$",
                   r"^\d+ L .* FMAX M3 M8$", r"^\d+ L .* FMAX M9$"),
    # GRBL has no tool table: no length offset word (the setup sheet says to touch Z0 off with the tool)
    "grbl": (None, r"^G55$", r"^M8$", r"^M9$"),
}


def program(name, setup=SETUP, cut=CUT):
    return write_program(contour_toolpath(CIRCLE, cut, "demo"), load_post(name), "demo", setup)


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_every_post_states_offsets_coolant_and_generator(name):
    text = program(name).text
    for pattern in EXPECTED[name]:
        if pattern is not None:
            assert re.search(pattern, text, re.M), (name, pattern)
    assert f"camcam {__version__}, spec demo.toml" in text
    assert not re.search(r"20\d\d-\d\d-\d\d", text)  # no date: same spec, same bytes
    # the coolant goes on before the first cut and off after the last
    lines = text.splitlines()
    feeds = [i for i, s in enumerate(lines) if re.search(r"^(N?\d+ )?(G[123] |C X|L .* F\d)", s)]
    on = next(i for i, s in enumerate(lines) if re.search(r"\bM8\b", s))
    off = next(i for i, s in enumerate(lines) if re.search(r"\bM9\b", s))
    first_feed, last_feed = feeds[0], feeds[-1]
    assert on <= first_feed and off > last_feed


def test_program_number_and_refusals():
    assert program("fanuc", ProgramSetup(program_number=1234)).text.startswith("%\nO1234 (demo")
    assert "\nO04321 (demo" in program("haas", ProgramSetup(program_number=4321)).text
    with pytest.raises(InputError, match=r"^program_number: expected 1–9999 for post fanuc, got 12345$"):
        program("fanuc", ProgramSetup(program_number=12345))
    with pytest.raises(InputError, match=r"^program_number: post linuxcnc does not print a program number$"):
        program("linuxcnc", ProgramSetup(program_number=7))
    with pytest.raises(InputError, match=r"^coolant: post heidenhain has no word for mist coolant$"):
        program("heidenhain", ProgramSetup(coolant="mist"))
    with pytest.raises(InputError, match=r"^work_offset: expected one of G54, G55"):
        program("linuxcnc", ProgramSetup(work_offset="G60"))


def test_sinumerik_maps_g58_g59_to_its_settable_frames():
    # Sinumerik's G58/G59 are programmable (axial) offsets; its 5th and 6th settable frames are G505/G506
    assert re.search(r"^N\d+ G505$", program("sinumerik", ProgramSetup("G58")).text, re.M)
    assert re.search(r"^N\d+ G506$", program("sinumerik", ProgramSetup("G59")).text, re.M)


def test_mist_and_off_words():
    assert re.search(r"^M7$", program("linuxcnc", ProgramSetup(coolant="mist")).text, re.M)
    off = program("linuxcnc", ProgramSetup(coolant="off")).text
    assert not re.search(r"^M[78]$", off, re.M) and len(re.findall(r"^M9$", off, re.M)) == 2


def test_heidenhain_continuation_line_is_not_numbered():
    lines = program("heidenhain").text.splitlines()
    i = next(k for k, s in enumerate(lines) if "CYCL DEF 247" in s)
    numbers = [int(s.split()[0]) for s in lines if s[:1].isdigit()]
    assert lines[i + 1] == "  Q339=+2 ;DATUM NUMBER"
    assert numbers == list(range(numbers[0], numbers[0] + len(numbers)))  # consecutive block numbers


def test_spec_keys_reach_the_program(tmp_path):
    from camcam.spec import load_spec
    from camcam.errors import SpecError

    base = (__import__("pathlib").Path(__file__).resolve().parents[2] / "samples" / "posts" / "fanuc.toml").read_text()
    spec = tmp_path / "job.toml"
    spec.write_text(base + 'work_offset = "G57"\ncoolant = "mist"\nprogram_number = 77\n')
    s = load_spec(spec)
    assert s.machining.setup == ProgramSetup("G57", "mist", 77, "job.toml")
    spec.write_text(base.replace('post = "fanuc"', 'post = "linuxcnc"') + "program_number = 77\n")
    with pytest.raises(SpecError, match=r"^machining.program_number: post linuxcnc does not print a program number$"):
        load_spec(spec)
    spec.write_text(base + 'coolant = "wet"\n')
    with pytest.raises(SpecError, match=r"^machining.coolant: "):
        load_spec(spec)


needs_rs274 = pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")


@needs_rs274
@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas", "grbl"])
def test_rs274_reads_it_and_applies_the_tool_length_offset(tmp_path, name):
    import subprocess

    prog = program(name)
    f = tmp_path / f"demo.{prog.extension}"
    f.write_text(prog.text)
    out = subprocess.run(["rs274", "-g", str(f)], stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    canon = out.stdout.splitlines()
    first_move = next(i for i, s in enumerate(canon) if "STRAIGHT_" in s or "ARC_FEED" in s)
    # G55 is coordinate system 2; rs274 announces it before any move
    assert any("SET_G5X_OFFSET(2," in s for s in canon[:first_move])
    assert any("FLOOD_ON()" in s for s in canon[:first_move]) and any("FLOOD_OFF()" in s for s in canon[first_move:])
    offsets = [re.search(r"USE_TOOL_LENGTH_OFFSET\(([-\d.]+) ([-\d.]+) ([-\d.]+),", s) for s in canon[:first_move]]
    z_offsets = [float(m.group(3)) for m in offsets if m]
    if name == "grbl":
        assert all(z == 0 for z in z_offsets)  # no tool table on GRBL: nothing to apply
    else:
        # rs274 without a tool table uses dummy tools; a non-zero Z offset before the first move means G43 took effect
        assert z_offsets[-1] != 0.0, canon[:first_move]
