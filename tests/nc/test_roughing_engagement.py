"""Roughing holds its own engagement limit (issue 43 A): on a cam whose profile bends inward, at every stepover,
and over seeded random translating-roller disc cams, measured by the material check's own sweep."""

import math
import random
from dataclasses import replace
from pathlib import Path

import pytest
import shapely

from camcam.geometry.build import build_cam
from camcam.verify import checked
from camcam.verify.removal import RemovalReport
from camcam.nc.roughing import disc_spiral
from camcam.nc.stock import blank_for
from camcam.verify.swept import Move, sweep_slabs
from camcam.report.setup_sheet import setup_blocks
from camcam.spec import load_spec
from camcam.toolpath.elements import Line

NOTCH = Path(__file__).parent / "data" / "rough-concave-notch.toml"


def _built(spec):
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))


def spiral_engagement(spec, stepover=None):
    """(largest engagement of the roughing spiral alone against the blank, the limit, turns): the check's sweep
    (camcam.verify.swept) over the spiral's own moves at one level."""
    m = spec.machining if stepover is None else replace(spec.machining, stepover=stepover)
    built = _built(spec)
    blank = blank_for(built, spec.stock, m.tool_diameter_mm, m.bore)
    r_t = m.tool_diameter_mm / 2
    sp = disc_spiral(blank.part, blank.region, r_t, m.finish_allowance_mm, m.stepover_mm,
                     clockwise=spec.cam.rotation == "cw", max_sweep_deg=m.post.max_arc_sweep_deg)
    z = -1.0
    s = sp.elements[0].start
    moves = [Move("line", (*sp.entry, z), (*s, z), centre=None, ccw=False, pass_kind="rough", pass_label="rough")]
    for e in sp.elements:
        kind, centre, ccw = ("line", None, False) if isinstance(e, Line) else ("arc", e.centre, e.ccw)
        moves.append(Move(kind, (*e.start, z), (*e.end, z), centre=centre, ccw=ccw, pass_kind="rough",
                          pass_label="rough"))
    swept = sweep_slabs(moves, [shapely.Polygon(blank.region)], [0.0, z], r_t, math.tan(math.radians(3.0)), 2e-4)
    return swept.engagement_mm, m.stepover_mm, sp


def test_concave_notch_program_holds_the_stepover():
    spec = load_spec(NOTCH)
    result = checked(_built(spec), spec.machining, spec.name, spec.stock)
    r = result.removal
    assert r.max_engagement_mm <= r.stepover_mm  # was 7.28 mm of 6.4 (exit 3)
    assert all(c.ok for c in result.checks)
    # the pass comment and the pass record say how the spiral is planned
    rough = [p for p in result.passes if p.kind == "rough"]
    assert rough and all(p.note.startswith("spiral ") and "turns" in p.note for p in rough)
    assert f"rough, profile, Z{rough[0].z:g}, climb, {rough[0].note}" in result.program.text
    table = setup_blocks(_built(spec), result, spec.machining)[2]
    plan = table.header.index("plan")
    assert [row[plan] for row in table.rows if row[1] == "rough"] == [p.note for p in rough]


@pytest.mark.parametrize("stepover", [0.4, 0.2, 0.1])
def test_lowering_the_stepover_lowers_the_engagement(stepover):
    # before: 7.59 of 6.4, 4.49 of 3.2, 2.73 of 1.6 (the excess grew as the stepover fell)
    e, limit, _ = spiral_engagement(load_spec(NOTCH), stepover)
    assert e <= limit


LAWS = ("modified-sine", "cycloidal", "modified-trapezoid", "harmonic", "polynomial-345")


def random_disc_spec(seed: int, stepover: float = 0.4) -> str:
    """A translating-roller disc cam drawn over the issue's ranges (rise 2-50 mm, base radius 15-160 mm, roller
    radius 2-20 mm, tool 6-16 mm, tolerance 0.002-0.05 mm, cw or ccw) with a round [stock] blank."""
    r = random.Random(seed)
    rise = round(r.uniform(2, 50), 2)
    base = round(r.uniform(15, 160), 1)
    roller = round(r.uniform(2, 20), 2)
    tool = round(r.uniform(6, 16), 1)
    tol = round(10 ** r.uniform(math.log10(0.002), math.log10(0.05)), 4)
    rot = r.choice(["cw", "ccw"])
    a1, d1, a2 = r.choice([90, 120, 150]), r.choice([30, 60]), r.choice([90, 120, 150])
    if a1 + d1 + a2 > 350:
        a2 = 350 - a1 - d1
    end = a1 + d1 + a2
    offset = round(r.uniform(-0.2, 0.2) * base, 1)
    thick = round(r.uniform(8, 20), 1)
    law1, law2 = r.choice(LAWS), r.choice(LAWS)
    return f"""name = "random{seed}"
[motion]
rpm = 100
segments = [
  {{ law = "{law1}", from = 0, to = {a1}, rise = {rise} }},
  {{ law = "dwell", from = {a1}, to = {a1 + d1} }},
  {{ law = "{law2}", from = {a1 + d1}, to = {end}, rise = {-rise} }},
  {{ law = "dwell", from = {end}, to = 360 }},
]
[cam]
kind = "disc"
base_radius = {base}
thickness = {thick}
rotation = "{rot}"
[follower]
kind = "translating-roller"
roller_radius = {roller}
offset = {offset}
[stock]
kind = "round"
diameter = {round(2 * (base + rise + r.uniform(2, 15)), 1)}
[machining]
post = "linuxcnc"
tool_diameter = {tool}
tolerance = {tol}
mode = "arcs"
feed = 400.0
spindle = 3000
depth = {thick}
stepdown = {round(thick / 2, 2)}
finish_allowance = 0.3
stepover = {stepover}
"""


# seeds of the generator: cams that bend inward (15, 22, 42, 52, 140, 195, 352: before issue 43 their
# spirals met 1.19, 1.19, 1.15, 1.29, 1.08, 1.13 and 1.20 × the stepover at stepover 0.4) and convex ones;
# some at a finer stepover, where the excess grew
CASES = [(22, 0.4), (52, 0.4), (352, 0.4), (15, 0.4), (140, 0.4), (195, 0.4), (42, 0.4), (1, 0.4), (5, 0.4),
         (352, 0.1), (140, 0.1), (2, 0.1)]


@pytest.mark.parametrize("seed, stepover", CASES)
def test_random_cams_hold_the_engagement_limit(tmp_path, seed, stepover):
    f = tmp_path / "cam.toml"
    f.write_text(random_disc_spec(seed, stepover))
    try:
        spec = load_spec(f)
    except Exception as err:  # the generator may draw a cam the spec refuses; that is not this test's case
        pytest.skip(f"spec refused: {err}")
    e, limit, sp = spiral_engagement(spec)
    assert e <= limit
    assert e > 0.5 * limit  # and the spiral really cuts at about the step


@pytest.mark.parametrize("where, advice", [
    ("pass 3/4: finish, profile, Z-12 at X1.000 Y2.000 Z-12.000", "lower [machining] finish_allowance or use a smaller tool"),
    ("pass 1/4: rough, profile, Z-6, spiral 9 turns at most 5.72 mm apart at X1.000 Y2.000 Z-6.000",
     "lower [machining] stepover (the roughing should have held it"),
])
def test_engagement_advice_names_the_passes_own_way_out(where, advice):
    # a finishing pass's engagement comes from the allowance wrapping round the tool in a concave corner: a
    # lower stepover (the old advice for every pass) changes nothing there
    r = RemovalReport(tool_radius_mm=8.0, stepover_mm=6.4, ramp_angle_deg=3.0, tolerance_mm=0.01, allowance_mm=0.3,
                      levels=(-6.0, -12.0), passes=4, max_engagement_mm=7.0, engagement_where=where,
                      max_slot_engagement_mm=0.0, plunges=0, plunge_where="", rapid_touches=0, rapid_where="",
                      material_left_mm=0.0, left_where="", overcut_mm=0.0, overcut_where="",
                      rough_clearance_mm=0.35, rough_clearance_where="")
    check = {c.name: c for c in r.checks()}["radial engagement"]
    assert not check.ok and advice in check.advice
