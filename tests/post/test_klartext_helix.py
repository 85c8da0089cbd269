"""Heidenhain's Klartext has helices only in polar coordinates (``CC`` pole, then ``CP IPA… IZ… DR…``): the post
prints every helical arc that way (a face groove's ramped entries, the helical bore), where it used to refuse
the job with exit 2 ("helical arcs (ramped groove entries) are not supported by this dialect", seen on
design-space cases 43:32 and 43:60 with a dowel hole or bore cut on Heidenhain)."""

import math
import re
from pathlib import Path

import pytest

from camcam.cli import main
from camcam.post.post import load_post
from camcam.post.readback import read_program

ROOT = Path(__file__).resolve().parents[2]


def _spec(tmp_path: Path, sample: str, extra: str = "", tool: str | None = None) -> Path:
    text = (ROOT / "samples" / f"{sample}.toml").read_text()
    text = re.sub(r'(?m)^post = ".*"$', 'post = "heidenhain"', text).replace("[machining]\n", "[machining]\n" + extra)
    if tool is not None:
        text = re.sub(r"(?m)^tool_diameter = .*$", f"tool_diameter = {tool}", text)
    spec = tmp_path / "hh.toml"
    spec.write_text(text)
    return spec


def test_helical_bore_prints_polar_helices_that_read_back_on_the_circle(tmp_path, capsys):
    assert main(["run", str(_spec(tmp_path, "disc-translating-roller", "bore = true\n", "8.0")),
                 "-o", str(tmp_path / "out")]) == 0
    text = (tmp_path / "out" / "disc-translating-roller.h").read_text()
    helices = re.findall(r"^\d+ CP IPA([+-][\d.]+) IZ([+-][\d.]+) DR([+-]) R0 F", text, re.M)
    assert helices and all(float(a) == 90.0 and d == "+" for a, _, d in helices)  # quarter turns, counter-clockwise
    # read back (the material check's reader): every helix ends on the tool-centre circle, Ø12 bore − Ø8 tool
    moves = [m for m in read_program(text, load_post("heidenhain")) if not isinstance(m, str)]
    arcs = [m for m in moves if m.kind == "arc" and m.centre == pytest.approx((0.0, 0.0), abs=1e-3)]
    for m in arcs:
        # printed to 0.001 mm; the bore's circle fitted within the job's 0.01 mm
        assert math.hypot(m.x, m.y) == pytest.approx(2.0, abs=0.011)
    # the Z travel adds up: from the top (Z0) down to the bore's depth, the cam's 12 mm
    assert sum(float(z) for _, z, _ in helices) == pytest.approx(-12.0, abs=1e-9)  # printed increments, exact sums
    assert min(m.z for m in arcs) == pytest.approx(-12.0, abs=1e-9)


def test_face_groove_on_heidenhain_is_cut_and_checked(tmp_path, capsys):
    """disc-groove's ramped entries are helices: on Heidenhain the job now runs, and the material check (which reads
    the Klartext back, helices included) passes it."""
    assert main(["run", str(_spec(tmp_path, "disc-groove")), "-o", str(tmp_path / "out")]) == 0
    out = capsys.readouterr().out
    assert "PASS" in out and "0 plunges into material" in out
    text = (tmp_path / "out" / "disc-groove.h").read_text()
    assert re.search(r"^\d+ CP IPA-[\d.]+ IZ-[\d.]+ DR- R0 F", text, re.M)
    assert "G2" not in text and "G3" not in text  # Klartext only


def test_readback_of_a_polar_helix():
    """The reader's arithmetic on a written example: a quarter turn about (10, 0) from (20, 0), 2 mm down."""
    moves = read_program("1 L X+20 Y+0 Z+0 R0 FMAX\n2 CC X+10 Y+0\n3 CP IPA+90 IZ-2 DR+ R0 F100\n",
                         load_post("heidenhain"))
    (m,) = [m for m in moves if not isinstance(m, str) and m.kind == "arc"]
    assert (m.x, m.y, m.z) == pytest.approx((10.0, 10.0, -2.0), abs=1e-12)  # cos/sin of 90°: 6e-16
    assert m.ccw and m.centre == (10.0, 0.0)
