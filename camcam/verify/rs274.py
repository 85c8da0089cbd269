"""Run LinuxCNC's standalone interpreter on a program and rebuild the path it would cut.

``rs274 -g FILE < /dev/null`` prints canonical moves, one per line::

    STRAIGHT_TRAVERSE(x, y, z, a, b, c)        G0
    STRAIGHT_FEED(x, y, z, a, b, c)            G1
    ARC_FEED(first_end, second_end, first_axis, second_axis, rotation, axis_end, a, b, c)

In G17 ``first`` is X and ``second`` Y (in G18 first is Z: only G17 arcs are
accepted here).  Numbers carry 4 decimals, so a program printed with at most
4 decimals is reproduced exactly; otherwise each coordinate may be off by
0.5·10⁻⁴ mm (:func:`print_margin_mm`).
"""

from __future__ import annotations

import re
import shutil
import subprocess
from dataclasses import KW_ONLY, dataclass
from pathlib import Path

import numpy as np

from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.poses import ToolPoses

__all__ = ["CanonMove", "rs274_available", "run_rs274", "feed_passes", "print_margin_mm", "tcp_readable",
           "poses_from_canon"]

_MOVE = re.compile(r"\b(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|SELECT_PLANE|COMMENT)\((.*)\)\s*$")


@dataclass(frozen=True)
class CanonMove:
    """One interpreted move: ``kind`` is "rapid", "line" or "arc"; ends in program units."""

    kind: str
    x: float
    y: float
    z: float
    _: KW_ONLY
    a: float
    centre: tuple[float, float] | None = None
    ccw: bool = False
    turns: int = 0
    b: float = 0.0


def rs274_available() -> bool:
    return shutil.which("rs274") is not None


def print_margin_mm(decimals: int) -> float:
    """Deviation rs274's 4-decimal printing may add to a program printed with ``decimals``."""
    return 0.0 if decimals <= 4 else 3 * 0.5 * 2**0.5 * 1e-4


def run_rs274(path: str | Path, timeout_s: float = 60.0, comments: bool = False,
              ini: str | Path | None = None) -> list:
    """Interpret ``path`` (with ``ini``: ``rs274 -i INI``); raise ``RuntimeError`` with rs274's message if it
    rejects the program.

    With ``comments`` the program's comments (``COMMENT("…")``, without rs274's
    own ``interpreter: …`` notes) come back as strings between the moves.
    """
    cmd = ["rs274"] + (["-i", str(ini)] if ini is not None else []) + ["-g", str(path)]
    proc = subprocess.run(cmd, stdin=subprocess.DEVNULL, capture_output=True, text=True, timeout=timeout_s)
    if proc.returncode != 0:
        msg = " / ".join(line.strip() for line in proc.stderr.splitlines() if line.strip())
        raise RuntimeError(f"rs274 rejected {path}: {msg}")
    moves: list[CanonMove] = []
    plane = "CANON_PLANE_XY"
    for line in proc.stdout.splitlines():
        m = _MOVE.search(line)
        if not m:
            continue
        kind, args = m.group(1), m.group(2)
        if kind == "COMMENT":
            text = args.strip().strip('"')
            if comments and not text.startswith("interpreter:"):
                moves.append(text)
            continue
        if kind == "SELECT_PLANE":
            plane = args.strip()
            continue
        v = [float(x) for x in args.replace(" ", "").split(",")]
        if kind == "ARC_FEED":
            if plane != "CANON_PLANE_XY":
                raise RuntimeError(f"arc in {plane}: only G17 arcs are expected")
            x, y, cx, cy, rot, z, a = v[:7]
            moves.append(CanonMove("arc", x, y, z, a=a, centre=(cx, cy), ccw=rot > 0, turns=int(abs(rot)) - 1))
        else:
            moves.append(CanonMove("rapid" if kind == "STRAIGHT_TRAVERSE" else "line", *v[:3], a=v[3], b=v[4]))
    return moves


#: rs274 knows no tool-centre-point codes: Fanuc's G43.4 is remapped to an empty subroutine (REMAP
#: accepts G codes in modal group 1 only here); Haas's G234 it cannot even parse ("G-code out of
#: range": G numbers stop at 99.9), so that one block is turned into a comment.  Neither changes a
#: coordinate: rs274 prints programmed positions (a length offset appears only in USE_TOOL_LENGTH_OFFSET).
_REMAPS = {"G43.4": "g43_4"}


def tcp_readable(text: str, tcp_on: tuple[str, ...], workdir: str | Path) -> tuple[Path, Path | None]:
    """Write a 5-axis program where rs274 can read it: ``(program path, ini path or None)``.

    ``tcp_on`` are the post's blocks that switch tool-centre-point control on (as printed).
    """
    workdir = Path(workdir)
    ini_lines, out = [], []
    for line in text.splitlines():
        words = line.split()
        block = " ".join(w for w in words if not (w[0] == "N" and w[1:].isdigit()))
        if block in tcp_on:
            code = block.split()[0]
            if code in _REMAPS:
                sub = workdir / f"{_REMAPS[code]}.ngc"
                sub.write_text(f"o<{_REMAPS[code]}> sub\no<{_REMAPS[code]}> endsub\nM2\n")
                ini_lines.append(f"REMAP={code} modalgroup=1 argspec=H ngc={_REMAPS[code]}")
            else:
                line = f"({block.replace('(', '[').replace(')', ']')}: tool-centre-point control, unknown to rs274)"
        out.append(line)
    prog = workdir / "program-rs274.ngc"
    prog.write_text("\n".join(out) + "\n")
    if not ini_lines:
        return prog, None
    ini = workdir / "tcp.ini"
    ini.write_text("[RS274NGC]\nSUBROUTINE_PATH = " + str(workdir) + "\n" + "\n".join(dict.fromkeys(ini_lines)) + "\n")
    return prog, ini


def feed_passes(moves: list[CanonMove]) -> list[tuple[float, list]]:
    """XY paths cut at constant Z: (z, elements) for each run of feed moves at one height.

    A run ends at a rapid or a Z change; the plunge into the run is not part of it.
    """
    out: list[tuple[float, list]] = []
    pos = None
    cur_z, cur = None, []
    for m in moves:
        if m.kind == "arc" and m.turns:
            raise RuntimeError("full-turn arc (P word) in the interpreted program")
        prev = pos
        pos = (m.x, m.y, m.z)
        if m.kind == "rapid" or prev is None:
            if cur:
                out.append((cur_z, cur))
            cur_z, cur = None, []
            continue
        if m.z != prev[2] or (cur_z is not None and m.z != cur_z):
            if cur:
                out.append((cur_z, cur))
            cur_z, cur = None, []
            if m.z != prev[2]:
                continue
        if (m.x, m.y) == (prev[0], prev[1]):
            continue
        cur_z = m.z
        if m.kind == "arc":
            cur.append(Arc((prev[0], prev[1]), (m.x, m.y), m.centre, m.ccw))
        else:
            cur.append(Line((prev[0], prev[1]), (m.x, m.y)))
    if cur:
        out.append((cur_z, cur))
    return out


def poses_from_canon(moves, a_axis: str = "right-hand") -> ToolPoses:
    """Tool poses from rs274's canonical moves (:func:`camcam.verify.rs274.run_rs274`)."""
    rows = []
    for m in moves:
        if m.kind == "arc":
            raise ValueError("arc move in an interpreted barrel-cam program")
        rows.append((m.x, m.y, m.z, m.a, float(getattr(m, "b", 0.0))))
    arr = np.array(rows)
    return ToolPoses(arr[:, :3], arr[:, 3], arr[:, 4], a_axis)
