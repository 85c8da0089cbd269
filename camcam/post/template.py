"""A post's header and footer lines: templates checked whole when the post is loaded.

A line is parsed with :meth:`string.Formatter.parse`.  Allowed are only the
fields of :data:`FIELDS` by their bare names (no ``.attr``, no ``[index]``,
no ``!conversion``) and, for the integer fields, a width (``{tool:02d}``,
at most :data:`MAX_WIDTH` digits); a format spec may not hold a nested field.
The literal text may not hold a control character (one template is one
line) and its comments must be closed and not nested.  Each field knows
whether it sits inside a comment: ``{title}`` must, and there it goes
through the post's comment encoder; ``{name}`` outside a comment must be a
program name.  Anything else rejects the whole post at load time with one
line naming the key.
"""

from __future__ import annotations

import re
import string
import unicodedata
from dataclasses import dataclass

from camcam.post.text import encode_comment, program_name

__all__ = ["FIELDS", "Template", "parse_template", "MAX_WIDTH", "TemplateError", "check_line", "SAMPLE_VALUES"]

#: Field name → kind: ``comment`` (free text, only inside a comment), ``name`` (a program
#: name), ``word`` (a word camcam checked, e.g. the units word), ``int`` (a whole number).
FIELDS = {"title": "comment", "name": "name", "units": "word", "tool": "int", "spindle": "int",
          "program_number": "int"}

#: Widest zero-padded integer field (digits).
MAX_WIDTH = 9

_INT_SPEC = re.compile(r"(0?[1-9])?d?")

#: Field values a template is rendered with when its code words are checked (an integer
#: field prints its digits whatever the value; a name prints as a program name).
SAMPLE_VALUES = {"title": "t", "name": "camcam", "units": "G21", "tool": 1, "spindle": 1000, "program_number": 1}

#: One G-code word: an address letter and a number (``G21``, ``Z-5.``, ``G43.4``), or a
#: controller keyword of capitals (Sinumerik's ``TRAORI``).  Words are separated by one space;
#: ``%`` (tape start/end) stands alone.  Lowercase, bare numbers, ``#`` parameters, ``=``
#: assignments and block-skip ``/`` are refused: rs274ngc, Fanuc and Sinumerik either reject
#: them or read them as something a header line must not do.
_GCODE_WORD = r"(?:[A-Z][+-]?[0-9]+\.?[0-9]*|[A-Z]{2,}[A-Z0-9_]*)"
_GCODE_LINE = re.compile(rf"{_GCODE_WORD}(?: {_GCODE_WORD})*|%|")

#: A Heidenhain conversational (Klartext) block a post's own lines may print: program begin and end, blank
#: form, tool call or definition, stop, M functions, cycle definition (and its ``~`` continuation) or call,
#: a Q parameter, a straight-line move; or nothing (a comment line).  The TNC refuses any other text, and a
#: line of digits alone (``0``) would read as a bare block number.
_KLARTEXT_LINE = re.compile(
    r"(?:BEGIN|END) PGM [A-Za-z0-9_-]+ MM|BLK FORM 0\.[12](?: [XYZ])?(?: [XYZ][+-]?[0-9.]+)*|"
    r"TOOL (?:CALL|DEF) [0-9]+(?: [XYZ])?(?: [SFDLR][+-]?[0-9.]+)*|STOP(?: M[0-9]+)*|M[0-9]+(?: M[0-9]+)*|"
    r"CYCL DEF [0-9.]+(?: [A-Z]+)*(?: ~)?|CYCL CALL(?: M[0-9]+)*|Q[0-9]+=[+-]?[0-9.]+|"
    r"L(?: [XYZABC][+-][0-9.]+)* R[0LR](?: F(?:MAX|[0-9.]+))?(?: M[0-9]+)*|")

#: What a comment looks like on a rendered line, per comment style (templates are checked
#: closed and unnested before they are rendered).
_COMMENT = {"parentheses": re.compile(r"\([^()]*\)"), "semicolon": re.compile(r";.*")}


class TemplateError(ValueError):
    """A template that is not allowed; the message says why (the caller names the key)."""


@dataclass(frozen=True)
class Part:
    literal: str
    field: str | None
    spec: str
    in_comment: bool


@dataclass(frozen=True)
class Template:
    """A parsed header/footer line."""

    parts: tuple[Part, ...]
    comment: str

    def fields(self) -> set[str]:
        return {p.field for p in self.parts if p.field}

    def width(self, field: str) -> int | None:
        """The zero-padded width ``field`` is printed with, if any."""
        for p in self.parts:
            if p.field == field and p.spec.startswith("0"):
                return int(p.spec.rstrip("d"))
        return None

    def code_text(self) -> str:
        """The literal text outside comments (for checking words such as units)."""
        return " ".join(p.literal for p in self.parts if not p.in_comment)

    def render(self, values: dict, post_name: str = "") -> str:
        out = []
        for p in self.parts:
            out.append(p.literal)
            if p.field is None:
                continue
            kind, v = FIELDS[p.field], values[p.field]
            if kind == "int":
                out.append(format(int(v), p.spec))
            elif p.in_comment:
                out.append(encode_comment(str(v), self.comment))
            elif kind == "name":
                out.append(program_name(str(v), post_name))
            else:
                out.append(str(v))
        return "".join(out)


#: Per dialect: what one of a post's own lines must be, and what the error says was expected.
_DIALECT_LINES = {
    "gcode": (_GCODE_LINE, "is not G-code words (expected words such as G21 or T1 separated by one space, or %)"),
    "heidenhain": (_KLARTEXT_LINE, "is not a Klartext block (expected e.g. BEGIN PGM, TOOL CALL, L ... R0 FMAX, "
                                   "M30, STOP, CYCL DEF, Q1=+1 or END PGM)"),
}


def check_line(template: Template, dialect: str, values: dict = SAMPLE_VALUES) -> None:
    """Raise :class:`TemplateError` unless ``template``'s code text, rendered with ``values``, is a line
    the ``dialect``'s controller reads: G-code words only (``"gcode"``), or one Heidenhain conversational
    block of the kinds a post's own lines print (``"heidenhain"``, see ``_KLARTEXT_LINE``).

    Examples
    --------
    >>> check_line(parse_template("O{program_number:04d} ({title})", "parentheses"), "gcode")
    >>> check_line(parse_template("0", "parentheses"), "gcode")
    Traceback (most recent call last):
    ...
    camcam.post.template.TemplateError: '0' is not G-code words (expected words such as G21 or T1 separated by one space, or %)
    >>> check_line(parse_template("TOOL CALL {tool} Z S{spindle} ; {title}", "semicolon"), "heidenhain")
    >>> check_line(parse_template("0", "semicolon"), "heidenhain")
    Traceback (most recent call last):
    ...
    camcam.post.template.TemplateError: '0' is not a Klartext block (expected e.g. BEGIN PGM, TOOL CALL, L ... R0 FMAX, M30, STOP, CYCL DEF, Q1=+1 or END PGM)
    """
    pattern, expected = _DIALECT_LINES[dialect]
    code = _COMMENT[template.comment].sub("", template.render(values)).strip()
    if not pattern.fullmatch(code):
        raise TemplateError(f"{code!r} {expected}")


def _bad_char(text: str) -> str | None:
    for ch in text:
        if unicodedata.category(ch)[0] in "CZ" and ch != " ":
            return ch
    return None


def _scan(literal: str, comment: str, inside: bool) -> bool:
    """Comment state after ``literal``; raise on a nested or stray comment character."""
    for ch in literal:
        if comment == "semicolon":
            if ch == ";":
                inside = True
            continue
        if inside:
            if ch == "(":
                raise TemplateError("a comment inside a comment")
            if ch == ")":
                inside = False
        elif ch == "(":
            inside = True
        elif ch == ")":
            raise TemplateError('")" closes no comment')
        elif ch == ";":
            raise TemplateError('";" in a post with parentheses comments (it ends a block on Fanuc controls)')
    return inside


def parse_template(line: str, comment: str) -> Template:
    """Parse and check one header/footer line for a post with comment style ``comment``.

    Examples
    --------
    >>> t = parse_template("O{program_number:04d} ({title})", "parentheses")
    >>> t.render({"program_number": 7, "title": "a (b)\\nG0"})
    'O0007 (a [b] G0)'
    >>> parse_template("T{tool:{title.__class__}}", "parentheses")
    Traceback (most recent call last):
    ...
    camcam.post.template.TemplateError: {tool}: a format may not hold a field ({title.__class__})
    """
    if not isinstance(line, str):
        raise TemplateError(f"expected a string, got {line!r}")
    bad = _bad_char(line)
    if bad is not None:
        raise TemplateError(f"character U+{ord(bad):04X} is not allowed (one template is one program line)")
    try:
        parsed = list(string.Formatter().parse(line))
    except ValueError as err:
        raise TemplateError(f"bad template: {err}") from None
    parts, inside = [], False
    for literal, field, spec, conversion in parsed:
        inside = _scan(literal, comment, inside)
        if field is None:
            parts.append(Part(literal, None, "", inside))
            continue
        if field not in FIELDS:
            raise TemplateError(f"unknown field {{{field}}}; known: {', '.join(sorted(FIELDS))} "
                                "(bare names only: no attributes, indexes or positions)")
        if conversion is not None:
            raise TemplateError(f"{{{field}}}: conversions (!{conversion}) are not allowed")
        if "{" in spec or "}" in spec:
            raise TemplateError(f"{{{field}}}: a format may not hold a field ({spec})")
        kind = FIELDS[field]
        if kind == "int":
            if not _INT_SPEC.fullmatch(spec):
                raise TemplateError(f"{{{field}}}: format {spec!r} not allowed; expected none, \"d\" or a width "
                                    f"of 1-{MAX_WIDTH} digits (\"04d\")")
        elif spec:
            raise TemplateError(f"{{{field}}}: a text field takes no format, got {spec!r}")
        if kind == "comment" and not inside:
            raise TemplateError(f"{{{field}}} must be inside a comment")
        parts.append(Part(literal, field, spec, inside))
    if inside and comment == "parentheses":
        raise TemplateError("a comment is not closed")
    return Template(tuple(parts), comment)
