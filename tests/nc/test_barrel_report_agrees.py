"""A barrel cam's report and its program agree (issue 43 B): pass order and Z, pass comments, cut depth, flute
length, the rotary feed distance and the cycle time, each read back from the printed program."""

import math
import re
import subprocess
from dataclasses import replace
from functools import lru_cache

import numpy as np
import pytest

from camcam.verify import checked
from camcam.post.post import load_post
from camcam.post.text import encode_comment
from camcam.report.setup_sheet import setup_blocks
from camcam.verify.rs274 import rs274_available, run_rs274

from tests.nc.test_job import built_and_result

needs_rs274 = pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")
BARRELS = ["cylindrical-translating", "cylindrical-oscillating"]


@lru_cache(maxsize=None)
def _job(sample):
    return built_and_result(sample)


@lru_cache(maxsize=None)
def _canon(sample, tmp):
    spec, built, result = _job(sample)
    f = tmp / result.program_filename
    f.write_text(result.program.text)
    return run_rs274(f, comments=True)


@pytest.fixture(scope="module")
def canon(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("barrels")
    return lambda sample: _canon(sample, tmp)


def _passes_read_back(events):
    """{pass comment: [feed moves]} in program order, from rs274's canonical moves and comments."""
    out, current = {}, None
    for ev in events:
        if isinstance(ev, str):
            if re.match(r"pass \d+/\d+: ", ev):
                current = ev
                out[current] = []
            continue
        if current is not None and ev.kind == "line":
            out[current].append(ev)
    return out


@needs_rs274
@pytest.mark.parametrize("sample", BARRELS)
def test_every_pass_opens_with_its_comment_and_states_its_z(canon, sample):
    spec, built, result = _job(sample)
    passes = _passes_read_back(canon(sample))
    n = len(result.passes)
    assert list(passes) == [encode_comment(f"pass {i + 1}/{n}: {p.kind}, {result.contours[p.contour].label}, "
                                           f"Z{p.z:g}, {p.direction}", "parentheses")
                            for i, p in enumerate(result.passes)]
    for p, moves in zip(result.passes, passes.values()):
        # the pass's Z is the lowest tip Z its blocks print (rs274 prints 4 decimals, as the post does)
        assert p.z == pytest.approx(min(mv.z for mv in moves), abs=1e-9)  # the same 4-decimal text, parsed twice
    table = setup_blocks(built, result, spec.machining)[2]
    assert [row[3] for row in table.rows] == [f"{p.z:g}" for p in result.passes]


@needs_rs274
def test_five_axis_passes_are_listed_top_first(canon):
    # the report listed the deepest first: pass 1/2 at Z63.288 where the program cuts pass 1 down to Z70.3543
    _, _, result = _job("cylindrical-oscillating")
    zs = [p.z for p in result.passes]
    assert zs == sorted(zs, reverse=True) and len(zs) == 2
    lows = [min(m.z for m in moves) for moves in _passes_read_back(canon("cylindrical-oscillating")).values()]
    assert lows == sorted(lows, reverse=True)


def _poses(text):
    """(X, Y, Z, A, B) of every G1 block, modal, from the program text."""
    pos = dict(X=None, Y=None, Z=None, A=0.0, B=0.0)
    out = []
    for line in text.splitlines():
        if line.startswith("("):
            continue
        words = dict((w[0], float(w[1:])) for w in line.split() if w[0] in "XYZAB")
        pos.update(words)
        if line.startswith("G1") and None not in pos.values():
            out.append(tuple(pos[k] for k in "XYZAB"))
    return np.array(out)


def _brute_reach(poses, r_t, top):
    """(deepest radius any point of the flat end reaches, largest distance up the tool at which its side is still
    inside the outer cylinder), brute force: the end disc and the side circles sampled every 0.1° and 0.001 mm."""
    phi = np.radians(np.arange(0.0, 360.0, 0.1))
    deepest, reach = math.inf, 0.0
    for x, y, z, a, b in poses:
        b = math.radians(b)
        axis = np.array([math.sin(b), 0.0, math.cos(b)])
        u, v = np.array([math.cos(b), 0.0, -math.sin(b)]), np.array([0.0, 1.0, 0.0])
        ring = r_t * (np.cos(phi)[:, None] * u + np.sin(phi)[:, None] * v)
        tip = np.array([x, y, z])
        lowest = lambda l: float(np.hypot(*(tip + l * axis + ring)[:, 1:].T).min())  # noqa: E731
        deepest = min(deepest, lowest(0.0))
        if lowest(0.0) < top:  # bisect the height where the side circle leaves the cylinder of radius top
            lo, hi = 0.0, 4 * top
            while hi - lo > 1e-3:
                mid = 0.5 * (lo + hi)
                lo, hi = (mid, hi) if lowest(mid) < top else (lo, mid)
            reach = max(reach, lo)
    return deepest, reach


@pytest.mark.parametrize("sample", BARRELS)
def test_cut_depth_and_flute_length_are_the_programs(sample):
    spec, built, result = _job(sample)
    cam, m = built.cam, spec.machining
    deepest, reach = _brute_reach(_poses(result.program.text), m.tool_diameter_mm / 2, cam.base_radius)
    check = {c.name: c for c in result.checks}["cut depth"]
    # the check's figure is how deep the printed tool goes (it said the stated depth: 10 of 10 mm where the
    # 4-axis tip runs 0.2988 mm deeper, and the 5-axis flat end 8.91 mm below the groove floor)
    assert check.value == pytest.approx(cam.base_radius - deepest, abs=1e-4)  # 0.1° sampling of a Ø30 end: 6e-6 mm
    assert check.ok  # as deep as the walls need, no deeper
    assert result.reach.below_floor_mm == pytest.approx(cam.bottom_radius - deepest, abs=1e-4)  # the same sampling
    # the setup sheet asks for the flute the program needs (it asked for 10 mm where the cut reaches 19.58)
    rows = dict(setup_blocks(built, result, m)[1].rows)
    asked = float(re.search(r"flute length ≥ ([\d.]+) mm", rows["tool"]).group(1))
    assert reach - 1e-3 <= asked < reach + 0.011  # the bisection's 1e-3 mm; rounded up to 0.01 mm


def test_a_deeper_stated_depth_warns_with_the_programs_depth():
    spec, built, _ = _job("cylindrical-translating")
    m = replace(spec.machining, depth_mm=11.0, stepdown_mm=5.5)
    result = checked(built, m, "deeper")
    check = {c.name: c for c in result.checks}["cut depth"]
    assert not check.ok and check.severity == "warn"
    assert check.value == pytest.approx(11.2988, abs=1e-9)  # 11 mm + the 0.2988 mm corner dip, as printed
    # the groove depth + the exact dip, 0.298737 mm (nc.rotary.corner_offset_mm: 4.88 mm off the axis plane on the
    # R40 bottom, where r_t sin α = 4.86 mm gave 0.295920)
    assert check.limit == pytest.approx(10.298737, abs=1e-5)


def _tip_path(p0, p1, chords=2000):
    """The tip's path in the part between two poses (X Y Z A), as dense chords of Rx(−A)·p."""
    u = np.linspace(0.0, 1.0, chords + 1)[:, None]
    q = (1 - u) * np.asarray(p0, float) + u * np.asarray(p1, float)
    a = -np.radians(q[:, 3])
    y = np.cos(a) * q[:, 1] - np.sin(a) * q[:, 2]
    z = np.sin(a) * q[:, 1] + np.cos(a) * q[:, 2]
    pts = np.column_stack([q[:, 0], y, z])
    return float(np.linalg.norm(np.diff(pts, axis=0), axis=1).sum())


@needs_rs274
@pytest.mark.parametrize("sample", BARRELS)
def test_cycle_time_is_what_the_controller_does(canon, sample, tmp_path):
    _, _, result = _job(sample)
    f = tmp_path / result.program_filename
    f.write_text(result.program.text)
    # rs274's canonical feed rates: in inverse time it sets rate = the move's XYZ length × F, so a move takes its
    # XYZ length / rate minutes (its A/B travel / rate when only they move): 1/F, the program's own words
    lines = subprocess.run(["rs274", "-g", str(f)], stdin=subprocess.DEVNULL, capture_output=True,
                           text=True).stdout.splitlines()
    inverse = [1.0 / float(re.search(r" F([\d.]+)", b).group(1)) for b in result.program.text.splitlines()
               if b.startswith("G1")]
    rate, pos, path, k = None, (0.0, 0.0, 0.0, 0.0, 0.0), 0.0, 0
    for line in lines:
        mr = re.search(r"SET_FEED_RATE\(([-\d.]+)\)", line)
        if mr:
            rate = float(mr.group(1))
        mm = re.search(r"(STRAIGHT_FEED|STRAIGHT_TRAVERSE)\((.*)\)", line)
        if mm:
            new = tuple(float(v) for v in mm.group(2).split(",")[:5])
            if mm.group(1) == "STRAIGHT_FEED":
                d = math.dist(pos[:3], new[:3]) or math.dist(pos[3:], new[3:])
                # rs274 prints the rate with 4 decimals: the move's time is known to d/(rate ∓ 5e-5).  It prints
                # no rate under 0.1 (the 0.0001 mm X step at A160 of the 5-axis sample, F472.8, would be 0.0473):
                # such a move is held to its printed F alone
                if rate > 0.1:  # (± 1e-12: float rounding of the quotients only)
                    assert d / (rate + 5e-5) - 1e-12 <= inverse[k] <= d / (rate - 5e-5) + 1e-12
                path += _tip_path(pos[:4], new[:4])
                k += 1
            pos = new
    assert k == len(inverse)
    ct = result.program.cycle_time
    assert ct.feed_s == pytest.approx(60 * sum(inverse), rel=1e-6)  # F as printed, 4 decimals, parsed again
    # the feed distance is the tip's path in the part, A's turn included (it was the XYZ travel alone:
    # 225 mm where the tip runs 1012 mm on cylindrical-translating)
    assert ct.feed_mm == pytest.approx(path, rel=1e-6)  # 2000 chords a move against Simpson's 16 intervals


def test_heidenhain_five_axis_time_is_the_tip_path_over_its_feed():
    # Klartext under M128: F is the tool tip's feed in mm/min along its path in the part (no inverse time)
    spec, built, _ = _job("cylindrical-oscillating")
    result = checked(built, replace(spec.machining, post=load_post("heidenhain")), "hh")
    pos, minutes, path = dict(X=0.0, Y=0.0, Z=0.0, A=0.0, B=0.0), 0.0, 0.0
    for line in result.program.text.splitlines():
        words = line.split()
        if len(words) < 2 or words[1] != "L":
            continue
        new = dict(pos, **{w[0]: float(w[1:]) for w in words[2:] if w[0] in "XYZAB"})
        feed = [float(w[1:]) for w in words if re.fullmatch(r"F[\d.]+", w)]
        if feed:
            d = _tip_path([pos[k] for k in "XYZA"], [new[k] for k in "XYZA"])
            minutes += d / feed[0]
            path += d
        pos = new
    ct = result.program.cycle_time
    assert ct.feed_s == pytest.approx(60 * minutes, rel=1e-6)  # 2000 chords a move against Simpson's 16 intervals
    assert ct.feed_mm == pytest.approx(path, rel=1e-6)  # the same
