"""Read our own printed programs back: the moves a controller would make, from the printed numbers.

Every dialect's reader lives here, beside its writer (:mod:`camcam.post.gcode`):
:func:`read_program` for 2.5-D programs and :func:`read_poses` for the 4- and
5-axis poses of a barrel cam (:class:`~camcam.toolpath.poses.ToolPoses`).
:mod:`camcam.verify` measures what they read.

This is the in-process twin of :func:`camcam.verify.rs274.run_rs274` (same move fields) for the
report (every post, no external program): G-code (G0/G1/G2/G3 with X Y Z,
I J incremental or absolute, or R; modal motion and coordinates; ``N``
numbers; parenthesis or semicolon comments) and Heidenhain conversational
(``L … R0 FMAX``/``F``, ``CC`` + ``C … DR±``).  Comments come back as
strings between the moves, so the pass names the program prints travel with
it.  Only what our posts print is read; anything else raises ``ValueError``
naming the line.
"""

from __future__ import annotations

import math
import re

from dataclasses import KW_ONLY, dataclass

import numpy as np

from camcam.toolpath.poses import ToolPoses

__all__ = ["read_program", "Move", "read_poses", "poses_from_program", "klartext_as_gcode"]


@dataclass(frozen=True)
class Move:
    """One move read back (the fields of :class:`camcam.verify.rs274.CanonMove`): ``kind`` "rapid", "line" or "arc"."""

    kind: str
    x: float
    y: float
    z: float
    _: KW_ONLY
    a: float = 0.0
    centre: tuple[float, float] | None = None
    ccw: bool = False

_WORD = re.compile(r"([A-Z]+)\s*([+-]?(?:\d+\.?\d*|\.\d+))")
_PAREN = re.compile(r"\(([^)]*)\)")


def _r_centre(sx, sy, ex, ey, r, ccw):
    """Centre of the short arc of radius r from s to e (as :func:`camcam.post.gcode.printed_elements`)."""
    mx, my = (sx + ex) / 2, (sy + ey) / 2
    vx, vy = ex - sx, ey - sy
    half = math.hypot(vx, vy) / 2
    h = math.sqrt(max(r * r - half * half, 0.0))
    nx, ny = -vy / (2 * half), vx / (2 * half)
    side = 1.0 if ccw else -1.0
    return mx + side * h * nx, my + side * h * ny


def _gcode(text: str, post) -> list:
    out: list = []
    x = y = z = 0.0
    mode = None
    for no, raw in enumerate(text.splitlines(), 1):
        line = raw.strip()
        if post.comment == "semicolon" and ";" in line:
            line, comment = line.split(";", 1)
            out.append(comment.strip())
        for c in _PAREN.findall(line):
            out.append(c.strip())
        line = _PAREN.sub(" ", line).strip()
        if not line or line.startswith("%") or re.match(r"^O\d+", line):
            continue
        words = _WORD.findall(line.upper())
        vals: dict[str, float] = {}
        moved = False
        for letter, num in words:
            if letter == "N":
                continue
            if letter == "G":
                g = float(num)
                if g in (0, 1, 2, 3):
                    mode = int(g)
                continue
            vals[letter] = float(num)
        if not any(k in vals for k in "XYZ"):
            continue
        nx, ny, nz = vals.get("X", x), vals.get("Y", y), vals.get("Z", z)
        if mode in (0, 1):
            out.append(Move("rapid" if mode == 0 else "line", nx, ny, nz, a=0.0))
            moved = True
        elif mode in (2, 3):
            ccw = mode == 3
            if "R" in vals:
                cx, cy = _r_centre(x, y, nx, ny, vals["R"], ccw)
            elif post.arc_format == "ij_absolute":
                cx, cy = vals.get("I", x), vals.get("J", y)
            else:
                cx, cy = x + vals.get("I", 0.0), y + vals.get("J", 0.0)
            out.append(Move("arc", nx, ny, nz, a=0.0, centre=(cx, cy), ccw=ccw))
            moved = True
        if not moved:
            raise ValueError(f"line {no}: coordinates without a motion mode: {raw.strip()!r}")
        x, y, z = nx, ny, nz
    return out


def _heidenhain(text: str) -> list:
    out: list = []
    x = y = z = 0.0
    cc = None
    for no, raw in enumerate(text.splitlines(), 1):
        line = re.sub(r"^\d+\s+", "", raw.strip())
        if ";" in line:
            line, comment = line.split(";", 1)
            out.append(comment.strip())
        line = line.strip()
        if not line:
            continue
        head = line.split()[0]
        vals = {k: float(v) for k, v in _WORD.findall(line) if k in ("X", "Y", "Z")}
        if head == "CC":
            cc = (vals["X"], vals["Y"])
            continue
        if head == "L":
            nx, ny, nz = vals.get("X", x), vals.get("Y", y), vals.get("Z", z)
            out.append(Move("rapid" if "FMAX" in line else "line", nx, ny, nz, a=0.0))
        elif head == "C":
            if cc is None:
                raise ValueError(f"line {no}: C without CC: {raw.strip()!r}")
            nx, ny, nz = vals.get("X", x), vals.get("Y", y), z
            out.append(Move("arc", nx, ny, nz, a=0.0, centre=cc, ccw="DR+" in line))
        elif head == "CP":  # a helix about the pole CC: incremental polar angle IPA and Z travel IZ
            inc = {k: float(v) for k, v in _WORD.findall(line) if k in ("IPA", "IZ")}
            if cc is None or "IPA" not in inc:
                raise ValueError(f"line {no}: CP needs a pole (CC) and IPA: {raw.strip()!r}")
            r, a0 = math.hypot(x - cc[0], y - cc[1]), math.atan2(y - cc[1], x - cc[0])
            a1 = a0 + math.radians(inc["IPA"])
            nx, ny, nz = cc[0] + r * math.cos(a1), cc[1] + r * math.sin(a1), z + inc.get("IZ", 0.0)
            out.append(Move("arc", nx, ny, nz, a=0.0, centre=cc, ccw="DR+" in line))
        else:
            continue
        x, y, z = nx, ny, nz
    return out


def read_program(text: str, post) -> list:
    """Moves (:class:`Move`) and comments (str) of a program printed for ``post`` (its dialect, comment and arc format).

    Examples
    --------
    >>> from camcam.post.post import load_post
    >>> ev = read_program("(pass 1/1: rough)\\nG0 X10 Y0\\nG1 Z-2 F100\\nG3 X0 Y10 I-10 J0\\nM2\\n", load_post("linuxcnc"))
    >>> ev[0], ev[-1].kind, ev[-1].centre
    ('pass 1/1: rough', 'arc', (0.0, 0.0))
    """
    return _heidenhain(text) if post.dialect == "heidenhain" else _gcode(text, post)


# -- 4- and 5-axis poses ------------------------------------------------------------------
_AXIS_WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")
_COMMENT = re.compile(r"\([^)]*\)|;.*$")


def poses_from_program(text: str, a_axis: str = "right-hand", assume: dict | None = None) -> ToolPoses:
    """Tool poses read back from a printed G-code program (G0/G1 with X Y Z A B, modal).

    Poses start once X, Y, Z and A are all known (B is 0 until given);
    ``assume`` gives axis values a program never prints (e.g. ``{"Y": 0.0}``
    for a program that leaves Y where the machine has it).  G90/G91 set
    absolute/incremental words.  A block with G28 (return to the reference
    point, Fanuc's ``G91 G28 Z0.``) or G53 (machine coordinates, Haas's
    ``G53 G00 Z0.``) leaves the work frame: its words are no work-frame
    position, so they are not read as one (they were: ``Z0.`` put the tool on
    the cam axis, issue 43, a 2.1 mm "overcut" at the seam of a 5-axis
    program).  G28's intermediate point is a work-frame move and is read; the
    retract itself goes up machine Z to the top of the travel, which the
    reader takes as far as the highest Z the program printed (a pure +Z move
    from there only goes farther from the part); the axes it names are
    unknown after it, and a later move that would need them is refused.
    Arcs (G2/G3) are refused: a barrel-cam program has none.

    Examples
    --------
    >>> p = poses_from_program("G0 X0 Y0 Z60 A0\\nG1 X10 A90 F3\\nM2\\n")
    >>> p.tip_mm.tolist(), p.a_deg.tolist()
    ([[0.0, 0.0, 60.0], [10.0, 0.0, 60.0]], [0.0, 90.0])
    >>> p = poses_from_program("G0 X0 Y0 Z60 A0\\nG1 X10 Z40 A90 F3\\nG0 Z60\\nG91 G28 Z0.\\nM30\\n")
    >>> p.tip_mm[:, 2].tolist()
    [60.0, 40.0, 60.0]
    """
    pos = {"X": None, "Y": None, "Z": None, "A": None, "B": 0.0}
    pos.update(assume or {})
    motion = None
    incremental = False
    homed: set[str] = set()  # axes a reference return left at a place the work frame cannot name
    top = -np.inf  # the highest tip Z printed
    rows = []

    def add(retract: bool = False) -> None:
        if motion is not None and all(pos[k] is not None for k in "XYZA"):
            row = (pos["X"], pos["Y"], pos["Z"], pos["A"], pos["B"])
            if not (retract and rows and rows[-1] == row):
                rows.append(row)

    for raw in text.splitlines():
        line = _COMMENT.sub("", raw.upper()).strip()
        if not line or line.startswith("%") or line.startswith("O"):
            continue
        words = _AXIS_WORD.findall(line)
        gs = [float(num) for letter, num in words if letter == "G"]
        for g in gs:
            if g in (0.0, 1.0):
                motion = int(g)
            elif g in (2.0, 3.0):
                raise ValueError(f"arc move in a barrel-cam program: {raw.strip()!r}")
        incremental = (incremental or 91.0 in gs) and 90.0 not in gs
        axes = [(letter, float(num)) for letter, num in words if letter in pos]
        if not axes:
            continue
        if homed:
            raise ValueError(f"a move after a return to the machine's reference point: {raw.strip()!r}")
        if 28.0 in gs or 53.0 in gs:
            if 28.0 in gs:  # the intermediate point first, in the work frame
                for letter, v in axes:
                    if incremental and pos[letter] is None:
                        raise ValueError(f"incremental move of an unknown axis {letter}: {raw.strip()!r}")
                    pos[letter] = pos[letter] + v if incremental else v
                add(retract=True)
            if "Z" in dict(axes) and pos["Z"] is not None:  # up machine Z, at least as high as the program went
                pos["Z"] = max(pos["Z"], top)
                add(retract=True)
            homed.update(letter for letter, _ in axes)
            continue
        for letter, v in axes:
            if incremental and pos[letter] is None:
                raise ValueError(f"incremental move of an unknown axis {letter}: {raw.strip()!r}")
            pos[letter] = pos[letter] + v if incremental else v
        if pos["Z"] is not None:
            top = max(top, pos["Z"])
        add()
    if len(rows) < 2:
        raise ValueError("the program positions X, Y, Z and A fewer than twice")
    arr = np.array(rows)
    return ToolPoses(arr[:, :3], arr[:, 3], arr[:, 4], a_axis)


def klartext_as_gcode(text: str) -> str:
    """A Heidenhain program's straight-line blocks as G0/G1 lines (same words), for the pose reader.

    ``L X+1 Z+2 A+3 B+4 R0 F100`` → ``G1 X+1 Z+2 A+3 B+4``; ``FMAX`` makes a G0; other blocks are dropped.

    Examples
    --------
    >>> klartext_as_gcode("7 L X+1 Z+2 A+3 B+4 R0 F100\\n8 L Z+60 R0 FMAX\\n")
    'G1 X+1 Z+2 A+3 B+4\\nG0 Z+60\\n'
    """
    out = []
    for line in text.splitlines():
        words = line.split()
        if len(words) > 1 and words[0].isdigit() and words[1] == "L":
            axes = [w for w in words[2:] if w[0] in "XYZAB"]
            out.append(("G0 " if "FMAX" in words else "G1 ") + " ".join(axes))
    return "\n".join(out) + "\n"


def read_poses(text: str, post, a_axis: str = "right-hand") -> ToolPoses:
    """The tool poses of a 4- or 5-axis program printed for ``post`` (:func:`poses_from_program`; a Klartext
    program's L blocks are read as the G-code they say, :func:`klartext_as_gcode`)."""
    return poses_from_program(klartext_as_gcode(text) if post.dialect == "heidenhain" else text, a_axis)
