"""The program writer: a neutral :class:`~camcam.toolpath.path.Toolpath` + a :class:`Post` → text.

Coordinates are printed from integers on the 10^−d grid, so the same input
gives the same bytes.  After the post's header come the generator line
(camcam's version and the spec's file name, no date), the work offset, the
tool length offset and coolant on (:class:`~camcam.nc.settings.ProgramSetup`);
coolant off precedes the footer.  The writer records every move it prints,
from the printed numbers (``Program.printed_moves``, timed by
:mod:`camcam.verify.cycle_time`).  Arcs print X/Y and I/J (incremental or absolute) or R,
or Heidenhain's CC/C pair.  A 4-axis path (``rotary``) is printed in inverse
time (G93): every feed move carries F = feed / move length (1/min).  A 5-axis
path (``five_axis``: X Y Z = tool tip, A, B) sits between the post's
``tcp_on`` and ``tcp_off`` blocks; Heidenhain prints it with M128 and the
tool tip's feed in mm/min (Klartext has no inverse time).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

from camcam.errors import InputError, PostError
from camcam.nc.result import Program
from camcam import __version__
from camcam.nc.settings import ProgramSetup
from camcam.post.template import parse_template
from camcam.post.text import encode_comment
from camcam.toolpath.arcsweep import printed_sweep_rad
from camcam.toolpath.elements import Arc
from camcam.toolpath.path import ArcMove, Comment, Feed, Rapid, Toolpath

if TYPE_CHECKING:  # annotations only: post.post imports this module to print its programs
    from camcam.post.post import Post

__all__ = ["Program", "write_program", "format_number", "printed_elements"]


def format_number(v: float, post: Post, signed: bool = False) -> str:
    """``v`` rounded to the post's decimals, trailing zeros dropped.

    Examples
    --------
    >>> from camcam.post.post import load_post
    >>> format_number(10.0, load_post("fanuc")), format_number(-0.00001, load_post("linuxcnc"))
    ('10.', '0')
    >>> format_number(2.5, load_post("heidenhain"), signed=True)
    '+2.5'
    """
    return _fmt_int(post.quantizer.count(v), post, signed)


def _fmt_int(n: int, post: Post, signed: bool = False) -> str:
    d = post.decimals
    sign = "-" if n < 0 else ("+" if signed else "")
    whole, frac = divmod(abs(n), 10**d)
    fs = f"{frac:0{d}d}".rstrip("0")
    if fs:
        return f"{sign}{whole}.{fs}"
    return f"{sign}{whole}." if post.decimal_point_always else f"{sign}{whole}"


def printed_elements(elements, post: Post) -> tuple:
    """The contour as the controller will cut it from the printed numbers (:meth:`Quantizer.printed_elements`)."""
    return post.quantizer.printed_elements(elements)


class _Writer:
    def __init__(self, post: Post):
        self.post = post
        self.lines: list[str] = []
        self.pos = [None, None, None]  # printed grid integers
        self.rot = {"A": None, "B": None}
        self.feed = None
        self.counts = {"line": 0, "arc": 0, "rapid": 0}
        self.count = post.quantizer.count
        self.log: list[tuple] = []  # the moves as printed (Program.printed_moves)

    def where(self) -> tuple[float, float, float]:
        """The printed position in mm (an axis never stated counts as 0, as rs274 starts)."""
        scale = 10.0 ** -self.post.decimals
        return tuple(0.0 if v is None else v * scale for v in self.pos)

    def a_now(self) -> float:
        """The printed A in degrees (0 until stated, as rs274 starts)."""
        return 0.0 if self.rot["A"] is None else self.rot["A"] * 10.0 ** -self.post.decimals

    def per_mm(self, count: int) -> float:
        return count * 10.0 ** -self.post.decimals

    def n(self, v, signed=False):
        return _fmt_int(v, self.post, signed)

    def emit(self, text: str):
        self.lines.append(text)

    def f_word(self, value: float) -> str:
        """``F…`` for a feed (mm/min, or 1/min in inverse time); never ``F0``."""
        g = self.count(value)
        if g <= 0:
            raise InputError(f"machining.feed: {value:g} would print as F0 with post {self.post.name}'s "
                             f"{self.post.decimals} decimals")
        return f"F{self.n(g)}"

    def comment(self, text: str) -> str:
        text = encode_comment(text, self.post.comment)
        return f"({text})" if self.post.comment == "parentheses" else f"; {text}"

    # -- G-code ---------------------------------------------------------------------
    def axes(self, x, y, z, force_xy=False):
        words = []
        for i, (name, v) in enumerate(zip("XYZ", (x, y, z))):
            if v is None:
                continue
            g = self.count(v)
            if g != self.pos[i] or (force_xy and i < 2):
                words.append(f"{name}{self.n(g)}")
            self.pos[i] = g
        return words

    def rotary_words(self, m) -> list[str]:
        """A and B words of a move that changes them (degrees, on the post's grid)."""
        words = []
        for name, v in (("A", m.a_deg), ("B", m.b_deg)):
            if v is None:
                continue
            g = self.count(v)
            if g != self.rot[name]:
                words.append(f"{name}{self.n(g, self.post.dialect == 'heidenhain')}")
            self.rot[name] = g
        return words

    def gcode_move(self, m, rotary: bool):
        d = self.post.decimals
        if isinstance(m, Comment):
            self.emit(self.comment(m.text))
            self.log.append(("comment", m.text))
            return
        before, a_before = self.where(), self.a_now()
        if isinstance(m, Rapid):
            w = self.axes(m.x, m.y, m.z) + self.rotary_words(m)
            if w:
                self.emit("G0 " + " ".join(w))
                self.counts["rapid"] += 1
                self.log.append(("rapid", before, self.where()))
            return
        if isinstance(m, Feed):
            w = self.axes(m.x, m.y, m.z) + self.rotary_words(m)
            if not w:
                return
            if rotary:
                inv = m.feed_mm_min / max(m.length_mm, 10.0**-d)
                w.append(self.f_word(inv))
                self.log.append(("inverse", before, self.where(), self.per_mm(self.count(inv)), a_before, self.a_now()))
            else:
                if m.feed_mm_min != self.feed:
                    w.append(self.f_word(m.feed_mm_min))
                    self.feed = m.feed_mm_min
                self.log.append(("line", before, self.where(), self.per_mm(self.count(m.feed_mm_min)), 0.0, 0.0))
            self.emit("G1 " + " ".join(w))
            self.counts["line"] += 1
            return
        sx, sy = self.pos[0], self.pos[1]
        ex, ey = self.count(m.x), self.count(m.y)
        cx, cy = self.count(m.cx), self.count(m.cy)
        self.check_arc(sx, sy, ex, ey, cx, cy, m.ccw)
        zw = self.axes(None, None, m.z)
        self.pos[0], self.pos[1] = ex, ey
        w = [f"X{self.n(ex)}", f"Y{self.n(ey)}"] + zw
        if self.post.arc_format == "ij_incremental":
            w += [f"I{self.n(cx - sx)}", f"J{self.n(cy - sy)}"]
        elif self.post.arc_format == "ij_absolute":
            w += [f"I{self.n(cx)}", f"J{self.n(cy)}"]
        else:
            w += [f"R{self.n(self.post.quantizer.radius_word((sx, sy), (cx, cy)))}"]  # the fitter's R model
        if m.feed_mm_min != self.feed:
            w.append(self.f_word(m.feed_mm_min))
            self.feed = m.feed_mm_min
        self.log.append(("arc", before, self.where(), (self.per_mm(cx), self.per_mm(cy)), m.ccw,
                       self.per_mm(self.count(m.feed_mm_min))))
        self.emit(("G3 " if m.ccw else "G2 ") + " ".join(w))
        self.counts["arc"] += 1

    def check_arc(self, sx, sy, ex, ey, cx, cy, ccw):
        if sx is None or sy is None:
            raise PostError("toolpath: an arc move before any XY position")
        scale = 10.0 ** -self.post.decimals
        r0 = math.hypot(sx - cx, sy - cy) * scale
        r1 = math.hypot(ex - cx, ey - cy) * scale
        if abs(r0 - r1) > self.post.max_radius_error_mm:
            raise PostError(f"arc to X{ex * scale:g} Y{ey * scale:g}: start/end radius differ by {abs(r0 - r1):.4g} mm "
                                f"after rounding (post {self.post.name} allows {self.post.max_radius_error_mm:g})")
        if (sx, sy) == (ex, ey):
            raise PostError(f"arc at X{sx * scale:g} Y{sy * scale:g} would be a full circle")
        # the sweep the controller cuts from these printed numbers, as the planners judged it (arcsweep)
        sweep = math.degrees(printed_sweep_rad(Arc((sx * scale, sy * scale), (ex * scale, ey * scale),
                                                   (cx * scale, cy * scale), ccw), self.post.quantizer))
        if sweep > self.post.max_arc_sweep_deg:
            raise PostError(f"arc to X{ex * scale:g} Y{ey * scale:g} sweeps {sweep:.3f}° > post {self.post.name}'s "
                                f"max_arc_sweep_deg {self.post.max_arc_sweep_deg:g}")

    # -- Heidenhain --------------------------------------------------------------------
    def hh_helix(self, m, before) -> bool:
        """A helical arc (a ramped entry, a helical bore): Klartext programs a helix only in polar coordinates,
        ``CC`` (the pole: the centre) then ``CP IPA… IZ… DR…`` (the incremental polar angle and Z travel), as
        HEIDENHAIN's TNC manuals state ("A helix is programmed only in polar coordinates").  The angle is the
        sweep from the printed start to the printed end about the printed centre, printed to 1e-4°; the
        controller ends the helix on the start's radius, within the arc check's radius error of the printed end."""
        sx, sy, sz = self.pos
        ex, ey, ez, cx, cy = (self.count(v) for v in (m.x, m.y, m.z, m.cx, m.cy))
        self.check_arc(sx, sy, ex, ey, cx, cy, m.ccw)
        a0, a1 = math.atan2(sy - cy, sx - cx), math.atan2(ey - cy, ex - cx)
        sweep = math.degrees((a1 - a0) % (2 * math.pi) if m.ccw else -((a0 - a1) % (2 * math.pi)))
        if abs(sweep) < 1e-4:  # a full turn: the printed ends coincide
            sweep = 360.0 if m.ccw else -360.0
        self.emit(f"CC X{self.n(cx, True)} Y{self.n(cy, True)}")
        self.emit(f"CP IPA{sweep:+.4f} IZ{self.n(ez - sz, True)} DR{'+' if m.ccw else '-'} R0 {self.f_word(m.feed_mm_min)}")
        self.pos[0], self.pos[1], self.pos[2] = ex, ey, ez
        self.counts["arc"] += 1
        self.log.append(("arc", before, self.where(), (self.per_mm(cx), self.per_mm(cy)), m.ccw,
                         self.per_mm(self.count(m.feed_mm_min))))
        return False

    def hh_move(self, m, first_words: str, five_axis: bool = False) -> bool:
        """One move; ``first_words`` (spindle and coolant on) go on it if it prints an L block (then True)."""
        if isinstance(m, Comment):
            self.emit(self.comment(m.text))
            self.log.append(("comment", m.text))
            return False
        before, a_before = self.where(), self.a_now()
        if isinstance(m, Feed) and m.a_deg is not None and not five_axis:
            raise InputError(f"post {self.post.name}: 4-axis programs are not supported by this dialect")
        if isinstance(m, ArcMove):
            if self.pos[2] is not None and self.count(m.z) != self.pos[2]:
                return self.hh_helix(m, before)
            sx, sy = self.pos[0], self.pos[1]
            ex, ey, cx, cy = (self.count(v) for v in (m.x, m.y, m.cx, m.cy))
            self.check_arc(sx, sy, ex, ey, cx, cy, m.ccw)
            self.emit(f"CC X{self.n(cx, True)} Y{self.n(cy, True)}")
            self.pos[0], self.pos[1] = ex, ey
            self.emit(f"C X{self.n(ex, True)} Y{self.n(ey, True)} DR{'+' if m.ccw else '-'} R0 {self.f_word(m.feed_mm_min)}")
            self.counts["arc"] += 1
            self.log.append(("arc", before, self.where(), (self.per_mm(cx), self.per_mm(cy)), m.ccw,
                           self.per_mm(self.count(m.feed_mm_min))))
            return False
        words = []
        for i, (name, v) in enumerate(zip("XYZ", (m.x, m.y, m.z))):
            if v is None:
                continue
            g = self.count(v)
            if g != self.pos[i]:
                words.append(f"{name}{self.n(g, True)}")
            self.pos[i] = g
        if five_axis:
            words += self.rotary_words(m)
        if not words:
            return False
        rapid = isinstance(m, Rapid)
        f = "FMAX" if rapid else self.f_word(m.feed_mm_min)
        self.emit(f"L {' '.join(words)} R0 {f}" + (f" {first_words}" if first_words else ""))
        self.counts["rapid" if rapid else "line"] += 1
        if rapid:
            self.log.append(("rapid", before, self.where()))
        else:  # under M128 F is the tool tip's feed along its path in the part (A turning with it)
            self.log.append(("line", before, self.where(), self.per_mm(self.count(m.feed_mm_min)), a_before, self.a_now()))
        return True


@dataclass(frozen=True)
class _Spindle:
    """A spindle speed change the writer prints with the post's spindle line."""

    rpm: int


def _with_spindle(toolpath: Toolpath):
    """``toolpath.moves``, with a :class:`_Spindle` after a pass's opening comments where its speed changes."""
    now = int(round(toolpath.spindle_rpm))
    yield from toolpath.opening
    for p in toolpath.passes:
        rpm = now if p.spindle_rpm is None else int(round(p.spindle_rpm))
        k = next((i for i, m in enumerate(p.moves) if not isinstance(m, Comment)), len(p.moves))
        yield from p.moves[:k]
        if rpm != now:
            yield _Spindle(rpm)
            now = rpm
        yield from p.moves[k:]
    yield from toolpath.closing


def write_program(toolpath: Toolpath, post: Post, name: str = "camcam", setup: ProgramSetup = ProgramSetup()) -> Program:
    """Print ``toolpath`` for ``post`` with the work offset, coolant and program number of ``setup``.

    Examples
    --------
    >>> from camcam.post.post import load_post
    >>> tp = Toolpath.of_moves("demo", (Rapid(0.0, 0.0, 5.0), Feed(10.0, 0.0, 5.0, 300.0)), 1000)
    >>> p = write_program(tp, load_post("linuxcnc"))
    >>> print(p.text.splitlines()[-4])
    G1 X10 F300
    >>> p.text.splitlines()[5:8]
    ['G54', 'G43 H1', 'M8']
    >>> [m[0] for m in p.printed_moves]  # timed by camcam.verify.cycle_time
    ['tool change', 'rapid', 'line']
    """
    if toolpath.five_axis and not post.five_axis:
        raise InputError(f"post {post.name}: has no 5-axis mode (tool-centre-point control); use axes = 4 "
                         f"or a post with one")
    if toolpath.rotary and not toolpath.five_axis and not post.inverse_time:
        raise InputError(f"post {post.name}: has no inverse-time feed (G93) for a 4-axis program")
    if toolpath.five_axis and post.dialect != "heidenhain" and not post.inverse_time:
        raise InputError(f"post {post.name}: has no inverse-time feed (G93) for a 5-axis program")
    setup.check(post)
    number = post.program_number if setup.program_number is None else setup.program_number
    fields = {"title": toolpath.title, "name": name, "units": post.units,
              "tool": toolpath.tool_number, "spindle": int(round(toolpath.spindle_rpm)),
              "program_number": number}
    for key in ("tool", "spindle"):
        if fields[key] < 1:
            raise InputError(f"{key}: {fields[key]} would print as {key[0].upper()}{fields[key]}; expected at least 1")

    def lines(templates):
        return [parse_template(t, post.comment).render(fields, post.name) for t in templates]

    def spindle_line(rpm: int) -> str:
        """The header's spindle line (``S{spindle} M3``, Heidenhain's ``TOOL CALL``) at a pass's own speed."""
        line = next((t for t in post.header if "{spindle" in t), None)
        if line is None:
            raise InputError(f"post {post.name}: its header has no {{spindle}} line to print a pass's spindle "
                             f"speed with")
        return parse_template(line, post.comment).render({**fields, "spindle": rpm}, post.name)

    w = _Writer(post)
    body: list[str] = []
    body += lines(post.header)
    body.append(w.comment(f"camcam {__version__}" + (f", spec {setup.source}" if setup.source else "")))
    for c in toolpath.comments:
        body.append(w.comment(c))
    body += lines(post.work_offset_lines(setup.work_offset))
    if post.tool_length_offset:
        body += lines((post.tool_length_offset,))
    coolant_on, coolant_off = post.coolant_word(setup.coolant), post.coolant_off
    if post.tool_change:
        w.log.append(("tool change", post.tool_change_s))
    tcp_on = lines(post.tcp_on) if toolpath.five_axis else []
    tcp_off = lines(post.tcp_off) if toolpath.five_axis else []
    if post.dialect == "heidenhain":
        # Klartext has no inverse time: with M128 the programmed F is the tool tip's feed (mm/min)
        w.lines += tcp_on
        first = f"M3 {coolant_on}"  # spindle and coolant on ride on the first L block (comments are not moves)
        for m in _with_spindle(toolpath):
            if isinstance(m, _Spindle):
                w.emit(spindle_line(m.rpm))
            elif w.hh_move(m, first, toolpath.five_axis):
                first = ""
        last = max(i for i, line in enumerate(w.lines) if line.startswith("L "))
        w.lines[last] += f" {coolant_off}"
        w.lines += tcp_off
    else:
        body.append(coolant_on)
        w.lines += tcp_on
        if toolpath.rotary:
            w.emit("G93")
        for m in _with_spindle(toolpath):
            if isinstance(m, _Spindle):
                w.emit(spindle_line(m.rpm))
            else:
                w.gcode_move(m, toolpath.rotary)
        if toolpath.rotary:
            w.emit("G94")
        w.lines += tcp_off
        w.emit(coolant_off)
    body += w.lines
    body += lines(post.footer)
    out = []
    k = post.line_number_start
    for line in body:
        numbered = post.line_numbers and not line[:1].isspace() and (
            post.dialect == "heidenhain" or not (line.startswith("%") or line.startswith("O")))
        if numbered:
            if k > post.max_line_number:
                raise InputError(f"post {post.name}: the program needs block numbers past max_line_number = "
                                 f"{post.max_line_number}; set line_numbers = false or a smaller line_number_step")
            out.append(f"{k} {line}" if post.dialect == "heidenhain" else f"N{k} {line}")
            k += post.line_number_step
        else:
            out.append(line)
    return Program(text="\n".join(out) + "\n", extension=post.extension, line_blocks=w.counts["line"],
                   arc_blocks=w.counts["arc"], rapid_blocks=w.counts["rapid"],
                   printed_moves=tuple(w.log))
