"""Read our own printed programs back: the moves a controller would make, from the printed numbers.

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

from dataclasses import dataclass

__all__ = ["read_program", "Move"]


@dataclass(frozen=True)
class Move:
    """One move read back (the fields of :class:`camcam.verify.rs274.CanonMove`): ``kind`` "rapid", "line" or "arc"."""

    kind: str
    x: float
    y: float
    z: float
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
            out.append(Move("rapid" if mode == 0 else "line", nx, ny, nz, 0.0))
            moved = True
        elif mode in (2, 3):
            ccw = mode == 3
            if "R" in vals:
                cx, cy = _r_centre(x, y, nx, ny, vals["R"], ccw)
            elif post.arc_format == "ij_absolute":
                cx, cy = vals.get("I", x), vals.get("J", y)
            else:
                cx, cy = x + vals.get("I", 0.0), y + vals.get("J", 0.0)
            out.append(Move("arc", nx, ny, nz, 0.0, (cx, cy), ccw))
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
            out.append(Move("rapid" if "FMAX" in line else "line", nx, ny, nz, 0.0))
        elif head == "C":
            if cc is None:
                raise ValueError(f"line {no}: C without CC: {raw.strip()!r}")
            nx, ny, nz = vals.get("X", x), vals.get("Y", y), z
            out.append(Move("arc", nx, ny, nz, 0.0, cc, "DR+" in line))
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
