"""Cutting data per pass kind and the feed at the cutting edge, read back by LinuxCNC's interpreter.

The printed program is run through ``rs274`` (its canonical ``SET_SPINDLE_SPEED``, ``SET_FEED_RATE``,
``STRAIGHT_FEED`` and ``ARC_FEED`` calls).  The expected speeds and feeds are worked out here from the
published figures (Tungaloy's carbon-steel row, see :mod:`camcam.nc.cutting_data`) and the catalogue
formulas n = 1000·vc/(π·D), vf = fz·z·n; the edge feed of every arc from the interpreted centre and
radius: the edge runs on R − r_t where the material is on the centre's side, R + r_t where it is not.
"""

import math
import re
import subprocess
from pathlib import Path

import pytest
from hypothesis import given, strategies as st

from camcam.errors import SpecError
from camcam.geometry.build import build_cam
from camcam.nc import machine_program
from camcam.nc.cutting_data import feed_mm_min, spindle_rpm
from camcam.nc.feeds import MAX_ARC_FACTOR, MIN_ARC_FACTOR, arc_factor, centre_feed
from camcam.spec import load_spec
from camcam.toolpath.path import ArcMove
from camcam.verify.rs274 import rs274_available

ROOT = Path(__file__).resolve().parents[2]
DISC = ROOT / "samples" / "disc-translating-roller.toml"  # [cam] material = "C45 steel", a Ø16 tool
GROOVE = Path(__file__).parent / "data" / "groove-rough-bend-43-140.toml"  # a Ø16 tool in a 38.6 mm groove

needs_rs274 = pytest.mark.skipif(not rs274_available(), reason="LinuxCNC's rs274 not installed")


def _spec(tmp_path, source: Path, machining: str, drop=("feed", "spindle"), cam: str = ""):
    text = source.read_text()
    for key in drop:
        text = re.sub(rf"(?m)^{key} = .*\n", "", text)
    text = text.replace("bore = 12.0\n", "bore = 24.0\n")  # a helical bore the Ø16 tool fits
    keys, sub, tables = machining.partition("[machining.")  # sub-tables go last: keys after them would be theirs
    text = text.replace("[cam]\n", "[cam]\n" + cam).replace("[machining]\n", "[machining]\n" + keys)
    text += "\n" + sub + tables
    path = tmp_path / source.name
    path.write_text(text)
    return load_spec(path)


def _job(spec):
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    return machine_program(built, spec.machining, spec.name, spec.stock)


def _canon(result, tmp_path) -> list[tuple[str, list]]:
    prog = tmp_path / "p.ngc"
    prog.write_text(result.program.text)
    out = subprocess.run(["rs274", "-g", str(prog)], stdin=subprocess.DEVNULL, capture_output=True, text=True,
                         timeout=120, check=True).stdout
    calls = []
    for line in out.splitlines():
        m = re.search(r"\b([A-Z_]+)\((.*)\)\s*$", line)
        if m:
            calls.append((m.group(1), m.group(2)))
    return calls


def _read(result, tmp_path) -> list[dict]:
    """Every feed move with the pass it belongs to, the interpreter's S and F at it."""
    s = f = None
    at, kind, direction, out = None, None, None, []
    for call, args in _canon(result, tmp_path):
        if call == "SET_SPINDLE_SPEED":
            s = float(args.split(",")[1])
        elif call == "SET_FEED_RATE":
            f = float(args)
        elif call == "COMMENT" and args.startswith('"pass '):
            head = args.strip('"').split(": ", 1)[1].split(", ")
            kind, direction = head[0], head[3]
        elif call in ("STRAIGHT_TRAVERSE", "STRAIGHT_FEED", "ARC_FEED"):
            v = [float(x) for x in args.split(",")]
            if call == "ARC_FEED":
                end, centre, ccw, z = (v[0], v[1]), (v[2], v[3]), v[4] > 0, v[5]
            else:
                end, centre, ccw, z = (v[0], v[1]), None, False, v[2]
            if call != "STRAIGHT_TRAVERSE" and at is not None:
                out.append(dict(kind=kind, direction=direction, s=s, f=f, start=at, end=end, centre=centre, ccw=ccw,
                                vertical=end == at[:2] and z != at[2]))
            at = (*end, z)
    return out


def _expected(vc, fz_per_mm, d=16.0, z=3):
    """(rev/min, mm/min) from the published vc and chip load per mm of diameter, rounded as a machinist types them."""
    n = round(1000 * vc / (math.pi * d))
    return n, round(fz_per_mm * d * z * n)


STEEL = {"rough": _expected(160.0, 0.0575 / 11), "finish": _expected(225.0, 0.115 / 11)}  # Tungaloy p. 1091
STEEL["spring"] = STEEL["finish"]
STEEL["bore"] = STEEL["rough"][0], round(STEEL["rough"][1] * 0.5)  # full width: the rough feed x 0.5
STEEL["slot"] = STEEL["bore"]


def _check_moves(moves, table, r_t=8.0):
    """Each pass at its kind's S; lines at its F; arcs with the edge at F (one-sided passes)."""
    arcs = 0
    for mv in moves:
        n, feed = table[mv["kind"]]
        assert mv["s"] == n, mv
        if mv["vertical"]:
            continue  # a plunge, at the plunge feed
        if mv["centre"] is None or mv["direction"] == "both":
            assert mv["f"] == feed, mv
            continue
        cx, cy = mv["centre"]
        radius = math.hypot(mv["end"][0] - cx, mv["end"][1] - cy)
        material_left = mv["direction"] == "conventional"
        at_centre = material_left == mv["ccw"]  # a ccw arc's centre is on the left of travel
        edge = radius - r_t if at_centre else radius + r_t
        k = radius / edge if edge > 0 else math.inf
        if MIN_ARC_FACTOR < k < MAX_ARC_FACTOR:
            # the centre feed is printed to whole mm/min: the edge's is off by at most half of that × edge/R
            assert mv["f"] * edge / radius == pytest.approx(feed, abs=0.5 * edge / radius + 1e-9), mv
        else:
            assert mv["f"] == round(feed * min(max(k, MIN_ARC_FACTOR), MAX_ARC_FACTOR)), mv
        arcs += 1
    return arcs


@needs_rs274
@pytest.mark.parametrize("direction", ["climb", "conventional"])
def test_disc_passes_run_at_their_kinds_data_with_the_edge_feed_on_every_arc(tmp_path, direction):
    spec = _spec(tmp_path, DISC, f'flutes = 3\nbore = true\ndirection = "{direction}"\n')
    result = _job(spec)
    moves = _read(result, tmp_path)
    assert {mv["kind"] for mv in moves} == {"rough", "finish", "spring", "bore"}
    assert _check_moves(moves, STEEL) > 50
    # the speeds worked out here are the program's, and its header starts with the first pass's
    assert STEEL["rough"] == (3183, 799) and STEEL["finish"] == (4476, 2246)
    assert "S3183 M3" in result.program.text.splitlines()[:5] and "\nS4476 M3\n" in result.program.text
    assert "vc 160 m/min, fz 0.08364 mm x 3 flutes: S3183 F799" in result.program.text


@needs_rs274
def test_grooved_disc_slot_at_half_the_rough_feed_walls_at_the_edge_feed(tmp_path):
    spec = _spec(tmp_path, GROOVE, "flutes = 3\n", cam='material = "C45 steel"\n')
    moves = _read(_job(spec), tmp_path)
    assert {mv["kind"] for mv in moves} == {"slot", "rough", "finish"}
    assert _check_moves(moves, STEEL) > 50


@needs_rs274
def test_explicit_speeds_and_chip_loads_per_kind(tmp_path):
    spec = _spec(tmp_path, DISC, 'flutes = 2\n[machining.rough]\nrpm = 2500\nfeed_mm_min = 350\n'
                                 '[machining.finish]\nvc_m_min = 180\nfz_mm = 0.04\n', drop=())
    m = spec.machining
    n = spindle_rpm(180.0, 16.0)
    assert n == round(1000 * 180 / (math.pi * 16)) == 3581  # the catalogue formula, by hand: 3580.99
    table = {"rough": (2500, 350), "finish": (n, round(0.04 * 2 * n)), "spring": (n, round(0.04 * 2 * n))}
    kinds = ("rough", "finish", "spring")
    assert [(c.kind, c.rpm, c.feed_mm_min) for c in m.cutting] == [(k, *table[k]) for k in kinds]
    assert m.cutting[0].fz_mm == pytest.approx(350 / (2 * 2500))  # derived for the comment; exact up to float
    moves = _read(_job(spec), tmp_path)
    assert _check_moves(moves, table) > 20


def test_the_catalogue_example():
    # WIDIA's worked example ("Calculating Speed and Feed"): D1 = 125 mm, vc = 200 m/min -> 510 rev/min;
    # fz 0.2 mm, Z = 8 -> vf = 816 mm/min (their n rounded up from 509.3; ours to the nearest)
    assert spindle_rpm(200.0, 125.0) == 509
    assert feed_mm_min(0.2, 8, 510.0) == 816


def test_arc_factor_is_sandvik_circular_interpolation():
    # Sandvik Coromant: external vf_centre = vf (Dm + Dc)/Dm, internal (Dm − Dc)/Dm, Dm the part's diameter
    dm, dc = 40.0, 16.0
    assert arc_factor((dm + dc) / 2, dc / 2, True) == pytest.approx((dm + dc) / dm, rel=1e-12)  # float rounding only
    assert arc_factor((dm - dc) / 2, dc / 2, False) == pytest.approx((dm - dc) / dm, rel=1e-12)
    assert arc_factor(9.0, 8.0, True) == MAX_ARC_FACTOR  # a 1 mm convex nose: capped


@pytest.mark.parametrize("machining, field", [
    ("flutes = 3\n[machining.rough]\nvc_m_min = 160\nrpm = 3000\n", "machining.rough.rpm"),
    ("flutes = 3\n[machining.rough]\nvc_m_min = 160\n", "machining.rough.fz_mm"),
    ("flutes = 3\n[machining.rough]\nvc_m_min = 5000\nfz_mm = 0.05\n", "machining.rough.vc_m_min"),
    ("flutes = 3\n[machining.finish]\nrpm = 3000\nfeed_mm_min = -1\n", "machining.finish.feed_mm_min"),
    ("[machining.rough]\nrpm = 3000\nfeed_mm_min = 400\n", "machining.rough"),
    ("flutes = 0\n", "machining.flutes"),
])
def test_bad_cutting_data_names_the_field(tmp_path, machining, field):
    with pytest.raises(SpecError, match=rf"^{re.escape(field)}: "):
        _spec(tmp_path, DISC, machining, drop=() if "flutes" not in machining else ("feed", "spindle"))


def test_no_preset_and_no_feed_is_refused(tmp_path):
    with pytest.raises(SpecError, match=r"^machining.rough: missing; expected \[machining.rough\]"):
        _spec(tmp_path, DISC.parent / "disc-oscillating-flat.toml", "flutes = 3\n")


def test_setup_sheet_states_each_kinds_figures_and_source(tmp_path):
    from camcam.report.setup_sheet import setup_blocks
    from camcam.verify import checked

    spec = _spec(tmp_path, DISC, "flutes = 3\n")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    result = checked(built, spec.machining, spec.name, spec.stock)  # with the cycle time the sheet states
    _, keys, passes = setup_blocks(built, result, spec.machining)
    text = dict(keys.rows)["cutting data"]
    assert "rough vc 160 m/min, fz 0.08364 mm × 3: S3183 F799 (preset steel: Tungaloy" in text
    assert "finish vc 225 m/min, fz 0.1673 mm × 3: S4476 F2246 (preset steel" in text
    assert "spring vc 225 m/min, fz 0.1673 mm × 3: S4476 F2246 (as finish)" in text
    assert [(r[1], r[4], r[5]) for r in passes.rows] == [("rough", "799", "3183"), ("rough", "799", "3183"),
                                                          ("finish", "2246", "4476"), ("spring", "2246", "4476")]
    assert text.startswith("climb milling (the material right of travel); S printed at each pass")


@given(radius=st.floats(0.5, 500.0), r_t=st.floats(0.5, 20.0), feed=st.floats(50.0, 5000.0), ccw=st.booleans(),
       side=st.sampled_from(["left", "right"]))
def test_the_edge_runs_at_the_pass_feed_on_any_arc(radius, r_t, feed, ccw, side):
    arc = ArcMove(radius, 0.0, 0.0, 0.0, ccw=ccw, z=0.0, feed_mm_min=feed)
    centre = centre_feed(feed, arc, r_t, side)
    at_centre = (side == "left") == ccw  # a ccw arc's centre is on the left of travel
    edge = radius - r_t if at_centre else radius + r_t
    k = radius / edge if edge > 0 else math.inf
    if MIN_ARC_FACTOR < k < MAX_ARC_FACTOR:
        # whole mm/min at the centre: the edge is off by at most half of that x edge/R (plus float noise)
        assert abs(centre * edge / radius - feed) <= 0.5 * edge / radius + 1e-9
    else:
        assert centre == round(feed * min(max(k, MIN_ARC_FACTOR), MAX_ARC_FACTOR))
    # convex (the material on the centre's side): the centre runs faster than the edge; concave: slower
    assert (centre >= round(feed)) if at_centre else (centre <= round(feed))


def _limited_post(tmp_path, rpm: float, feed: float) -> str:
    from camcam.post.post import load_post

    text = (load_post.__globals__["_post_dir"]() / "linuxcnc.toml").read_text()
    path = tmp_path / "limited.toml"
    path.write_text(text + f"max_spindle_rpm = {rpm}\nmax_feed_mm_min = {feed}\n")
    return str(path)


def test_a_post_s_limits_refuse_speeds_over_them_and_cap_the_arc_feed(tmp_path):
    post = _limited_post(tmp_path, 4000, 930)
    # the steel preset's finish: 4476 rev/min with the Ø16 tool, over 4000
    with pytest.raises(SpecError, match=r"^machining.finish: the steel preset makes 4476 rev/min .* max_spindle_rpm "
                                        r"4000"):
        _spec(tmp_path, DISC, f'post = "{post}"\nflutes = 3\n', drop=("feed", "spindle", "post"))
    with pytest.raises(SpecError, match=r"^machining.spindle: 5000 is over post limited's max_spindle_rpm 4000"):
        _spec(tmp_path, DISC, f'post = "{post}"\nspindle = 5000\n', drop=("post", "spindle"))
    # within the speeds, the rough feed 799 under the post's 930: the spiral's convex arcs (up to 961 unlimited)
    # stop at 930
    spec = _spec(tmp_path, DISC, f'post = "{post}"\nflutes = 3\n[machining.finish]\nrpm = 3500\nfeed_mm_min = 700\n',
                 drop=("feed", "spindle", "post"))
    result = _job(spec)
    arcs = [m.feed_mm_min for p in result.passes for m in p.moves if isinstance(m, ArcMove)]
    assert max(arcs) == 930.0 and sum(f == 930.0 for f in arcs) > 5
