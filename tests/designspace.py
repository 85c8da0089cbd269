"""The design-space campaign (issue 43): seeded random valid specs, run, classified, advice followed.

A *case* is drawn deterministically from ``(seed, index)`` (:func:`draw_case`): a disc cam with each of
the four follower kinds, a face-groove disc cam, or a barrel cam (translating roller on 4 axes,
oscillating roller on 4 or 5 axes), on every post that supports the job (4-axis barrels need G93 —
not Heidenhain's Klartext; 5-axis needs tool-centre-point control — not GRBL), cw or ccw, with or
without ``[stock]``, with segment layouts of random laws from :data:`camcam.motion.catalog.LAWS`
(now and then dwell-only or a tiny rise).  Sizes are the ones a user would write: base radius
15–160 mm, rise 2–50 mm (swing angles for oscillating followers from the same lift over the arm),
rollers 4–20 mm, tools 6–16 mm (a groove's tool is often the roller's diameter), tolerance
0.002–0.05 mm.  A drawn combination may still be impossible (an undercut, a tool too large for a
concave part): then exit 2 with its advice is the right answer.

:func:`run_case` writes the spec into a folder, runs ``python -m camcam run SPEC -o OUT`` and
records the exit status, the stderr lines and their cause (:func:`classify`).  An exit-0 disc
program on a post LinuxCNC's ``rs274`` reads (linuxcnc, fanuc, haas, grbl) is read back by it
(:func:`camcam.verify.rs274.run_rs274`) and every finishing pass — found by the pass comment the
program prints (``pass i/n: kind, contour, Z…``) — is measured both ways
(:func:`camcam.toolpath.deviation.measure_deviation`) against the exact tool-centre curve rebuilt
here from the spec (the profile offset by the tool radius, the pitch curve or a flank offset), not
taken from camcam's own result.  A barrel program is measured by the report's 3-D groove figure
(``verdict.checks["3-D groove deviation"]`` of ``report.json``), and rs274 (through
:func:`camcam.verify.rs274.tcp_readable` on 5 axes) must accept it.  An exit 2 or 3 whose line names
``section.key`` with a value is followed (:func:`parse_advice`): the value is put into the spec and the
run repeated, at most :data:`ADVICE_STEPS` times.

``benchmarks/anycam.py`` runs many cases in a process pool and prints the tallies;
``tests/test_anycam.py`` holds a fixed subset to the issue's targets.
"""

from __future__ import annotations

import json
import math
import os
import random
import re
import resource
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Motion laws a case draws from (``camcam laws``), kept literal so cases do not move when a law is added.
LAWS = ("cycloidal", "harmonic", "polynomial-345", "polynomial-4567", "modified-trapezoid", "modified-sine",
        "modified-constant-velocity", "parabolic", "yu-lee")
POSTS = ("linuxcnc", "fanuc", "haas", "grbl", "sinumerik", "heidenhain")
#: Posts for a 4-axis barrel program: inverse-time feed (G93) needed; Heidenhain's Klartext post has none.
POSTS_4AXIS = ("linuxcnc", "fanuc", "haas", "grbl", "sinumerik")
#: Posts for a 5-axis barrel program: tool-centre-point control needed; GRBL has none.
POSTS_5AXIS = ("linuxcnc", "fanuc", "haas", "sinumerik", "heidenhain")
#: Dialects LinuxCNC's rs274 interprets (Sinumerik's G71 and Heidenhain's Klartext it cannot read).
RS274_READS = ("linuxcnc", "fanuc", "haas", "grbl")
#: Families and their weights in a draw.
FAMILIES = {"disc-translating-roller": 12, "disc-translating-flat": 9, "disc-oscillating-roller": 10,
            "disc-oscillating-flat": 9, "disc-groove": 14, "barrel-translating": 16,
            "barrel-oscillating-4axis": 8, "barrel-oscillating-5axis": 16}
#: Most advice-following reruns after the first run.
ADVICE_STEPS = 2
RUN_TIMEOUT_S = 600.0


# --------------------------------------------------------------------------------------------- the draw

@dataclass(frozen=True)
class Case:
    seed: int
    index: int
    family: str
    spec: dict

    @property
    def key(self) -> str:
        return f"{self.seed}:{self.index}"

    @property
    def post(self) -> str:
        return self.spec["machining"]["post"]

    def toml(self) -> str:
        return to_toml(self.spec)


def _r(x: float, nd: int = 2) -> float:
    return float(round(x, nd))


def _logu(rng: random.Random, lo: float, hi: float) -> float:
    return math.exp(rng.uniform(math.log(lo), math.log(hi)))


def _spans(rng: random.Random, minima: list[float]) -> list[int]:
    """Integer angle spans, each at least its minimum, summing to 360."""
    spare = 360 - sum(minima)
    w = [rng.expovariate(1.0) for _ in minima]
    spans = [int(m + spare * x / sum(w)) for m, x in zip(minima, w)]
    spans[-1] += 360 - sum(spans)
    return spans


def _law(rng: random.Random) -> str:
    return rng.choice(LAWS)


def draw_segments(rng: random.Random, lift: float, nd: int = 3) -> tuple[list[dict], str]:
    """A segment layout over 0–360° whose lifts sum to 0, and its shape's name.  ``lift`` is the largest
    lift (mm, or degrees for an oscillating follower)."""
    shape = rng.choices(["rise-dwell-return-dwell", "rise-return", "rise-dwell-return", "two-step",
                         "two-lobes", "dwell-only", "tiny-rise"], [34, 14, 12, 14, 10, 6, 10])[0]
    if shape == "dwell-only":
        return [{"law": "dwell", "from": 0, "to": 360}], shape
    if shape == "tiny-rise":
        lift = _r(rng.uniform(0.01, 0.3) * (lift / max(lift, 1e-9)), nd)
        shape_moves = [("move", lift), ("dwell", 0), ("move", -lift), ("dwell", 0)]
    elif shape == "rise-dwell-return-dwell":
        shape_moves = [("move", lift), ("dwell", 0), ("move", -lift), ("dwell", 0)]
    elif shape == "rise-return":
        shape_moves = [("move", lift), ("move", -lift)]
    elif shape == "rise-dwell-return":
        shape_moves = [("move", lift), ("dwell", 0), ("move", -lift)]
    elif shape == "two-step":
        a = _r(lift * rng.uniform(0.3, 0.7), nd)
        shape_moves = [("move", a), ("dwell", 0), ("move", _r(lift - a, nd)), ("dwell", 0), ("move", -lift),
                       ("dwell", 0)]
    else:  # two lobes
        b = _r(lift * rng.uniform(0.4, 1.0), nd)
        shape_moves = [("move", lift), ("move", -lift), ("dwell", 0), ("move", b), ("move", -b), ("dwell", 0)]
    if rng.random() < 0.5:  # start elsewhere in the cycle, where the follower is down (no lift below 0)
        level, bottoms = 0.0, []
        for k, (_, rise) in enumerate(shape_moves):
            if abs(level) < 1e-9:
                bottoms.append(k)
            level += rise
        k = rng.choice(bottoms)
        shape_moves = shape_moves[k:] + shape_moves[:k]
    minima = [30.0 if kind == "move" else 10.0 for kind, _ in shape_moves]
    spans = _spans(rng, minima)
    segs, at = [], 0
    for (kind, rise), span in zip(shape_moves, spans):
        seg = {"law": "dwell" if kind == "dwell" else _law(rng), "from": at, "to": at + span}
        if kind == "move":
            seg["rise"] = rise
        segs.append(seg)
        at += span
    return segs, shape


def _machining(rng: random.Random, post: str, tool: float, depth: float, *, mode: str | None = None,
               quick: bool = False) -> dict:
    tol = _logu(rng, 0.02 if quick else 0.002, 0.05)
    tol = float(f"{tol:.2g}")
    m = {"post": post, "tool_diameter": tool, "tolerance": tol,
         "mode": mode or rng.choices(["arcs", "lines"], [80, 20])[0],
         "feed": float(rng.choice([150, 200, 250, 300, 400, 500, 600, 800])),
         "spindle": rng.choice([1200, 2000, 2500, 3000, 4000, 6000]),
         "depth": _r(depth, 2)}
    passes = rng.choice([1, 2] if quick else [1, 1, 2, 2, 3, 4])
    m["stepdown"] = _r(math.ceil(depth / passes * 100) / 100, 2)
    return m


def draw_case(seed: int, index: int, families: tuple[str, ...] | None = None, quick: bool = False) -> Case:
    """The case ``index`` of campaign ``seed`` (the same spec for the same pair, on any machine).

    ``families`` limits the draw to those families; ``quick`` draws smaller cams (base radius up to 45 mm,
    rise up to 15 mm, thickness up to 12 mm, at most 2 depth passes) at looser tolerances (0.02–0.05 mm),
    for a test that must run fast.
    """
    rng = random.Random(f"anycam:{seed}:{index}{':quick' if quick else ''}")
    names = [f for f in FAMILIES if families is None or f in families]
    family = rng.choices(names, [FAMILIES[f] for f in names])[0]
    rotation = rng.choice(["ccw", "cw"])
    base = _r(_logu(rng, 15.0, 45.0 if quick else 160.0), 1)
    lift_mm = _r(_logu(rng, 2.0, 15.0 if quick else 50.0), 2)
    rpm = rng.choice([30, 60, 100, 120, 200, 300])
    spec: dict = {"name": f"case-{seed}-{index}"}
    if family.startswith("disc"):
        _disc(rng, spec, family, base, lift_mm, rotation, rpm, quick)
    else:
        _barrel(rng, spec, family, base, lift_mm, rotation, rpm, quick)
    _options(random.Random(f"anycam-options:{seed}:{index}{':quick' if quick else ''}"), spec)
    return Case(seed, index, family, spec)


def _options(rng: random.Random, spec: dict) -> None:
    """The options a user adds to a cam (a helical bore, a dowel hole cut or not, a keyway), drawn from a
    stream of their own so that every case keeps the cam, motion and machining it was drawn with before."""
    cam, m = spec["cam"], spec["machining"]
    if cam["kind"] == "cylindrical":
        return
    tool = m["tool_diameter"]
    rr = spec["follower"].get("roller_radius", 0.0)
    room = cam["base_radius"] - rr - 1.0  # the bore must stay inside the base circle minus the roller
    if "bore" in cam and rng.random() < 0.25:
        bore = _r(tool * rng.uniform(1.15, 1.85), 1)  # a tool of at least half the bore and smaller than it
        if bore / 2 < room:
            cam["bore"], m["bore"] = bore, True
    if "bore" in cam and rng.random() < 0.15:
        width, depth = _r(cam["bore"] * rng.uniform(0.2, 0.45), 1), _r(cam["bore"] * rng.uniform(0.1, 0.3), 1)
        if math.hypot(width / 2, cam["bore"] / 2 + depth) < cam["base_radius"] - 1.0 and width >= 0.5 and depth >= 0.5:
            cam["keyway"] = {"width": width, "depth": depth, "angle": float(rng.choice([0, 90, 135, 270]))}
    if cam["kind"] == "disc" and rng.random() < 0.2:
        cut = rng.random() < 0.5
        diameter = _r(tool * rng.uniform(1.15, 1.85) if cut else rng.uniform(3.0, 10.0), 1)
        k = cam.get("keyway")
        inner = (cam.get("bore", 0.0) / 2 if k is None
                 else math.hypot(k["width"] / 2, cam["bore"] / 2 + k["depth"]))
        lo, hi = inner + diameter / 2 + 1.0, cam["base_radius"] - diameter / 2 - 1.0
        if lo < hi:
            cam["dowel"] = {"diameter": diameter, "radius": _r(rng.uniform(lo, hi), 1),
                            "angle": float(rng.choice([0, 45, 90, 200, 300]))}
            if cut:
                m["dowel"] = True


def _tool(rng: random.Random, hi: float = 16.0) -> float:
    return float(rng.choice([x for x in (6, 8, 10, 12, 14, 16) if x <= hi] or [6]))


def _disc(rng, spec, family, base, lift_mm, rotation, rpm, quick=False) -> None:
    thickness = _r(rng.uniform(5.0, 12.0 if quick else 30.0), 1)
    cam = {"kind": "disc", "base_radius": base, "thickness": thickness, "rotation": rotation}
    if rng.random() < 0.7:
        cam["bore"] = _r(base * rng.uniform(0.2, 0.6), 1)
    fol: dict
    rr = 0.0
    if family == "disc-groove":
        cam["kind"] = "disc-groove"
        fol = {"kind": "translating-roller"}
        # a tool of the roller's diameter: one centre pass
        rr, tool = _groove_roller_and_tool(rng, rng.random() < 0.6)
        fol["roller_radius"] = rr
        if rng.random() < 0.4:
            fol["offset"] = _r(rng.uniform(-0.3, 0.3) * base, 1)
        cam["groove_depth"] = _r(rng.uniform(0.25, 0.7) * thickness, 1)
        cam["thickness"] = thickness
        if "bore" in cam:
            cam["bore"] = _r(min(cam["bore"], base), 1)
        unit_lift = lift_mm
        depth = cam["groove_depth"]
    else:
        kind = family[len("disc-"):]
        fol = {"kind": kind}
        tool = _tool(rng)
        if kind.endswith("roller"):
            rr = _r(rng.uniform(4.0, min(20.0, max(4.0, 0.8 * base))), 1)
            fol["roller_radius"] = rr
        if kind.startswith("translating"):
            if rng.random() < 0.4:
                fol["offset"] = _r(rng.uniform(-0.3, 0.3) * base, 1)
            unit_lift = lift_mm
        elif kind == "oscillating-roller":
            r0 = base + rr
            arm = _r(r0 * rng.uniform(1.1, 2.5), 1)
            fol["arm_length"] = arm
            fol["pivot_distance"] = _r(min(math.hypot(arm, r0) * rng.uniform(0.98, 1.15), arm + r0 - 1.0), 1)
            unit_lift = _r(min(math.degrees(lift_mm / arm), 30.0), 2)
        else:  # oscillating flat
            d = _r(base * rng.uniform(1.8, 3.5), 1)
            fol["pivot_distance"] = d
            unit_lift = _r(min(math.degrees(lift_mm / (0.8 * d)), 25.0), 2)
        depth = thickness + (0.5 if rng.random() < 0.3 else 0.0)
    segs, shape = draw_segments(rng, unit_lift, 3 if unit_lift < 1 else 2)
    spec["motion"] = {"rpm": rpm, "segments": segs}
    spec["cam"] = cam
    spec["follower"] = fol
    # the cam's largest radius, as a user would estimate it for the blank
    reach = base + lift_mm + 2.0 * rr + abs(fol.get("offset", 0.0)) * 0.2
    u = rng.random()
    if u < 0.45:
        stock = {"kind": "round", "diameter": float(math.ceil(2 * reach + rng.uniform(2.0, 20.0)))}
        if rng.random() < 0.2:
            stock["top_allowance"] = _r(rng.uniform(0.2, 2.0), 1)
        spec["stock"] = stock
    elif u < 0.65 and cam["kind"] == "disc":
        spec["stock"] = {"kind": "offset", "allowance": _r(rng.uniform(1.0, 6.0), 1)}
    # every post cuts a disc or face groove (Heidenhain's Klartext prints helices as CP IPA … IZ …); barrels need G93
    post = rng.choice(POSTS if cam["kind"] == "disc" else POSTS_4AXIS)
    m = _machining(rng, post, float(tool), depth, quick=quick)
    if cam["kind"] == "disc":
        if rng.random() < 0.25:
            m["finish_allowance"] = _r(rng.uniform(0.1, 0.5), 2)
        if rng.random() < 0.25:
            m["spring_pass"] = True
        if rng.random() < 0.2:
            m["stepover"] = rng.choice([0.2, 0.3, 0.5, 0.6])
    spec["machining"] = m
    spec["_shape"] = shape


def _groove_roller_and_tool(rng: random.Random, same: bool) -> tuple[float, float]:
    """(roller radius, tool diameter) of a groove: the roller's diameter (one centre pass) when ``same``, else a
    roller of 4-20 mm radius and a tool no wider than it (a centre pass and flank passes)."""
    if same:
        tool = _tool(rng)
        rr = tool / 2 if tool >= 8 else 4.0
        return rr, 2 * rr
    rr = _r(rng.uniform(4.0, 20.0), 1)
    return rr, _tool(rng, min(16.0, 2 * rr))


def _barrel(rng, spec, family, base, lift_mm, rotation, rpm, quick=False) -> None:
    base = max(base, 25.0)
    # the roller's diameter: one centre pass (5 axes: always, the tool rides on the roller's axis)
    rr, tool = _groove_roller_and_tool(rng, family.endswith("5axis") or rng.random() < 0.6)
    groove = _r(min(rr * rng.uniform(0.8, 1.6), 0.5 * base), 1)
    cam = {"kind": "cylindrical", "base_radius": base, "groove_depth": groove, "rotation": rotation}
    if rng.random() < 0.6:
        cam["bore"] = _r((base - groove) * rng.uniform(0.3, 1.0), 1)
    fol: dict = {"roller_radius": rr}
    m_extra: dict = {}
    if family == "barrel-translating":
        fol["kind"] = "translating-roller"
        unit_lift, travel = lift_mm, lift_mm
        posts = POSTS_4AXIS
    else:
        fol["kind"] = "oscillating-roller"
        arm = _r(rng.uniform(max(60.0, 1.2 * lift_mm), 120.0 if quick else 250.0), 1)
        d = _r(arm + base - groove / 2, 1)
        fol["pivot_distance"], fol["arm_length"] = d, arm
        unit_lift = _r(min(math.degrees(lift_mm / arm), 30.0), 2)
        reach = d - (base - groove)
        travel = 2 * reach * math.sin(math.radians(unit_lift) / 2) * 1.05
        axes = 5 if family.endswith("5axis") else 4
        m_extra["axes"] = axes
        posts = POSTS_5AXIS if axes == 5 else POSTS_4AXIS
    cam["length"] = float(math.ceil(travel + 2 * rr + rng.uniform(8.0, 40.0)))
    segs, shape = draw_segments(rng, unit_lift, 3 if unit_lift < 1 else 2)
    spec["motion"] = {"rpm": rpm, "segments": segs}
    spec["cam"] = cam
    spec["follower"] = fol
    m = _machining(rng, rng.choice(posts), float(tool), groove, mode=rng.choices(["lines", "arcs"], [85, 15])[0],
                   quick=quick)
    m.update(m_extra)
    if tool < 2 * rr and rng.random() < 0.3:
        m["accept_out_of_tolerance"] = True
    spec["machining"] = m
    spec["_shape"] = shape


# ------------------------------------------------------------------------------------------ TOML out

def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, list):
        return "[\n" + "".join(f"  {_value(x)},\n" for x in v) + "]"
    return str(v)


def to_toml(spec: dict) -> str:
    """A spec dict as TOML (scalars first, then one table per section; keys starting with ``_`` are ours)."""
    lines = [f"{k} = {_value(v)}" for k, v in spec.items() if not isinstance(v, dict) and not k.startswith("_")]
    for k, v in spec.items():
        if isinstance(v, dict):
            lines += ["", f"[{k}]"] + [f"{kk} = {_value(x)}" for kk, x in v.items()]
    return "\n".join(lines) + "\n"


# -------------------------------------------------------------------------------------- classifying

#: (regex on the one line, cause); the first that matches names the cause.
CAUSES = (
    (r"internal error: PostError: .*max_arc_sweep", "PostError max_arc_sweep"),
    (r"internal error: (\w+)", "internal fault: {0}"),
    (r"FAIL: radial engagement", "roughing engagement FAIL"),
    (r"FAIL: 3-D groove deviation", "3-D groove FAIL"),
    (r"FAIL: NC deviation", "NC deviation FAIL"),
    (r"FAIL: ([^0-9]+?) [-\d.]+ ", "FAIL {0}"),
    (r"part outline", "part outline (drawing) fault"),
    (r"undercut|cusp", "undercut advice"),
    (r"smallest concave radius|concave", "tool too large for a concave part"),
    (r"stock\.diameter|blank .*smaller|smaller than the cam", "stock too small"),
    (r"wider than the groove|narrower|third of", "groove tool size"),
    (r"pressure angle", "pressure angle"),
    (r"cam\.length .*too short", "barrel length too short"),
    (r"arm_length .*must reach", "arm length"),
    (r"pivot_distance", "pivot distance"),
    (r"bore", "bore"),
    (r"tolerance", "tolerance"),
    (r"error: ([a-z_]+\.[a-z_]+)", "bad input {0}"),
)


def classify(status: int, lines: list[str]) -> str:
    """The cause of an outcome, from its exit status and stderr lines."""
    if status == 0:
        return "ok (accepted FAIL)" if any("FAIL:" in line for line in lines) else "ok"
    text = message(status, lines)
    for pattern, cause in CAUSES:
        m = re.search(pattern, text)
        if m:
            return cause.format(*m.groups())
    if status < 0 or status > 128:
        return f"signal/timeout {status}"
    return f"exit {status}: " + text[:60]


def message(status: int, lines: list[str]) -> str:
    """The one line an exit 1/2/3 promises (the last error/FAIL line if there are more)."""
    for line in reversed(lines):
        if line.startswith(("camcam: error", "camcam: internal error", "camcam: FAIL", "FAIL")):
            return line
    return lines[-1] if lines else ""


# ------------------------------------------------------------------------------------------- advice

_ADVICE = re.compile(r"(?:\[(cam|follower|machining|stock|motion|report)\]\s*|\b(cam|follower|machining|stock|motion|report)\.)"
                     r"([a-z_]+)\s*(>=|<=|=|≥|≤|to|at least|at most)\s*([-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?)")
#: a bad-input line naming its key first: "stock.diameter: 227 mm is smaller than the cam …; expected at least 240 mm"
_EXPECTED = re.compile(r"error: (cam|follower|machining|stock|motion|report)\.([a-z_]+): .*\bexpected "
                       r"(?:at least|at most|>=|<=|≥|≤)\s*([-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?)")
_TOL = re.compile(r"accept a tolerance of at least ([\d.]+) mm|tolerance of at least ([\d.]+)")
#: the text between two settings that belong together (not an alternative: no "or")
_JOINED = re.compile(r"\s*(?:mm|°|deg)?\s*(?:\([^()]*\))?\s*(?:with|and)\s+(?:\[\w+\]\s*)?")
_STEP = re.compile(r"\b(lower|raise|reduce|increase)\s+(?:the\s+)?(?:\[(\w+)\]\s*|(\w+)\.)?([a-z_]+)")


def parse_advice(line: str, strict: bool = False) -> list[tuple[str, str, float]]:
    """Every ``(section, key, value)`` setting the line names, in order (:func:`advice_pieces`, flattened)."""
    return [item for piece in advice_pieces(line, strict)
            for item in (piece if isinstance(piece[0], tuple) else (piece,))]


def advice_pieces(line: str, strict: bool = False) -> list:
    """The pieces of advice a one-line message names with a value, in the order given: each a ``(section, key,
    value)`` setting (``cam.base_radius >= 44.47 mm``, ``[machining] axes = 5``, ``stock.diameter: … expected at
    least 240 mm``), or a tuple of settings joined by "with" or "and", which go together.  Unless ``strict``,
    also the informal "accept a tolerance of at least X mm" (no key named: listed by the campaign as a form to
    normalise).

    >>> advice_pieces("camcam: error: …; cam.base_radius >= 27.8 mm with follower.pivot_distance = 232.7 mm avoids it")
    [(('cam', 'base_radius', 27.8), ('follower', 'pivot_distance', 232.7))]
    >>> advice_pieces("camcam: error: …; expected cam.bore = 0 (no bore), or cam.base_radius >= 16 mm takes it")
    [('cam', 'bore', 0.0), ('cam', 'base_radius', 16.0)]
    """
    out = []
    last = None
    for m in _ADVICE.finditer(line):
        item = (m.group(1) or m.group(2), m.group(3), float(m.group(5)))
        # "cam.base_radius >= 27.8 mm with follower.pivot_distance = 232.7 mm" and "… = 8 … and … = 5" are one
        # piece of advice: the settings are applied together (an alternative is introduced by "or")
        if last is not None and _JOINED.fullmatch(line[last.end():m.start()]):
            out[-1] = out[-1] + (item,) if isinstance(out[-1][0], tuple) else (out[-1], item)
        else:
            out.append(item)
        last = m
    m = _EXPECTED.search(line)
    if m:
        out.append((m.group(1), m.group(2), float(m.group(3))))
    if not out and not strict:
        m = _TOL.search(line)
        if m:
            out.append(("machining", "tolerance", float(m.group(1) or m.group(2))))
    return out


def apply_advice(spec: dict, advice: list) -> dict | None:
    """``spec`` with the first piece of advice that changes it applied (a value a little beyond the stated bound,
    rounded outward so the printed number still meets it), or None if none applies.  A piece is one
    ``(section, key, value)`` or a tuple of them that go together (:func:`advice_pieces`)."""
    for piece in advice:
        settings = piece if isinstance(piece[0], tuple) else (piece,)
        new = json.loads(json.dumps(spec))
        changed = False
        for section, key, value in settings:
            changed |= _set(new, section, key, value)
        if changed:
            return new
    return None


def _set(new: dict, section: str, key: str, value: float) -> bool:
    """Set one advised value in ``new`` (see :func:`apply_advice`); False when it holds that value already."""
    if section not in new:
        new[section] = {"kind": "round"} if section == "stock" else {}
    old = new[section].get(key)
    if isinstance(old, (int, float)) and not isinstance(old, bool) and math.isclose(old, value, rel_tol=1e-9):
        return False
    if key in ("tolerance",):
        value = math.ceil(value * 1e4) / 1e4
    elif isinstance(old, (int, float)) and old > value:
        value = math.floor(value * 100) / 100
    else:
        value = math.ceil(value * 100) / 100
    if float(value).is_integer() and (old is None or (isinstance(old, int) and not isinstance(old, bool))):
        value = int(value)  # axes = 5, not 5.0 (an integer key refuses a float)
    new[section][key] = value
    return True


def advice_forms(line: str) -> str:
    """The advice part of a message with its numbers blanked (for listing message forms)."""
    text = re.sub(r"[-+]?\d+(?:\.\d+)?", "#", line)
    return re.sub(r"/tmp/\S+|case-\d+-\d+", "…", text)


# --------------------------------------------------------------------------------------------- runs

@dataclass
class Attempt:
    status: int
    lines: list[str]
    cause: str
    seconds: float
    cpu_s: float
    spec: dict
    readback: dict = field(default_factory=dict)

    @property
    def message(self) -> str:
        return message(self.status, self.lines)


def run_spec(spec: dict, folder: Path, timeout_s: float = RUN_TIMEOUT_S) -> tuple[Attempt, Path]:
    """Run ``camcam run`` on ``spec`` in ``folder`` (as a subprocess); the attempt and the output folder."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / f"{spec['name']}.toml"
    path.write_text(to_toml(spec))
    out = folder / "out"
    env = dict(os.environ, PYTHONPATH=str(ROOT), OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    try:
        proc = subprocess.run([sys.executable, "-m", "camcam", "run", str(path), "-o", str(out), "--force"],
                              capture_output=True, text=True, timeout=timeout_s, env=env, cwd=folder)
        status, err = proc.returncode, proc.stderr
    except subprocess.TimeoutExpired as exc:
        status, err = -9, (exc.stderr or b"").decode() if isinstance(exc.stderr, bytes) else (exc.stderr or "")
        err += "\ncamcam: timeout after %g s" % timeout_s
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    lines = [line for line in err.splitlines() if line.strip()]
    return Attempt(status, lines, classify(status, lines), wall, cpu, spec), out


def run_case(case: Case, workdir: str | Path | None = None, follow: bool = True, readback: bool = True) -> dict:
    """Run one case (and its advice, if any); a JSON-able record."""
    self0, kids0 = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory(prefix="anycam-", dir=workdir) as tmp:
        attempts: list[Attempt] = []
        spec = case.spec
        for step in range(1 + (ADVICE_STEPS if follow else 0)):
            att, out = run_spec(spec, Path(tmp) / f"step{step}")
            if att.status == 0 and readback:
                try:
                    att.readback = read_back(spec, out)
                except Exception as exc:  # a fault of the read-back is recorded, not raised
                    att.readback = {"error": f"{type(exc).__name__}: {exc}"}
            attempts.append(att)
            if att.status not in (2, 3) or not follow or step == ADVICE_STEPS:
                break
            new = apply_advice(spec, advice_pieces(att.message))
            if new is None:
                break
            spec = new
    self1, kids1 = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
    # user + sys of this process (read-back) and of every process it waited for (camcam runs, rs274)
    cpu = sum(getattr(b, f) - getattr(a, f) for a, b in ((self0, self1), (kids0, kids1)) for f in ("ru_utime", "ru_stime"))
    first = attempts[0]
    rec = {"key": case.key, "seed": case.seed, "index": case.index, "family": case.family, "post": case.post,
           "shape": case.spec.get("_shape"), "status": first.status, "cause": first.cause, "lines": first.lines,
           "message": first.message if first.status else "", "seconds": sum(a.seconds for a in attempts),
           "cpu_s": cpu, "readback": first.readback,
           "advice": None}
    if first.status in (2, 3):
        adv = parse_advice(first.message)
        rec["advice"] = {"named": [f"{s}.{k} = {v:g}" for s, k, v in parse_advice(first.message, strict=True)],
                         "informal": [f"{s}.{k} = {v:g}" for s, k, v in adv], "form": advice_forms(first.message),
                         "steps": [{"status": a.status, "cause": a.cause, "message": a.message,
                                    "readback": a.readback, "changed": _diff(case.spec, a.spec)}
                                   for a in attempts[1:]]}
        if attempts[1:]:
            last = attempts[-1]
            rec["advice"]["result"] = ("exit 0" if last.status == 0 else
                                       "other reason" if last.cause != first.cause else "same reason")
    return rec


def _diff(a: dict, b: dict) -> dict:
    out = {}
    for sec, tab in b.items():
        if isinstance(tab, dict):
            for k, v in tab.items():
                if a.get(sec, {}).get(k) != v:
                    out[f"{sec}.{k}"] = v
    return out


# -------------------------------------------------------------------------------------- read-back

def _report(out: Path) -> dict:
    files = list(out.glob("*-report.json"))
    return json.loads(files[0].read_text()) if files else {}


#: a pass's comment: kind, contour, Z and, on rough passes, the plan ("ring 1 of 2, 3.77 mm apart", "spiral 11 turns …")
_PASS = re.compile(r"^pass \d+/\d+: (\w+), (.+?), Z(-?[\d.]+)(?:, .*)?$")


def read_back(spec: dict, out: Path) -> dict:
    """Measure a written program: rs274 read-back against the exact curves (disc cams on posts it reads),
    or the report's 3-D groove figure (barrels, with rs274 accepting the program).  Returns
    ``{"tolerance", "deviation", "multiple", "how", ...}`` (``multiple`` None when nothing is measured)."""
    from camcam.verify.rs274 import rs274_available, run_rs274, tcp_readable

    m = spec["machining"]
    tol = float(m.get("tolerance", 0.01))
    report = _report(out)
    progs = [p for p in out.iterdir() if p.suffix in (".ngc", ".nc", ".gcode", ".mpf", ".h")]
    rec: dict = {"tolerance": tol, "deviation": None, "multiple": None, "how": None}
    if spec["cam"]["kind"] == "cylindrical":
        checks = {c["name"]: c for c in report.get("verdict", {}).get("checks", [])}
        g = checks.get("3-D groove deviation")
        if g is not None:
            rec.update(deviation=g["value"], multiple=g["value"] / tol, how="report 3-D groove",
                       where=g.get("where", ""))
        if m["post"] in RS274_READS and rs274_available() and progs:
            from camcam.post.post import load_post

            text = progs[0].read_text()
            try:
                if m.get("axes") == 5:
                    tcp = tuple(line.format(tool=m.get("tool_number", 1)) for line in load_post(m["post"]).tcp_on)
                    prog, ini = tcp_readable(text, tcp, out)
                    run_rs274(prog, ini=ini)
                else:
                    run_rs274(progs[0])
                rec["rs274"] = "read"
                if m.get("axes") == 5:
                    rec.update(_swept(spec, out, run_rs274(prog, ini=ini)))
            except RuntimeError as exc:
                rec["rs274"] = f"rejected: {str(exc)[-200:]}"
        return rec
    if m["post"] not in RS274_READS or not rs274_available():
        rec["how"] = f"not read ({m['post']})"
        rec["report_deviation"] = report.get("max_deviation_mm")
        return rec
    moves = run_rs274(progs[0], comments=True)
    worst, where, passes = 0.0, "", 0
    curves = _exact_curves(spec)
    from camcam.toolpath.deviation import measure_deviation
    from camcam.verify.rs274 import feed_passes, print_margin_mm
    from camcam.post.post import load_post

    margin = print_margin_mm(load_post(m["post"]).decimals)
    current, last = None, None
    segments: list[tuple[tuple, list]] = []
    for mv in moves:
        if isinstance(mv, str):
            hit = _PASS.match(mv)
            if mv.startswith("pass ") and hit is None:  # never fold an unread pass into the one before it
                raise RuntimeError(f"a pass comment the read-back cannot parse: {mv!r}")
            if hit:
                # a parentheses-comment post prints the label's "(rough)" as "[rough]"
                current = (hit.group(1), hit.group(2).replace("[", "(").replace("]", ")"), float(hit.group(3)))
                segments.append((current, [last] if last is not None else []))
            continue
        last = mv
        if current is not None:
            segments[-1][1].append(mv)
    skipped = []
    for (kind, label, z), seg in segments:
        if kind == "rough":
            continue
        if label not in curves:
            skipped.append(f"{kind} {label}")
            continue
        runs = [els for zz, els in feed_passes(seg) if abs(zz - z) < 1e-3]
        if not runs:
            raise RuntimeError(f"pass {kind} {label} Z{z}: no feed run at its depth in rs274's moves")
        els = max(runs, key=len)
        curve, leads = curves[label]
        els = els[1:-1] if leads else els
        # the figure is an upper bound (the sampled deviation plus the between-samples bound, 2 % of the
        # tolerance); near the limit it is measured again with a bound 20 times finer
        dev = measure_deviation(curve, els, margin_mm=0.02 * tol).max_deviation_mm
        if dev > 0.98 * tol:
            dev = measure_deviation(curve, els, margin_mm=0.001 * tol).max_deviation_mm
        passes += 1
        if dev > worst:
            worst, where = dev, f"{kind} {label} Z{z:g}"
    rec.update(deviation=worst, multiple=(worst - margin) / tol if passes else None, how="rs274 read-back",
               passes=passes, skipped=skipped, where=where, report_deviation=report.get("max_deviation_mm"), print_margin=margin)
    return rec


def _exact_curves(spec: dict) -> dict:
    """label → (exact tool-centre curve, whether its pass has leads), rebuilt from the spec alone."""
    from camcam.geometry.build import disc_follower
    from camcam.geometry.disc import DiscCam
    from camcam.geometry.groove import GrooveCam
    from camcam.spec import parse_spec

    import tomllib

    s = parse_spec(tomllib.loads(to_toml(spec)), ROOT / "spec.toml")
    disc = DiscCam(disc_follower(s.follower), s.motion.program(s.unit), s.cam.base_radius, s.cam.rotation)
    r_t = spec["machining"]["tool_diameter"] / 2
    holes = {}  # the helical bore's and the dowel hole's tool-centre circles (their passes have no leads)
    if spec["machining"].get("bore"):
        holes["bore"] = (_circle(spec["cam"]["bore"] / 2 - r_t, (0.0, 0.0)), False)
    if spec["machining"].get("dowel"):
        d = spec["cam"]["dowel"]
        a = math.radians(d.get("angle", 90.0))
        holes["dowel hole"] = (_circle(d["diameter"] / 2 - r_t, (d["radius"] * math.cos(a), d["radius"] * math.sin(a))),
                               False)
    if spec["cam"]["kind"] == "disc":
        return {"profile": (disc.offset_profile(r_t), True), **holes}
    cam = GrooveCam(disc, s.cam.groove_depth)
    return {"groove centre": (cam.pitch, False), "groove centre (rough)": (cam.pitch, False),
            "inner flank": (cam.offset_flank(0, r_t), False), "outer flank": (cam.offset_flank(1, r_t), False),
            **holes}


def _circle(radius: float, centre: tuple[float, float]):
    """The circle of ``radius`` about ``centre`` as an exact closed curve (written here, not camcam's bore_curve)."""
    import numpy as np

    from camcam.geometry.curve import FunctionCurve

    def func(t, k):
        c, s = np.cos(t), np.sin(t)
        v = radius * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], -1)
        return v + np.asarray(centre) if k == 0 else v

    return FunctionCurve(func, 0.0, 2 * math.pi, closed=True)


def _swept(spec: dict, out: Path, canon: list) -> dict:
    """A 5-axis groove cut by the moves rs274 read, measured by the brute-force sweep of the tests
    (:func:`tests.nc.test_fiveaxis.groove_deviation`: both walls, 240 angles, 3 radii): its worst overcut and
    material left, and their larger as a multiple of the tolerance."""
    from camcam.geometry.build import build_cam
    from camcam.spec import load_spec
    from tests.nc.test_fiveaxis import groove_deviation

    s = load_spec(out.parent / f"{spec['name']}.toml")
    built = build_cam(s.cam, s.follower, s.motion.program(s.unit))
    moves = [("rapid" if mv.kind == "rapid" else "feed", (mv.x, mv.y, mv.z, mv.a, mv.b)) for mv in canon]
    over, left = groove_deviation(built, moves, a_axis=spec["machining"].get("a_axis", "right-hand"))
    tol = float(spec["machining"].get("tolerance", 0.01))
    return {"swept_overcut": float(over), "swept_left": float(left), "swept_multiple": float(max(over, left)) / tol}
