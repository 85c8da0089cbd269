"""Issue 47: a barrel program's A goes back to the next pass's start in a G0 at the safe height (the unwind was a
10 s feed move, ``G1 Z52 A0 F6``), or, on a controller that takes no rotary word in G0 (post ``rotary_rapid =
false``), counts on the shortest way; no feed move is slower than the job's slowest feed. Read back from the
printed program on every post, and by LinuxCNC's interpreter."""

import math
import re
from dataclasses import replace
from functools import lru_cache

import pytest

from camcam.geometry.build import build_cam
from camcam.nc import machine_program
from camcam.post.post import known_posts, load_post
from camcam.post.readback import klartext_as_gcode
from camcam.spec import load_spec
from camcam.verify.rs274 import rs274_available, run_rs274

from tests.nc.test_job import _path

_WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")


@lru_cache(maxsize=None)
def _built(sample):
    spec = load_spec(_path(sample))
    return spec, build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))


def _program(sample, post):
    spec, built = _built(sample)
    return spec, machine_program(built, replace(spec.machining, post=post), spec.name, spec.stock)


def _moves(text: str, post) -> list:
    """(kind "G0"/"G1", start, end, F as printed, inverse time?) per move; positions as dicts of X Y Z A B."""
    if post.dialect == "heidenhain":
        text = klartext_as_gcode(text)
    pos = {"X": None, "Y": None, "Z": None, "A": 0.0, "B": 0.0}
    mode, inverse, feed, out = None, False, None, []
    for raw in text.splitlines():
        line = re.sub(r"\([^)]*\)|;.*$", "", raw.upper()).strip()
        if not line or line[0] in "%O":
            continue
        words = [(k, float(v)) for k, v in _WORD.findall(line) if k != "N"]
        gs = [v for k, v in words if k == "G"]
        if 53.0 in gs or 28.0 in gs:
            continue  # a return to the machine's reference (Fanuc, Haas): not a work-frame move
        for g in gs:
            if g in (0.0, 1.0):
                mode = f"G{int(g)}"
            inverse = True if g == 93.0 else False if g == 94.0 else inverse
        feed = next((v for k, v in words if k == "F"), feed)
        axes = {k: v for k, v in words if k in pos}
        if axes:
            start = dict(pos)
            pos.update(axes)
            out.append((mode, start, dict(pos), feed, inverse))
    return out


def _check_moves(moves, spec, radius_mm):
    """Every large A change is a G0 at the safe height; every G1 runs at least at the plunge feed."""
    m = spec.machining
    safe = radius_mm + m.safe_z_mm
    slowest = min(m.plunge_feed_mm_min, m.feed_mm_min)
    unwinds = 0
    for kind, s, e, f, inverse in moves:
        if None in (s["X"], s["Z"]):
            continue
        turn = abs(e["A"] - s["A"])
        if turn >= 180.0:
            unwinds += 1
            assert kind == "G0" and s["Z"] >= safe - 1e-9 and e["Z"] >= safe - 1e-9, (kind, s, e)
        if kind == "G1" and inverse:
            # the block's path: the tip's XYZ chord and A's arc at the cam's radius (the inverse-time length the
            # planner uses is the developed chord, within 1 % of it on these short blocks)
            length = math.hypot(e["X"] - s["X"], e["Y"] - s["Y"], e["Z"] - s["Z"],
                                radius_mm * math.radians(e["A"] - s["A"]))
            # F is printed to 4 significant decimals at least: 1 % covers it and the developed-chord difference
            assert length * f >= 0.99 * slowest, (s, e, f, length * f)
    return unwinds


FOUR_AXIS = [p for p in known_posts() if load_post(p).inverse_time]
FIVE_AXIS = [p for p in known_posts() if load_post(p).five_axis]


@pytest.mark.parametrize("post", FOUR_AXIS)
def test_four_axis_unwind_is_a_rapid_on_every_post(post):
    spec, r = _program("cylindrical-translating", load_post(post))
    assert len(r.passes) >= 2  # a pass to unwind after
    moves = _moves(r.program.text, r.post)
    assert _check_moves(moves, spec, spec.cam.base_radius) == len(r.passes) - 1  # one unwind between passes
    assert not re.search(r"G1 Z[\d.]+ A0\.? F", r.program.text)  # the old feed move down and back at once


@pytest.mark.parametrize("post", FIVE_AXIS)
def test_five_axis_unwind_is_a_rapid_on_every_post(post):
    spec, r = _program("cylindrical-oscillating", load_post(post))
    moves = _moves(r.program.text, r.post)
    if r.post.dialect == "heidenhain":  # Klartext: F in mm/min, no inverse time; its FMAX blocks read as G0
        assert any(k == "G0" and abs(e["A"] - s["A"]) >= 180 for k, s, e, _, _ in moves)
        return
    assert _check_moves(moves, spec, spec.cam.base_radius) == len(r.passes) - 1


def test_without_rotary_rapids_a_counts_on_the_shortest_way(tmp_path):
    text = (load_post.__globals__["_post_dir"]() / "linuxcnc.toml").read_text()
    path = tmp_path / "norotary.toml"
    path.write_text(text + "rotary_rapid = false\n")
    post = load_post(str(path))
    assert post.rotary_rapid is False and load_post("linuxcnc").rotary_rapid is True
    spec, r = _program("cylindrical-translating", post)
    moves = _moves(r.program.text, r.post)
    assert all(not (k == "G0" and e["A"] != s["A"]) for k, s, e, _, _ in moves)  # no rotary word in a G0
    a = [e["A"] for _, _, e, _, _ in moves]
    assert all(y >= x for x, y in zip(a, a[1:]))  # A never turns back: right-hand, cam angle rising
    assert a[-1] == pytest.approx(360.0 * len(r.passes), abs=1e-9)  # exact: printed whole degrees, summed
    assert _check_moves(moves, spec, spec.cam.base_radius) == 0


@pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")
def test_linuxcnc_interprets_the_unwind_as_a_traverse(tmp_path):
    spec, r = _program("cylindrical-translating-small-tool", load_post("linuxcnc"))
    ngc = tmp_path / "p.ngc"
    ngc.write_text(r.program.text)
    canon = run_rs274(ngc)
    prev, unwinds = None, 0
    for mv in canon:
        if prev is not None and abs(mv.a - prev.a) >= 180.0:
            unwinds += 1
            # rs274 prints 4 decimals: the safe height R50 + 25 is exact at that
            assert mv.kind == "rapid" and min(mv.z, prev.z) >= 75.0 - 1e-4, (prev, mv)
        prev = mv
    # a pass that starts where the last one's A ended needs no unwind: with climb milling flank 0 runs A down
    # (issue 47, Shop II), so of the 5 pass changes 3 unwind (slot -> slot, flank 0 -> flank 0, flank 1 -> flank 1)
    a = [[m.a_deg for m in p.moves if getattr(m, "a_deg", None) is not None] for p in r.passes]
    jumps = sum(abs(nxt[0] - last[-1]) >= 180.0 for last, nxt in zip(a, a[1:]))
    assert unwinds == jumps == 3 and len(r.passes) == 6
