"""The ``[machining]`` table: post, tool, tolerance, feeds and depths of the NC program.

```toml
[machining]
post = "linuxcnc"          # a bundled post, or a path to your own post file
tool_diameter = 16.0       # mm
tolerance = 0.01           # mm, two-sided, on the printed program
mode = "arcs"              # or "lines" (default: arcs; lines for a cylindrical cam, cut in G1 only)
feed = 400.0               # mm/min
spindle = 3000             # rev/min
depth = 12.0               # mm
stepdown = 4.0             # mm
work_offset = "G54"        # G54 … G59, printed in the post's words
coolant = "flood"          # "flood", "mist" or "off"
program_number = 1234      # only for posts that print one (Fanuc, Haas)
flute_length = 32.0        # mm, the tool's cutting length (default: twice its diameter, longer if the cut needs it)
holder_diameter = 40.0     # mm, the tool holder (with stick_out: every move is checked to keep it off the blank)
stick_out = 45.0           # mm, the tool tip to the holder's face
a_axis = "right-hand"      # barrel cams: a positive A turns the part by the right-hand rule about +X
                           # ("left-hand": the machine's positive A turns the part the other way)
accept_out_of_tolerance = false  # true: a FAIL verdict only warns (exit 0)
stepover = 0.4             # roughing: radial step, a fraction of the tool diameter
ramp_angle = 3.0           # deg, steepest descent into material (grooves: ramped entries)
bore = false               # true: cut the bore as a helical bore
dowel = false              # true: cut the dowel hole ([cam] dowel) as a helical bore (a tool of half its
                           # diameter or more, and smaller than it)
units_checked = false      # true: a tolerance over 1 % of the cam's size or a feed under 50 mm/min is meant
                           # (both are refused otherwise: likely µm typed as mm, mm/s or in/min typed as mm/min)
direction = "climb"        # or "conventional": the side of travel the material is on with the M3 spindle
                           # (climb: clockwise round a disc's profile, counter-clockwise round the bore)
flutes = 3                 # the end mill's flutes: turns on cutting data per pass kind (then feed and spindle
                           # are optional), each from its own table, a [cam] material preset, or feed and spindle
axes = 5                   # cylindrical cams: 4 (X A) or 5 (X Y Z A B, tool axis on the roller axis);
                           # default 5 for an oscillating roller, 4 otherwise

[machining.rough]          # and [machining.finish], [machining.spring] (spring: as finish when not given)
vc_m_min = 160.0           # cutting speed, m/min, with
fz_mm = 0.05               # the chip load, mm per flute; or instead rpm = 3000 and feed_mm_min = 450
```

With ``flutes`` and ``[cam] material`` naming steel, cast iron, aluminium or brass, a pass kind
without its own table takes the preset of :mod:`camcam.nc.cutting_data` (figures and sources there).
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

from camcam.errors import InputError, SpecError
from camcam.geometry.followers import follower_kind as follower_class
from camcam.nc.settings import COOLANTS, DIRECTIONS, WORK_OFFSETS, MachiningSpec, ProgramSetup
from camcam.post.post import five_axis_posts, load_post
from camcam.nc.cutting_data import (CUT_KINDS, PRESETS, CuttingData, from_chip_load, from_speed_and_feed,
                                    preset_for)
from camcam.spec.reader import MISSING, Table
from camcam.toolpath.budget import DEFAULT_BUDGET

__all__ = ["MachiningSpec", "read_machining", "FEED_RANGE_MM_MIN", "SPINDLE_RANGE_RPM", "MAX_PASSES",
           "MIN_SIZE_MM", "BREAK_THROUGH_MM", "check_passes",
           "default_axes", "barrel_axes", "PLAUSIBLE_FEED_MM_MIN", "PLAUSIBLE_TOLERANCE_SHARE"]

#: Feeds a milling machine runs (mm/min): below 1 nothing is cut, above 100 m/min no machine feeds.
FEED_RANGE_MM_MIN = (1.0, 100_000.0)

#: Slowest feed taken as millimetres per minute without ``units_checked = true``: a cam's end mill (3-20 mm)
#: cuts at 100-2000 mm/min, which is 1.7-33 in mm/s and 3.9-79 in in/min, so a number under 50 is far more
#: likely one of those than a real feed in mm/min (the 400 mm/min of the samples is 6.7 mm/s, 15.7 in/min).
PLAUSIBLE_FEED_MM_MIN = 50.0

#: Largest tolerance, as a share of the cam's size (the base circle's or cylinder's diameter), taken without
#: ``units_checked = true``: over 1 % it is far more likely microns typed as millimetres (10 for 0.01 mm).
PLAUSIBLE_TOLERANCE_SHARE = 0.01

#: Spindle speeds (rev/min): at least 1 (``S0`` stops the spindle), at most 100 000.
SPINDLE_RANGE_RPM = (1.0, 100_000.0)

#: Most depth passes a program may have (each pass repeats the whole contour).
MAX_PASSES = 1000

#: Smallest tool diameter, depth, step, lead radius (mm): ten times the finest post resolution.
MIN_SIZE_MM = 0.01

#: How far a disc cam's profile may be cut below its thickness (through the part into the fixture plate).
BREAK_THROUGH_MM = 2.0


def check_passes(m: MachiningSpec) -> None:
    """At most :data:`MAX_PASSES` depth passes (checked after ``depth`` itself)."""
    if m.depth_mm / m.stepdown_mm > MAX_PASSES:
        raise SpecError("machining.stepdown", f"{m.stepdown_mm:g} mm makes {math.ceil(m.depth_mm / m.stepdown_mm)} "
                        f"passes for depth = {m.depth_mm:g} mm; at most {MAX_PASSES} are allowed")


def default_axes(cam_kind: str | None, follower_kind: str | None) -> int:
    """Axes a job uses when ``[machining] axes`` is not given: 5 for an oscillating roller on a
    cylindrical cam (its roller axis tilts with the arm), 4 for other cylindrical cams, 3 for discs
    (the first of the follower kind's ``barrel_axes``)."""
    if cam_kind != "cylindrical":
        return 3
    return barrel_axes(follower_kind)[0]


def barrel_axes(kind: str | None) -> tuple[int, ...]:
    """The ``axes`` a cylindrical cam with a follower of ``kind`` may be cut with, the default first."""
    return follower_class(kind).barrel_axes if kind is not None else (4,)


def _feed_units(t: Table, key: str, feed: float, checked: bool) -> None:
    """A feed under :data:`PLAUSIBLE_FEED_MM_MIN` is refused unless ``units_checked``: most likely mm/s or in/min."""
    if checked or feed >= PLAUSIBLE_FEED_MM_MIN:
        return
    meant = [f"if it is {feed:g} {unit} give {feed * factor:.6g}" for unit, factor in (("mm/s", 60.0), ("in/min", 25.4))
             if PLAUSIBLE_FEED_MM_MIN <= feed * factor <= FEED_RANGE_MM_MIN[1]]
    raise t.error(key, f"{feed:g} mm/min is slower than a cam is cut (at least {PLAUSIBLE_FEED_MM_MIN:g} mm/min "
                       f"expected); {', '.join(meant + [''])}or set [machining] units_checked = true if you mean "
                       f"{feed:g} mm/min")


#: Most flutes an end mill has.
MAX_FLUTES = 16

#: Largest chip load taken (mm per flute): no end mill cuts a millimetre per tooth.
MAX_CHIP_LOAD_MM = 1.0

#: Largest cutting speed taken (m/min): carbide in aluminium runs to about 1500.
MAX_CUTTING_SPEED_M_MIN = 3000.0


def _within(t: Table, key: str, value: float, what: str, bounds: tuple[float, float], unit: str) -> None:
    """Refuse a speed or feed that ``key`` makes outside ``bounds``."""
    t.check(key, bounds[0] <= value <= bounds[1], f"makes {what} {value:g} {unit}; expected {bounds[0]:g} to "
                                                  f"{bounds[1]:g} {unit}")


def _kind_data(t: Table, kind: str, flutes: int, tool: float, checked: bool) -> CuttingData:
    """One ``[machining.<kind>]`` table: fz_mm and vc_m_min, or rpm and feed_mm_min."""
    sub = t.table(kind)
    chip = [k for k in ("fz_mm", "vc_m_min") if sub.has(k)]
    direct = [k for k in ("rpm", "feed_mm_min") if sub.has(k)]
    if chip and direct:
        raise sub.error(direct[0], f"give fz_mm and vc_m_min, or rpm and feed_mm_min, not both ({', '.join(chip)} "
                                   f"given too)")
    if direct:
        rpm = sub.number("rpm", minimum=SPINDLE_RANGE_RPM[0], maximum=SPINDLE_RANGE_RPM[1], unit="rev/min")
        feed = sub.number("feed_mm_min", minimum=FEED_RANGE_MM_MIN[0], maximum=FEED_RANGE_MM_MIN[1], unit="mm/min")
        _feed_units(sub, "feed_mm_min", feed, checked)
        sub.done()
        return from_speed_and_feed(kind, rpm=rpm, feed=feed, flutes=flutes, diameter_mm=tool, origin="spec")
    vc = sub.number("vc_m_min", minimum=0.0, maximum=MAX_CUTTING_SPEED_M_MIN, inclusive=False, unit="m/min")
    fz = sub.number("fz_mm", minimum=0.0, maximum=MAX_CHIP_LOAD_MM, inclusive=False, unit="mm")
    sub.done()
    data = from_chip_load(kind, vc_m_min=vc, fz_mm=fz, flutes=flutes, diameter_mm=tool, origin="spec")
    _within(sub, "vc_m_min", data.rpm, f"with the Ø{tool:g} mm tool a spindle speed of", SPINDLE_RANGE_RPM, "rev/min")
    _within(sub, "fz_mm", data.feed_mm_min, f"with {flutes} flutes at {data.rpm:g} rev/min a feed of",
            FEED_RANGE_MM_MIN, "mm/min")
    _feed_units(sub, "fz_mm", data.feed_mm_min, checked)
    return data


def _post_limits(t: Table, post, spindle: float | None, feed: float | None, cutting, tool: float) -> None:
    """Refuse a speed or feed over the post's ``max_spindle_rpm`` or ``max_feed_mm_min`` (when it states them)."""
    for key, value, top, what in (("spindle", spindle, post.max_spindle_rpm, "max_spindle_rpm"),
                                  ("feed", feed, post.max_feed_mm_min, "max_feed_mm_min")):
        if value is not None and top is not None:
            t.check(key, value <= top, f"{value:g} is over post {post.name}'s {what} {top:g}")
    for c in cutting:
        if c.origin in ("feed and spindle", "as finish"):
            continue  # the spindle and feed keys above, or the finish pass's (checked as finish)
        for value, top, what, unit in ((c.rpm, post.max_spindle_rpm, "max_spindle_rpm", "rev/min"),
                                       (c.feed_mm_min, post.max_feed_mm_min, "max_feed_mm_min", "mm/min")):
            if top is not None and value > top:
                how = (f"the {c.origin.removeprefix('preset ')} preset makes" if c.origin.startswith("preset ") else
                       "its figures make")
                raise t.error(c.kind, f"{how} {value:g} {unit} with the Ø{tool:g} mm tool, over post "
                                      f"{post.name}'s {what} {top:g}; give [machining.{c.kind}] rpm and feed_mm_min "
                                      f"within it")


def _cutting_data(t: Table, flutes: int, tool: float, material: str | None, feed: float | None,
                  spindle: float | None, checked: bool) -> tuple[CuttingData, ...]:
    """Rough, finish and spring cutting data: each kind's table, else (spring) the finish's, a material
    preset, or the single feed and spindle."""
    preset, out = preset_for(material), {}
    for kind in CUT_KINDS:
        if t.has(kind):
            out[kind] = _kind_data(t, kind, flutes, tool, checked)
        elif kind == "spring":
            out[kind] = dataclasses.replace(out["finish"], kind="spring", origin="as finish")
        elif preset is not None:
            vc, fz_per_mm = preset.data(kind)
            out[kind] = from_chip_load(kind, vc_m_min=vc, fz_mm=fz_per_mm * tool, flutes=flutes, diameter_mm=tool,
                                       origin=f"preset {preset.name}")
            _within(t, "flutes", out[kind].feed_mm_min, f"with the {preset.name} preset a {kind} feed of",
                    FEED_RANGE_MM_MIN, "mm/min")
        elif feed is not None and spindle is not None:
            out[kind] = from_speed_and_feed(kind, rpm=spindle, feed=feed, flutes=flutes, diameter_mm=tool,
                                            origin="feed and spindle")
        else:
            raise t.error(kind, f"missing; expected [machining.{kind}] with fz_mm and vc_m_min or rpm and "
                                f"feed_mm_min, a [cam] material naming {', '.join(PRESETS)}, or [machining] feed "
                                f"and spindle")
    return tuple(out[k] for k in CUT_KINDS)


def read_machining(t: Table, base: Path, cam_kind: str | None = None, follower_kind: str | None = None,
                   source: str = "", cam_size_mm: float | None = None, material: str | None = None) -> MachiningSpec:
    """Validate ``[machining]``; ``base`` anchors a relative post path; the cam and follower kinds
    decide which ``axes`` values apply (:func:`default_axes`); ``source`` is the spec's file name
    (the program's generator line); ``cam_size_mm`` (the base circle's or cylinder's diameter) bounds
    the tolerance unless ``units_checked = true`` (:data:`PLAUSIBLE_TOLERANCE_SHARE`); ``material`` (``[cam]
    material``) may name a cutting-data preset (:func:`camcam.nc.cutting_data.preset_for`)."""
    checked = t.boolean("units_checked", False)
    name = t.string("post", "linuxcnc")
    try:
        post = load_post(name, base)
    except InputError as err:
        raise t.error("post", str(err)) from None
    tool = t.number("tool_diameter", minimum=MIN_SIZE_MM, unit="mm")
    tol = t.number("tolerance", 0.01, minimum=0.0, inclusive=False, unit="mm")
    need = DEFAULT_BUDGET.floor_mm(post.quantizer)
    t.check("tolerance", tol >= need, f"{tol:g} mm is too fine for post {post.name}'s {post.decimals} decimals; "
            f"expected >= {need:.2g} mm")
    if cam_size_mm is not None and not checked and tol > PLAUSIBLE_TOLERANCE_SHARE * cam_size_mm:
        most = PLAUSIBLE_TOLERANCE_SHARE * cam_size_mm
        raise t.error("tolerance", f"{tol:g} mm is over 1 % of the cam's size (Ø{cam_size_mm:g} mm: at most "
                                   f"{most:g} mm expected); if it is {tol:g} µm give {tol / 1000:g}; or set "
                                   f"[machining] units_checked = true if you mean {tol:g} mm")
    # a barrel cam's program is G1 lines whatever the mode: its default says so (no note for a default never set)
    mode = t.string("mode", "lines" if cam_kind == "cylindrical" else "arcs", choices=("arcs", "lines"))
    # with flutes the cutting data per pass kind may stand in for feed and spindle (cutting_data)
    flutes = t.integer("flutes", None, minimum=1, maximum=MAX_FLUTES)
    optional = None if flutes is not None else MISSING
    feed = t.number("feed", optional, minimum=FEED_RANGE_MM_MIN[0], maximum=FEED_RANGE_MM_MIN[1], unit="mm/min")
    if feed is not None:
        _feed_units(t, "feed", feed, checked)
    spindle = t.number("spindle", optional, minimum=SPINDLE_RANGE_RPM[0], maximum=SPINDLE_RANGE_RPM[1],
                       unit="rev/min")
    cutting = ()
    if flutes is not None:
        cutting = _cutting_data(t, flutes, tool, material, feed, spindle, checked)
        feed = cutting[1].feed_mm_min if feed is None else feed  # the finish pass's
        spindle = cutting[1].rpm if spindle is None else spindle
    else:
        for kind in CUT_KINDS:
            t.check(kind, not t.has(kind), "needs [machining] flutes (the chip load is per flute)")
    _post_limits(t, post, spindle if t.has("spindle") else None, feed if t.has("feed") else None, cutting, tool)
    depth = t.number("depth", minimum=MIN_SIZE_MM, unit="mm")
    stepdown = t.number("stepdown", depth, minimum=MIN_SIZE_MM, unit="mm")
    slowest = min([feed] + [c.feed_mm_min for c in cutting])  # with cutting data: half the slowest pass's feed
    plunge = t.number("plunge_feed", max(slowest / 2, FEED_RANGE_MM_MIN[0]), minimum=FEED_RANGE_MM_MIN[0],
                      maximum=FEED_RANGE_MM_MIN[1], unit="mm/min")
    if t.has("plunge_feed"):  # a default (half the feed) is not the user's number
        _feed_units(t, "plunge_feed", plunge, checked)
    clearance = t.number("clearance_z", 2.0, minimum=MIN_SIZE_MM, unit="mm")
    safe = t.number("safe_z", 25.0, minimum=clearance, unit="mm")
    lead = t.number("lead_radius", max(tool / 2, 1.0), minimum=MIN_SIZE_MM, unit="mm")
    allowance = t.number("finish_allowance", 0.0, minimum=0.0, unit="mm")
    spring = t.boolean("spring_pass", False)
    tool_number = t.integer("tool_number", 1, minimum=1, maximum=999)
    accept = t.boolean("accept_out_of_tolerance", False)
    flute = t.number("flute_length", None, minimum=0.0, inclusive=False, unit="mm")
    # unstated: twice the tool's diameter, longer where the cut needs it (MachiningSpec.flute_for)
    flute_stated, flute = flute is not None, flute if flute is not None else 2.0 * tool
    a_axis = t.string("a_axis", "right-hand", choices=("right-hand", "left-hand"))
    holder = t.number("holder_diameter", None, minimum=0.0, inclusive=False, unit="mm")
    stick_out = t.number("stick_out", None, minimum=0.0, inclusive=False, unit="mm")
    for key, given, other in (("holder_diameter", holder, "stick_out"), ("stick_out", stick_out, "holder_diameter")):
        if given is not None:
            t.check(key, holder is not None and stick_out is not None,
                    f"{given:g} mm needs [machining] {other} too: the holder is checked against the blank with both")
    axes = default_axes(cam_kind, follower_kind)
    if t.has("axes"):
        if cam_kind != "cylindrical":
            raise t.error("axes", "applies to cylindrical cams only (a disc cam is cut with 3 axes)")
        allowed = barrel_axes(follower_kind)
        axes = t.integer("axes", minimum=4, maximum=5)
        t.check("axes", axes in allowed, f"expected 4 for a {follower_kind} follower (its roller axis stays radial, "
                f"so B would stay 0), got {axes}")
    if axes == 5:
        t.check("post", post.five_axis, f"post {post.name} has no 5-axis mode (tool-centre-point control); "
                f"use a post with one ({', '.join(five_axis_posts())}) or axes = 4")
    stepover = t.number("stepover", 0.4, minimum=0.0, maximum=1.0, inclusive=False)
    ramp = t.number("ramp_angle", 3.0, minimum=0.0, maximum=45.0, inclusive=False, unit="deg")
    bore = t.boolean("bore", False)
    dowel = t.boolean("dowel", False)
    if dowel and cam_kind == "cylindrical":
        raise t.error("dowel", "applies to disc cams only (a cylindrical cam has no dowel hole)")
    direction = t.string("direction", DIRECTIONS[0], choices=DIRECTIONS)
    work_offset = t.string("work_offset", "G54", choices=WORK_OFFSETS)
    coolant = t.string("coolant", "flood", choices=COOLANTS)
    setup = ProgramSetup(work_offset, coolant, t.integer("program_number", None, minimum=1), source)
    try:
        setup.check(post)
    except InputError as err:
        key, _, message = str(err).partition(": ")
        raise t.error(key, message) from None
    t.done()
    return MachiningSpec(post=post, tool_diameter_mm=tool, tolerance_mm=tol, mode=mode, feed_mm_min=feed,
                         spindle_rpm=spindle, depth_mm=depth, stepdown_mm=stepdown, plunge_feed_mm_min=plunge,
                         safe_z_mm=safe, clearance_z_mm=clearance, lead_radius_mm=lead,
                         finish_allowance_mm=allowance, spring_pass=spring, tool_number=tool_number,
                         accept_out_of_tolerance=accept, setup=setup, flute_length_mm=flute, flute_stated=flute_stated,
                         a_axis=a_axis,
                         stepover=stepover, ramp_angle_deg=ramp, bore=bore, dowel=dowel, axes=axes,
                         direction=direction, holder_diameter_mm=holder, stick_out_mm=stick_out, cutting=cutting)
