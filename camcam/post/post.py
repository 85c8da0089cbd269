"""Post definitions: one TOML file per controller dialect, validated when loaded.

The bundled posts live in ``camcam/post/data/`` beside this code (package data, shipped in
the wheel); a user's own post is loaded by path.

Keys (all required unless a default is given):

============================  =====================================================
``description``               text
``dialect``                   ``"gcode"`` (default) or ``"heidenhain"`` (conversational)
``extension``                 program file extension, without the dot
``units``                     millimetres: ``G21`` or ``G71`` (G-code), ``MM`` (Heidenhain); the
                              header must print it (literally or as ``{units}``)
``decimals``                  digits after the point, 3–6 (coordinates are rounded to them)
``arc_format``                ``"ij_incremental"``, ``"ij_absolute"``, ``"r"`` (G-code) or
                              ``"cc_absolute"`` (Heidenhain CC + C)
``max_arc_sweep_deg``         largest arc per block, [90, 180] (lead arcs are quarter circles)
``max_radius_error_mm``       start/end radius mismatch allowed (default 0.002)
``decimal_point_always``      print ``X10.`` instead of ``X10`` (Fanuc)
``line_numbers``              number the blocks (``N10``); start/step default 10/10
``max_line_number``           the controller's largest block number (default 99999); a longer
                              program is refused
``comment``                   ``"parentheses"`` or ``"semicolon"``
``tool_change``               print the tool change line(s) of the header
``inverse_time``              the controller has G93 (needed for 4-axis programs)
``header``, ``footer``        lists of lines; ``{title}``, ``{name}``, ``{units}``, ``{tool}``,
                              ``{spindle}``, ``{program_number}`` are filled in (checked
                              whole at load time: :mod:`camcam.post.template`; in
                              G-code a line's code text, filled in, must be words such
                              as ``G21``, ``T1`` or ``TRAORI``, or ``%``)
``program_number``            default 1 (Fanuc O-number); 1 up to the width the header
                              prints it with (``{program_number:04d}``: 9999); a spec's
                              ``[machining] program_number`` replaces it
``five_axis``                 the controller has tool-centre-point control for 5-axis
                              programs (X Y Z = tool tip; default false)
``tcp_on``, ``tcp_off``       blocks that switch it on before and off after a 5-axis
                              path (lists, may be empty: LinuxCNC's TCP lives in its
                              kinematics); ``{tool}`` is filled in, checked like the header
``tool_length_offset``        line that applies the tool length offset, printed after the
                              header (``"G43 H{tool}"``; default none: the header or the
                              tool call does it); a template checked like the header
``work_offsets``              six program texts for ``G54`` … ``G59`` (a spec's
                              ``work_offset``), in this dialect's words; a ``\\n`` splits
                              one into lines, an indented line is not numbered (default
                              ``G54`` … ``G59``); each line checked like the header
``coolant_flood``,            coolant words (defaults ``M8``, ``M7``, ``M9``); ``""``: the
``coolant_mist``,             controller has none, and a spec asking for it is refused
``coolant_off``
``rapid_mm_min``              rapid traverse rate for the cycle-time estimate (default 5000)
``tool_change_s``             seconds per tool change for the estimate (default 10)
``max_accel_mm_s2``           each linear axis's acceleration limit, mm/s² (default 500), for the
                              motion-model cycle time (:mod:`camcam.verify.motion_time`)
``max_accel_deg_s2``          the rotary axes' acceleration limit, °/s² (default 500)
``junction_deviation_mm``     GRBL's junction deviation ($11), mm (default 0.01): the cornering
                              speed rule of the motion model; each bundled post says where its
                              three values come from
``lookahead_blocks``          blocks the controller plans over (GRBL: its 16-block buffer); default
                              0: the model plans over the whole program
``arc_tolerance_mm``          the controller cuts arcs into chords within it (GRBL's $12); default 0:
                              arcs interpolated as arcs
``max_spindle_rpm``,          the machine's fastest spindle (rev/min) and feed (mm/min); default none
``max_feed_mm_min``           (not checked).  A spec whose speed or feed exceeds one is refused naming
                              the field; an arc's edge-held centre feed is capped at the feed
``rotary_rapid``              the controller moves its rotary axes in G0 (default true): a
                              barrel program turns A back to each pass's start in a G0 at
                              the safe height; false: A never turns back, each pass starts
                              at the equivalent (mod 360) of its start angle nearest where
                              the last one ended (the shortest way, A counting on)
============================  =====================================================

Text that reaches the program goes through the post's comment encoder
(:mod:`camcam.post.text`).  A post file is read as UTF-8 (at most
:data:`MAX_POST_BYTES`).
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from camcam.errors import InputError
from camcam.inputs import os_reason, read_limited
from camcam.post.template import SAMPLE_VALUES, TemplateError, check_line, parse_template
from camcam.nc.result import Program
from camcam.nc.settings import WORK_OFFSETS, ProgramSetup
from camcam.post.gcode import write_program
from camcam.toolpath.path import Toolpath
from camcam.toolpath.quantizer import Quantizer

__all__ = ["Post", "load_post", "known_posts", "five_axis_posts", "parse_post", "MAX_POST_BYTES", "MAX_LINE_NUMBER",
           "MAX_PROGRAM_NUMBER", "METRIC_UNITS", "WORK_OFFSETS"]

_ARC_FORMATS = {"gcode": ("ij_incremental", "ij_absolute", "r"), "heidenhain": ("cc_absolute",)}

#: Largest post file read.
MAX_POST_BYTES = 1 << 20

#: Largest block number any supported controller takes (Fanuc 30i: 8 digits).
MAX_LINE_NUMBER = 99_999_999

#: Largest program number (Fanuc 30i: O followed by 8 digits).
MAX_PROGRAM_NUMBER = 99_999_999

#: The units words camcam's millimetre programs may declare, per dialect.
METRIC_UNITS = {"gcode": ("G21", "G71"), "heidenhain": ("MM",)}
_INCH = re.compile(r"(?<![A-Za-z0-9.])(G0*20|G0*70|INCH)(?![0-9])", re.IGNORECASE)


#: ``work_offsets`` when a post does not give them: G-code's own words; Heidenhain's preset
#: (datum) numbers 1–6 set by cycle 247.
_DEFAULT_OFFSETS = {"gcode": WORK_OFFSETS,
                    "heidenhain": tuple(f"CYCL DEF 247 DATUM SETTING ~\n  Q339=+{k} ;DATUM NUMBER" for k in range(1, 7))}


@dataclass(frozen=True, kw_only=True)
class Post:
    """A validated controller dialect."""

    name: str
    description: str
    extension: str
    units: str
    decimals: int
    arc_format: str
    max_arc_sweep_deg: float
    header: tuple[str, ...]
    footer: tuple[str, ...]
    dialect: str = "gcode"
    max_radius_error_mm: float = 0.002
    decimal_point_always: bool = False
    line_numbers: bool = False
    line_number_start: int = 10
    line_number_step: int = 10
    max_line_number: int = 99999
    comment: str = "parentheses"
    tool_change: bool = True
    inverse_time: bool = True
    program_number: int = 1
    five_axis: bool = False
    tcp_on: tuple[str, ...] = ()
    tcp_off: tuple[str, ...] = ()
    tool_length_offset: str = ""
    work_offsets: tuple[str, ...] = WORK_OFFSETS
    coolant_flood: str = "M8"
    coolant_mist: str = "M7"
    coolant_off: str = "M9"
    rapid_mm_min: float = 5000.0
    tool_change_s: float = 10.0
    max_accel_mm_s2: float = 500.0
    max_accel_deg_s2: float = 500.0
    junction_deviation_mm: float = 0.01
    lookahead_blocks: int = 0
    arc_tolerance_mm: float = 0.0
    rotary_rapid: bool = True
    max_spindle_rpm: float | None = None
    max_feed_mm_min: float | None = None

    @property
    def uses_program_number(self) -> bool:
        """Whether the header or footer prints ``{program_number}``."""
        return any("program_number" in parse_template(line, self.comment).fields() for line in self.header + self.footer)

    @property
    def program_number_max(self) -> int:
        """The largest program number the header prints whole (its zero-padded width; else 8 digits)."""
        widths = [parse_template(line, self.comment).width("program_number") for line in self.header + self.footer]
        return min([10**w - 1 for w in widths if w is not None] + [MAX_PROGRAM_NUMBER])

    def work_offset_lines(self, work_offset: str) -> tuple[str, ...]:
        """The program lines selecting ``work_offset`` (``"G54"`` … ``"G59"``), as templates."""
        return tuple(self.work_offsets[WORK_OFFSETS.index(work_offset)].split("\n"))

    def coolant_word(self, coolant: str) -> str:
        """The word switching ``coolant`` ("flood", "mist", "off") on; ``""`` when the controller has none."""
        return {"flood": self.coolant_flood, "mist": self.coolant_mist, "off": self.coolant_off}[coolant]

    def length_offset_text(self, tool: int) -> str:
        """How the program applies the tool length (the setup sheet's line): ``H3 (G43)``, ``D1``, the tool
        call, or nothing (GRBL)."""
        lines = self.header + ((self.tool_length_offset,) if self.tool_length_offset else ())
        for line in lines:
            if "G43" in line and "{tool" in line:
                return f"H{line.split('H', 1)[1].format(tool=tool)} (G43 in the program)"
        if self.dialect == "heidenhain":
            return f"from the tool table (TOOL CALL {tool})"
        for line in lines:
            if "D1" in line:
                return "D1 with the tool call (tool table)"
        return "none: the controller has no tool table; set Z0 on the top face with this tool"

    def tcp_comment(self, tool_number: int) -> str:
        """The blocks that switch tool-centre-point control on, as a 5-axis program's header names them
        (``{tool}`` filled in), or where the machine's kinematics do it without a block."""
        tcp = "; ".join(self.tcp_on) or "in the machine's kinematics"
        return tcp.replace("{tool}", str(tool_number)).replace("{tool:02d}", f"{tool_number:02d}")

    @property
    def five_axis_feed_note(self) -> str:
        """What the F word of this dialect's 5-axis moves means (a header comment of the program)."""
        if self.dialect == "heidenhain":
            return "F = tool-tip feed in mm/min (M128)"
        return "G93 inverse time: F = 1 / block time, the tool tip's path in the part at the feed"

    @property
    def quantizer(self) -> Quantizer:
        """The printed rounding of this post (decimals and arc format): the one model of what it prints."""
        return Quantizer(self.decimals, self.arc_format)

    def write_program(self, toolpath: Toolpath, name: str = "camcam", setup: ProgramSetup = ProgramSetup()) -> Program:
        """``toolpath`` printed in this dialect with ``setup``'s work offset, coolant and number
        (:func:`camcam.post.gcode.write_program`)."""
        return write_program(toolpath, self, name, setup)


def _post_dir():
    return resources.files("camcam.post") / "data"


def known_posts() -> list[str]:
    """Names of the bundled posts."""
    return sorted(p.name[:-5] for p in _post_dir().iterdir() if p.name.endswith(".toml"))


def five_axis_posts() -> list[str]:
    """The bundled posts with a 5-axis mode (tool-centre-point control), by name."""
    return [name for name in known_posts() if load_post(name).five_axis]


def parse_post(data: dict, name: str) -> Post:
    """Validate a parsed post table; errors name the post and the key."""
    def fail(key, msg):
        raise InputError(f"post {name}: {key}: {msg}")

    types = {"description": str, "dialect": str, "extension": str, "units": str, "decimals": int,
             "arc_format": str, "max_arc_sweep_deg": (int, float), "max_radius_error_mm": (int, float),
             "decimal_point_always": bool, "line_numbers": bool, "line_number_start": int,
             "line_number_step": int, "max_line_number": int, "comment": str, "tool_change": bool, "inverse_time": bool,
             "header": list, "footer": list, "program_number": int, "five_axis": bool, "tcp_on": list,
             "tcp_off": list, "tool_length_offset": str, "work_offsets": list, "coolant_flood": str,
             "coolant_mist": str, "coolant_off": str, "rapid_mm_min": (int, float), "tool_change_s": (int, float),
             "rotary_rapid": bool, "max_accel_mm_s2": (int, float), "max_accel_deg_s2": (int, float),
             "junction_deviation_mm": (int, float), "lookahead_blocks": int, "arc_tolerance_mm": (int, float),
             "max_spindle_rpm": (int, float), "max_feed_mm_min": (int, float)}
    required = {"description", "extension", "units", "decimals", "arc_format", "max_arc_sweep_deg", "header", "footer"}
    for key in data:
        if key not in types:
            fail(key, f"unknown key; known: {', '.join(sorted(types))}")
    for key in sorted(required - set(data)):
        fail(key, "missing")
    for key, value in data.items():
        ok = isinstance(value, types[key]) and not (types[key] in (int, (int, float)) and isinstance(value, bool))
        if not ok:
            fail(key, f"expected {getattr(types[key], '__name__', 'a number')}, got {value!r}")
    dialect = data.get("dialect", "gcode")
    if dialect not in _ARC_FORMATS:
        fail("dialect", f'expected "gcode" or "heidenhain", got {dialect!r}')
    if data["arc_format"] not in _ARC_FORMATS[dialect]:
        fail("arc_format", f"expected one of {', '.join(_ARC_FORMATS[dialect])} for dialect {dialect}, got {data['arc_format']!r}")
    if not 3 <= data["decimals"] <= 6:
        fail("decimals", f"expected 3–6, got {data['decimals']}")
    if not 90 <= data["max_arc_sweep_deg"] <= 180:
        # the tangent lead-in/out arcs are quarter circles: a post that cannot hold 90° cannot print them
        fail("max_arc_sweep_deg", f"expected 90 to 180 (lead arcs are quarter circles), got {data['max_arc_sweep_deg']}")
    if data["arc_format"] == "r" and data["max_arc_sweep_deg"] >= 180:
        fail("max_arc_sweep_deg", "must be below 180 with arc_format r (R is ambiguous at a half circle)")
    if not 0 < data.get("max_radius_error_mm", 0.002) <= 0.1:
        fail("max_radius_error_mm", "expected in (0, 0.1]")
    if data.get("comment", "parentheses") not in ("parentheses", "semicolon"):
        fail("comment", f'expected "parentheses" or "semicolon", got {data["comment"]!r}')
    if not data["extension"].isalnum():
        fail("extension", f"expected letters/digits without a dot, got {data['extension']!r}")
    if data.get("five_axis", False) and "tcp_on" not in data:
        fail("tcp_on", "missing: a five_axis post names the blocks that switch tool-centre-point control on "
                       "(an empty list when the machine's kinematics do it)")
    for key in ("tcp_on", "tcp_off"):
        if key in data and not data.get("five_axis", False):
            fail(key, "only applies with five_axis = true")
    if not data["extension"].isascii():
        fail("extension", f"expected ASCII letters/digits, got {data['extension']!r}")
    comment = data.get("comment", "parentheses")
    templates = {}
    offsets = data.get("work_offsets", list(_DEFAULT_OFFSETS[dialect]))
    if len(offsets) != len(WORK_OFFSETS) or not all(isinstance(o, str) and o.strip() for o in offsets):
        fail("work_offsets", f"expected {len(WORK_OFFSETS)} non-empty strings (the words for {', '.join(WORK_OFFSETS)}), "
             f"got {offsets!r}")
    if not data.get("coolant_flood", "M8") and not data.get("coolant_mist", "M7"):
        fail("coolant_flood", "a post needs at least one coolant-on word (coolant_flood or coolant_mist)")
    if not data.get("coolant_off", "M9"):
        fail("coolant_off", "expected the coolant-off word, got an empty string")
    for key, default in (("rapid_mm_min", 5000.0), ("tool_change_s", 10.0)):
        v = data.get(key, default)
        low = 0.0 if key == "tool_change_s" else 1.0
        if not (math.isfinite(v) and low <= v <= 1e6):
            fail(key, f"expected {low:g} to 1e6, got {v}")
    for key, default, low, high in (("max_accel_mm_s2", 500.0, 0.1, 1e6), ("max_accel_deg_s2", 500.0, 0.1, 1e7),
                                    ("junction_deviation_mm", 0.01, 1e-4, 10.0)):
        v = data.get(key, default)
        if not (math.isfinite(v) and low <= v <= high):
            fail(key, f"expected {low:g} to {high:g}, got {v}")
    for key in ("max_spindle_rpm", "max_feed_mm_min"):
        if key in data and not (math.isfinite(data[key]) and 1.0 <= data[key] <= 1e6):
            fail(key, f"expected 1 to 1e6, got {data[key]}")
    if not (data.get("lookahead_blocks", 0) == 0 or 3 <= data["lookahead_blocks"] <= 100_000):
        fail("lookahead_blocks", f"expected 0 (the whole program) or 3 to 100000, got {data['lookahead_blocks']}")
    tol = data.get("arc_tolerance_mm", 0.0)
    if not (tol == 0.0 or (math.isfinite(tol) and 1e-4 <= tol <= 1.0)):
        fail("arc_tolerance_mm", f"expected 0 (arcs interpolated) or 0.0001 to 1, got {tol}")
    lines = {(key, i): line for key in ("header", "footer", "tcp_on", "tcp_off") for i, line in enumerate(data.get(key, ()))}
    for key in ("tool_length_offset", "coolant_flood", "coolant_mist", "coolant_off"):
        if data.get(key):
            lines[(key, None)] = data[key]
    for k, text in enumerate(offsets):
        for j, line in enumerate(text.split("\n")):
            lines[("work_offsets", f"{k}:{j}" if "\n" in text else k)] = line
    values = dict(SAMPLE_VALUES, units=data["units"])
    for (key, i), line in lines.items():
        try:
            templates[(key, i)] = parse_template(line, comment)
            check_line(templates[(key, i)], dialect, values)
        except TemplateError as err:
            fail(key if i is None else f"{key}[{i}]", str(err))
    units = data["units"]
    if units not in METRIC_UNITS[dialect]:
        fail("units", f"camcam writes millimetres; expected {' or '.join(METRIC_UNITS[dialect])} for dialect {dialect}, "
                      f"got {units!r}")
    word = re.compile(rf"(?<![A-Za-z0-9.]){units}(?![0-9])")
    header_has = any("units" in t.fields() or word.search(t.code_text()) for (k, _), t in templates.items() if k == "header")
    if not header_has:
        fail("header", f"must print the units word {units} (or {{units}}) so the controller reads millimetres")
    for (key, i), t in templates.items():
        m = _INCH.search(t.code_text())
        if m:
            fail(key if i is None else f"{key}[{i}]", f"{m.group(0)} selects inches; camcam writes millimetres")
    top = data.get("max_line_number", 99999)
    if not 1 <= top <= MAX_LINE_NUMBER:
        fail("max_line_number", f"expected 1 to {MAX_LINE_NUMBER}, got {top}")
    start, step = data.get("line_number_start", 10), data.get("line_number_step", 10)
    if not 0 <= start <= top:
        fail("line_number_start", f"expected 0 to max_line_number = {top}, got {start}")
    if not 1 <= step <= top:
        fail("line_number_step", f"expected 1 to max_line_number = {top}, got {step}")
    pn_limit = MAX_PROGRAM_NUMBER
    for t in templates.values():
        w = t.width("program_number")
        if w is not None:
            pn_limit = min(pn_limit, 10**w - 1)
    pn = data.get("program_number", 1)
    if not 1 <= pn <= pn_limit:
        fail("program_number", f"expected 1 to {pn_limit} (the digits the header prints it with), got {pn}")
    floats = ("max_arc_sweep_deg", "max_radius_error_mm", "rapid_mm_min", "tool_change_s", "max_accel_mm_s2",
              "max_accel_deg_s2", "junction_deviation_mm", "arc_tolerance_mm", "max_spindle_rpm", "max_feed_mm_min")
    fields = {k: (tuple(v) if isinstance(v, list) else (float(v) if k in floats else v)) for k, v in data.items()}
    fields.setdefault("work_offsets", _DEFAULT_OFFSETS[dialect])
    return Post(name=name, **fields)


def load_post(name_or_path: str | Path, base: Path | None = None) -> Post:
    """A bundled post by name (``"linuxcnc"``) or a user's post file by path (``"./mymill.toml"``).

    Examples
    --------
    >>> load_post("fanuc").decimal_point_always
    True
    >>> load_post("nope")
    Traceback (most recent call last):
    ...
    camcam.errors.InputError: unknown post 'nope'; known: fanuc, grbl, haas, heidenhain, linuxcnc, sinumerik (or a path to a .toml file)
    """
    text_name = str(name_or_path)
    if text_name.endswith(".toml") or "/" in text_name or "\\" in text_name:
        path = Path(text_name)
        if base is not None and not path.is_absolute():
            path = base / path
        try:
            raw = read_limited(path, MAX_POST_BYTES)
        except OSError as err:
            raise InputError(f"post {text_name}: cannot read: {os_reason(err)}") from None
        name = path.stem
        bad = [ch for ch in name if not ch.isprintable()]
        if bad or len(name) > 64:
            raise InputError(f"post {text_name!r}: the file name must be at most 64 printable characters "
                             "(it is printed in the program's title)")
    else:
        if text_name not in known_posts():
            raise InputError(f"unknown post {text_name!r}; known: {', '.join(known_posts())} (or a path to a .toml file)")
        raw = (_post_dir() / f"{text_name}.toml").read_bytes()
        name = text_name
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise InputError(f"post {name}: not UTF-8 text (byte {err.start})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"post {name}: not valid TOML: {err}") from None
    return parse_post(data, name)
