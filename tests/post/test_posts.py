import re

import pytest

from camcam.errors import InputError, PostError
from camcam.post.gcode import write_program
from camcam.post.post import known_posts, load_post
from camcam.toolpath.elements import Arc
from camcam.toolpath.path import ArcMove, CutSettings, Feed, Rapid, Toolpath, contour_toolpath

QUARTERS = [(10.0, 0.0), (0.0, 10.0), (-10.0, 0.0), (0.0, -10.0), (10.0, 0.0)]
CIRCLE = tuple(Arc(a, b, (0.0, 0.0), True) for a, b in zip(QUARTERS, QUARTERS[1:]))
CUT = CutSettings(depth_mm=6, stepdown_mm=4, feed_mm_min=400, spindle_rpm=3000)


def test_all_bundled_posts_load():
    names = known_posts()
    assert {"linuxcnc", "fanuc", "haas", "grbl", "sinumerik", "heidenhain"} <= set(names)
    for n in names:
        assert load_post(n).name == n


def test_posts_live_in_the_package_with_a_sample_each():
    """The bundled posts are camcam/post/data/*.toml, shipped as package data; samples/posts/ has a spec per post."""
    import tomllib
    from pathlib import Path

    root = Path(__file__).resolve().parents[2]
    assert sorted(p.stem for p in (root / "camcam" / "post" / "data").glob("*.toml")) == known_posts()
    assert sorted(p.stem for p in (root / "samples" / "posts").glob("*.toml")) == known_posts()
    package_data = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]["package-data"]
    assert "data/*.toml" in package_data["camcam.post"]


def test_unknown_post_lists_known():
    with pytest.raises(InputError, match=r"unknown post 'mach3'; known: fanuc, grbl"):
        load_post("mach3")


def test_user_post_by_path_and_validation(tmp_path):
    good = (tmp_path / "mymill.toml")
    text = (load_post.__globals__["_post_dir"]() / "linuxcnc.toml").read_text()
    good.write_text(text)
    assert load_post(str(good)).name == "mymill"
    assert load_post("./mymill.toml", base=tmp_path).extension == "ngc"
    bad = tmp_path / "bad.toml"
    bad.write_text(text.replace('arc_format = "ij_incremental"', 'arc_format = "ijk"'))
    with pytest.raises(InputError, match=r"^post bad: arc_format: expected one of"):
        load_post(str(bad))
    bad.write_text(text.replace("decimals = 4", "decimals = 1"))
    with pytest.raises(InputError, match=r"^post bad: decimals: expected 3–6, got 1$"):
        load_post(str(bad))
    bad.write_text(text + 'colour = "red"\n')
    with pytest.raises(InputError, match=r"^post bad: colour: unknown key"):
        load_post(str(bad))
    bad.write_text(text.replace("{title}", "{titel}"))
    with pytest.raises(InputError, match=r"unknown field \{titel\}"):
        load_post(str(bad))
    with pytest.raises(InputError, match="cannot read"):
        load_post(str(tmp_path / "missing.toml"))


@pytest.mark.parametrize("line", ["0", "G21", "TOOL CALL", "L X+10 FMAX", "end pgm cam mm"])
def test_a_heidenhain_post_line_must_be_a_klartext_block(tmp_path, line):
    # regression (tests/cli/test_bad_input_sweep.py found it): a Heidenhain post's footer ["0"] loaded, and
    # the program ended with the block "10 0", which the TNC refuses; G-code posts had their words checked,
    # Heidenhain's lines were not checked at all
    text = (load_post.__globals__["_post_dir"]() / "heidenhain.toml").read_text()
    bad = tmp_path / "tnc.toml"
    bad.write_text(text.replace('footer = ["STOP M5", "END PGM {name} MM"]', f'footer = ["STOP M5", "{line}"]'))
    with pytest.raises(InputError, match=rf"^post tnc: footer\[1\]: '{re.escape(line)}' is not a Klartext block"):
        load_post(str(bad))
    # what a user's TNC post prints besides camcam's own lines loads
    bad.write_text(text.replace('footer = ["STOP M5", "END PGM {name} MM"]',
                                'footer = ["L Z+100 R0 FMAX M5", "M30 ; end", "BLK FORM 0.1 Z X-50 Y-50 Z-20", '
                                '"CYCL CALL", "Q1=+5", "END PGM {name} MM"]'))
    assert load_post(str(bad)).footer[-1] == "END PGM {name} MM"


@pytest.mark.parametrize("name", ["linuxcnc", "fanuc", "haas", "grbl", "sinumerik", "heidenhain"])
def test_deterministic_and_dialect(name):
    tp = contour_toolpath(CIRCLE, CUT, "demo")
    post = load_post(name)
    a, b = write_program(tp, post, "demo"), write_program(tp, post, "demo")
    assert a.text.encode() == b.text.encode()
    assert a.arc_blocks == 12  # 2 passes × (lead-in + 4 arcs + lead-out)
    t = a.text
    if name == "fanuc":
        assert t.startswith("%\nO0001") and t.rstrip().endswith("%")
        coords = re.findall(r"\b[XYZIJ](-?[0-9.]+)", t)
        assert coords and all("." in c for c in coords)  # decimal point on every coordinate
    if name == "grbl":
        assert "M6" not in t and not re.search(r"\bT\d", t)
    if name == "heidenhain":
        assert t.startswith("0 BEGIN PGM demo MM") and "CC X+0. Y+0." in t and "DR+" in t
        assert t.rstrip().splitlines()[-1].endswith("END PGM demo MM")
    if name == "sinumerik":
        assert "G71" in t and "; demo" in t


def test_inverse_time_rotary():
    moves = (Rapid(None, None, 30.0), Feed(0.0, None, 20.0, 100.0, a_deg=0.0, length_mm=10.0),
             Feed(5.0, None, 20.0, 400.0, a_deg=90.0, length_mm=20.0))
    tp = Toolpath.of_moves("rot", moves, 1000, rotary=True)
    t = write_program(tp, load_post("linuxcnc")).text
    assert "G93" in t and "G94" in t
    assert "G1 X5 A90 F20" in t  # 400 mm/min over 20 mm → 20 per minute
    for line in t.splitlines():
        if line.startswith("G1"):
            assert " F" in line  # F on every feed move in G93


# an arc the fitter would never make: a fault of ours (exit 1), not the user's input
def test_bad_arc_is_refused():
    tp = Toolpath.of_moves("x",
                           (Rapid(0.0, 0.0, 1.0), ArcMove(10.0, 0.0, 5.0, 0.1, ccw=True, z=1.0, feed_mm_min=100.0)),
                           1000)
    with pytest.raises(PostError, match="sweeps"):
        write_program(tp, load_post("linuxcnc"))
    tp = Toolpath.of_moves("x",
                           (Rapid(0.0, 0.0, 1.0), ArcMove(10.0, 0.0, 4.0, 0.0, ccw=True, z=1.0, feed_mm_min=100.0)),
                           1000)
    with pytest.raises(PostError, match="radius differ"):
        write_program(tp, load_post("grbl"))
