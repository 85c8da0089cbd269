"""Post definitions: one TOML file per controller dialect, validated when loaded.

The bundled posts live in ``camcam/post_data/`` (the repository's top-level
``post/`` is that folder); a user's own post is loaded by path.

Keys (all required unless a default is given):

============================  =====================================================
``description``               text
``dialect``                   ``"gcode"`` (default) or ``"heidenhain"`` (conversational)
``extension``                 program file extension, without the dot
``units``                     units word printed in the header (``G21``, ``G71``, ``MM``)
``decimals``                  digits after the point, 3–6 (coordinates are rounded to them)
``arc_format``                ``"ij_incremental"``, ``"ij_absolute"``, ``"r"`` (G-code) or
                              ``"cc_absolute"`` (Heidenhain CC + C)
``max_arc_sweep_deg``         largest arc per block, (0, 180]
``max_radius_error_mm``       start/end radius mismatch allowed (default 0.002)
``decimal_point_always``      print ``X10.`` instead of ``X10`` (Fanuc)
``line_numbers``              number the blocks (``N10``); start/step default 10/10
``comment``                   ``"parentheses"`` or ``"semicolon"``
``tool_change``               print the tool change line(s) of the header
``inverse_time``              the controller has G93 (needed for 4-axis programs)
``header``, ``footer``        lists of lines; ``{title}``, ``{name}``, ``{tool}``,
                              ``{spindle}``, ``{program_number}`` are filled in
``program_number``            default 1 (Fanuc O-number)
============================  =====================================================
"""

from __future__ import annotations

import string
import tomllib
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from camcam.errors import InputError
from camcam.nc.result import Program
from camcam.post.gcode import write_program
from camcam.toolpath.path import Toolpath
from camcam.toolpath.quantizer import Quantizer

__all__ = ["Post", "load_post", "known_posts", "parse_post"]

_ARC_FORMATS = {"gcode": ("ij_incremental", "ij_absolute", "r"), "heidenhain": ("cc_absolute",)}
_FIELDS = {"title", "name", "tool", "spindle", "program_number"}


@dataclass(frozen=True)
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
    comment: str = "parentheses"
    tool_change: bool = True
    inverse_time: bool = True
    program_number: int = 1

    @property
    def quantizer(self) -> Quantizer:
        """The printed rounding of this post (decimals and arc format): the one model of what it prints."""
        return Quantizer(self.decimals, self.arc_format)

    def write_program(self, toolpath: Toolpath, name: str = "camcam") -> Program:
        """``toolpath`` printed in this dialect (:func:`camcam.post.gcode.write_program`)."""
        return write_program(toolpath, self, name)


def _post_dir():
    return resources.files("camcam") / "post_data"


def known_posts() -> list[str]:
    """Names of the bundled posts."""
    return sorted(p.name[:-5] for p in _post_dir().iterdir() if p.name.endswith(".toml"))


def parse_post(data: dict, name: str) -> Post:
    """Validate a parsed post table; errors name the post and the key."""
    def fail(key, msg):
        raise InputError(f"post {name}: {key}: {msg}")

    types = {"description": str, "dialect": str, "extension": str, "units": str, "decimals": int,
             "arc_format": str, "max_arc_sweep_deg": (int, float), "max_radius_error_mm": (int, float),
             "decimal_point_always": bool, "line_numbers": bool, "line_number_start": int,
             "line_number_step": int, "comment": str, "tool_change": bool, "inverse_time": bool,
             "header": list, "footer": list, "program_number": int}
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
    if not 0 < data["max_arc_sweep_deg"] <= 180:
        fail("max_arc_sweep_deg", f"expected in (0, 180], got {data['max_arc_sweep_deg']}")
    if data["arc_format"] == "r" and data["max_arc_sweep_deg"] >= 180:
        fail("max_arc_sweep_deg", "must be below 180 with arc_format r (R is ambiguous at a half circle)")
    if not 0 < data.get("max_radius_error_mm", 0.002) <= 0.1:
        fail("max_radius_error_mm", "expected in (0, 0.1]")
    if data.get("comment", "parentheses") not in ("parentheses", "semicolon"):
        fail("comment", f'expected "parentheses" or "semicolon", got {data["comment"]!r}')
    if not data["extension"].isalnum():
        fail("extension", f"expected letters/digits without a dot, got {data['extension']!r}")
    for key in ("header", "footer"):
        for i, line in enumerate(data[key]):
            if not isinstance(line, str):
                fail(f"{key}[{i}]", f"expected a string, got {line!r}")
            try:
                names = {f for _, f, _, _ in string.Formatter().parse(line) if f is not None}
            except ValueError as err:
                fail(f"{key}[{i}]", f"bad template: {err}")
            bad = names - _FIELDS
            if bad:
                fail(f"{key}[{i}]", f"unknown field {{{sorted(bad)[0]}}}; known: {', '.join(sorted(_FIELDS))}")
    fields = {k: (tuple(v) if isinstance(v, list) else (float(v) if k in ("max_arc_sweep_deg", "max_radius_error_mm") else v))
              for k, v in data.items()}
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
    if text_name.endswith(".toml") or "/" in text_name or "\\\\" in text_name:
        path = Path(text_name)
        if base is not None and not path.is_absolute():
            path = base / path
        try:
            text = path.read_text(encoding="utf-8")
        except OSError as err:
            raise InputError(f"post {text_name}: cannot read: {err.strerror or err}") from None
        name = path.stem
    else:
        if text_name not in known_posts():
            raise InputError(f"unknown post {text_name!r}; known: {', '.join(known_posts())} (or a path to a .toml file)")
        text = (_post_dir() / f"{text_name}.toml").read_text(encoding="utf-8")
        name = text_name
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise InputError(f"post {name}: not valid TOML: {err}") from None
    return parse_post(data, name)
