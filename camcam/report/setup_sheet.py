"""The setup sheet: what the machinist needs at the machine, from the values the stages returned.

Blank (size and material), work zero, angular datum, tool (T, length offset, diameter, flute
length), the passes (the program's :class:`~camcam.toolpath.path.Pass` records),
work offset, coolant and cycle time.  The report puts it right after the
verdict.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.followers import follower_kind
from camcam.nc.cutting_data import PRESETS
from camcam.nc.feeds import MIN_ENGAGEMENT_FACTOR, engagement_factor
from camcam.nc.result import MachiningResult
from camcam.verify.reach import flute_text
from camcam.report.html import DataTable, Drawing, KeyValues
from camcam.report.setup_picture import setup_picture

__all__ = ["setup_blocks"]


def _blank_rows(built, r: MachiningResult) -> list[tuple[str, str]]:
    """The blank's size (what goes into the vice or chuck) and the part's material."""
    spec = built.spec
    if r.blank is not None:
        b = r.blank
        size = (f"{b.describe()}, {spec.thickness + b.top_z_mm:g} mm thick"
                + (f" ({b.top_z_mm:g} mm face stock above Z0)" if b.top_z_mm > 0 else ""))
    elif r.rotary:
        size = (f"round bar turned to Ø{2 * built.cam.base_radius:g} × {built.cam.length:g} mm (the cam's cylinder; "
                f"the program cuts only the groove)")
    else:
        size = "not modelled for this job"
    material = spec.material or "not stated (give [cam] material)"
    return [("blank", size), ("material", material)]


def _blank_and_zero(built, r: MachiningResult) -> list[tuple[str, str]]:
    spec, cam = built.spec, built.cam
    v = built.mesh_parts.vertices
    if r.rotary:
        return [("part", f"cylinder Ø{2 * cam.base_radius:g} × {cam.length:g} mm"
                 + (f", bore Ø{spec.bore:g} mm" if spec.bore else "")), *_blank_rows(built, r),
                ("work zero", "X0 on the cam's left end face, Y0 Z0 on the cam axis; A turns the part about +X "
                              "(A0 = cam angle 0)")]
    r_max = float(np.hypot(v[:, 0], v[:, 1]).max())
    what = "cam" if spec.kind == "disc" else "grooved disc"
    rows = [("part", f"{what} Ø{2 * r_max:.2f} × {spec.thickness:g} mm (largest radius {r_max:.3f} mm)"
             + (f", bore Ø{spec.bore:g} mm (not machined by this program)" if spec.bore else "")),
            *_blank_rows(built, r),
            ("work zero", f"X0 Y0 on the cam axis (the bore centre), Z0 on the top face; the part lies below, "
                          f"Z −{spec.thickness:g} … 0 (the STL and the DXF share this frame)")]
    return rows


def _datum(built, r: MachiningResult) -> str:
    cam = built.cam
    p0 = cam.profile.evaluate(np.array([cam.profile.t_start]))[0]
    ang = math.degrees(math.atan2(p0[1], p0[0])) % 360.0
    # a face groove's cam has no follower of its own: X0 (its offset is the inner cam's, cam.cam.follower)
    where = follower_kind(cam.kind).datum_note(getattr(getattr(cam, "follower", None), "offset", 0.0))
    turn = "counter-clockwise" if cam.rotation == "ccw" else "clockwise"
    k, d = built.spec.keyway, built.spec.dowel
    clamp = "; ".join(
        ([f"Clamp the part by its keyway, {k.width:g} mm wide and {k.depth:g} mm deep in the Ø"
          f"{built.spec.bore:g} mm bore, its centre line at {k.angle_deg % 360:g}° from +X, "
          f"{(k.angle_deg - ang) % 360:.2f}° counter-clockwise from the cam-angle-0 line (DXF layer KEYWAY), not "
          f"cut by this program (an end mill would leave its radius in the keyway's square corners: broach or "
          f"wire-erode it after the bore)"]
         if k is not None else [])
        + ([f"Locate the part on its dowel hole, Ø{d.diameter:g} mm through the cam, its centre at radius "
            f"{d.radius:g} mm, {d.angle_deg % 360:g}° from +X, {(d.angle_deg - ang) % 360:.2f}° counter-clockwise "
            f"from the cam-angle-0 line (DXF layer DOWEL)" + (
                ", cut by this program as a helical bore ([machining] dowel = true)"
                if r.blank is not None and r.blank.dowel is not None else
                ", not cut by this program (drill and ream it, or set [machining] dowel = true with a tool of at "
                "least half its diameter)")] if d is not None else [])) or (
        "Clamp the part with its keyway or dowel where the drawing puts it relative to that line")
    return (f"program and drawing show the cam at cam angle 0: {where}; the cam-angle-0 contact point lies at "
            f"{ang:.2f}° from +X (DXF layer ANGLE-ZERO, X0 Y0 through that point). {clamp}; in service the cam "
            f"turns {turn}.")


def _direction_text(direction: str, passes) -> str:
    """The milling direction asked for and how the passes hold it (:mod:`camcam.nc.direction`)."""
    both = sum(p.direction == "both" for p in passes)
    return (f"{direction} milling (the material {'right' if direction == 'climb' else 'left'} of travel)"
            + (f", {both} full-width pass{'es' if both > 1 else ''} both sides" if both else ""))


def setup_blocks(built, r: MachiningResult, machining) -> tuple:
    """The part on the machine (a drawing), KeyValues of the setup and a table of the passes, in cutting order
    (``machining``: the spec's table)."""
    post, setup, spindle_rpm = r.post, machining.setup, machining.spindle_rpm
    tool = r.toolpath.tool_number
    passes = r.toolpath.passes
    top = r.reference_radius_mm if r.rotary and r.reference_radius_mm else 0.0
    depth = max((top - p.z for p in passes), default=0.0) if not r.rotary else machining.depth_mm
    rows = _blank_and_zero(built, r)
    if not r.rotary:
        rows.append(("angular datum", _datum(built, r)))
    else:
        rows.append(("angular datum", "A0 is cam angle 0: the developed drawing's u = 0 line (DXF layer ANGLE-ZERO)"))
    number = setup.program_number if setup.program_number is not None else post.program_number
    offset_words = " / ".join(s.strip() for s in post.work_offset_lines(setup.work_offset))
    rows += [
        ("program", f"{r.program_filename} (post {post.name}" + (f", program number {number}" if post.uses_program_number
                                                               else "") + ")"),
        ("work offset", f"{setup.work_offset}: {offset_words}"),
        ("tool", f"T{tool}, Ø{r.tool_diameter_mm:g} mm flat end mill, "
                 + (flute_text(r.reach) if r.reach is not None
                    else f"flute length ≥ {depth:g} mm (deepest pass {depth:g} mm below the top)")
                 + (f"; holder Ø{machining.holder_diameter_mm:g} mm at stick-out {machining.stick_out_mm:g} mm "
                    f"(clear of the blank at every move)" if machining.stick_out_mm is not None else "")),
        ("tool length offset", post.length_offset_text(tool)),
        ("spindle", f"{spindle_rpm:g} rev/min clockwise; {_direction_text(machining.direction, passes)}")
        if not machining.cutting else ("cutting data", f"{_direction_text(machining.direction, passes)}; "
                                                       f"{_cutting_text(machining)}"),
        ("coolant", f"{setup.coolant} ({post.coolant_word(setup.coolant)} on, {post.coolant_off} off)"),
        ("cycle time (estimate)", f"{r.program.cycle_time.describe()}; rapids at {post.rapid_mm_min:g} mm/min, "
                                  f"tool change {post.tool_change_s:g} s, acceleration not counted"),
    ]
    motion = r.program.motion_time
    if motion is not None:
        rows.append(("cycle time with acceleration", f"{motion.describe()}: trapezoidal moves, GRBL's cornering rule, "
                                                     f"the post's limits (docs/machine-ready.md)"))
    n = len(passes)
    # per pass: feed-only and motion-model seconds, when the program's pass comments split them (one per pass)
    timed = motion is not None and len(motion.passes) == n + 1
    times = [(f"{t.feed_only_s:.1f}", f"{t.model_s:.1f}") for t in motion.passes[1:]] if timed else [("", "")] * n
    # "plan": how a pass is planned where its kind does not say it (a roughing spiral's turns, Pass.note)
    table = DataTable(("pass", "kind", "contour", "Z", "feed mm/min", "spindle rev/min", "feed-only s",
                       "with acceleration s", "plan"),
                      tuple((f"{i + 1}/{n}", p.kind, r.contours[p.contour].label, f"{p.z:g}",
                             *_pass_speeds(machining, p), *times[i], p.note)
                            for i, p in enumerate(passes)),
                      "The passes in cutting order (each opens with a comment naming it in the program); their "
                      "times, feed-only and with acceleration, leave out the start (tool change and approach)"
                      + (f": {motion.passes[0].feed_only_s:.1f} s and {motion.passes[0].model_s:.1f} s." if timed else "."))
    picture = setup_picture(built, r, machining)
    return (Drawing(picture.svg, picture.caption), KeyValues(tuple(rows)), table)


def _pass_speeds(machining, p) -> tuple[str, str]:
    """A pass's (feed, spindle) as the pass table shows them: its kind's cutting data (arcs: at the edge)."""
    data = machining.cutting_for(p.kind)
    if data is None:
        return f"{machining.feed_mm_min:g}", f"{machining.spindle_rpm:g}"
    return f"{round(data.feed_mm_min * engagement_factor(p.kind, machining.stepover)):g}", f"{data.rpm:g}"


def _cutting_text(machining) -> str:
    """Each pass kind's cutting data and its source, in one row (:mod:`camcam.nc.cutting_data`)."""
    def source(c) -> str:
        if c.origin.startswith("preset "):
            return f"{c.origin}: {PRESETS[c.origin.removeprefix('preset ')].source}"
        return {"spec": f"[machining.{c.kind}]", "feed and spindle": "[machining] feed and spindle",
                "as finish": "as finish"}[c.origin]

    kinds = "; ".join(f"{c.kind} vc {c.vc_m_min:.4g} m/min, fz {c.fz_mm:.4g} mm × {c.flutes}: S{c.rpm:g} "
                      f"F{c.feed_mm_min:g} ({source(c)})" for c in machining.cutting)
    return (f"S printed at each pass; {kinds}; slot and bore at F × max(stepover, {MIN_ENGAGEMENT_FACTOR:g}); "
            f"arcs: the edge at F")
