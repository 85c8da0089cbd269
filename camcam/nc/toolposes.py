"""The tool a barrel-cam program cuts with, and its poses as printed.

:class:`CylinderTool` is the flat end mill (radius, cutting length);
:class:`ToolPoses` the tool tip X Y Z and the A and B angles of every
printed position, read back from the program text
(:func:`poses_from_program`) or from rs274's canonical moves
(:func:`poses_from_canon`).  :mod:`camcam.nc.groove3d` measures the groove
they cut.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

import numpy as np

__all__ = ["ToolPoses", "CylinderTool", "poses_from_program", "poses_from_canon", "A_AXIS_SENSE", "frozen_array"]

#: Sign of the part's turn for a positive A: Rx(sign·A).
A_AXIS_SENSE = {"right-hand": 1, "left-hand": -1}


def frozen_array(a) -> np.ndarray:
    """``a`` as a read-only float array."""
    arr = np.array(a, dtype=float)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class ToolPoses:
    """Tool poses as printed: tip X Y Z (mm), A and B (degrees), in program order.

    The tool moves linearly in every axis word from one pose to the next.

    Examples
    --------
    >>> p = ToolPoses([[0.0, 0.0, 60.0], [10.0, 0.0, 60.0]], [0.0, 90.0], [0.0, 0.0])
    >>> len(p), p.a_axis
    (2, 'right-hand')
    """

    tip_mm: np.ndarray
    a_deg: np.ndarray
    b_deg: np.ndarray
    a_axis: str = "right-hand"

    def __post_init__(self) -> None:
        tip = frozen_array(self.tip_mm)
        a = frozen_array(self.a_deg)
        b = frozen_array(self.b_deg)
        if tip.ndim != 2 or tip.shape[1] != 3 or len(tip) < 2:
            raise ValueError(f"tip_mm must be (n, 3) with n ≥ 2, got shape {tip.shape}")
        if a.shape != (len(tip),) or b.shape != (len(tip),):
            raise ValueError(f"a_deg and b_deg must have {len(tip)} values, got {a.shape} and {b.shape}")
        if not (np.all(np.isfinite(tip)) and np.all(np.isfinite(a)) and np.all(np.isfinite(b))):
            raise ValueError("tool poses must be finite")
        if np.any(np.abs(b) >= 90.0):
            raise ValueError("B must stay within ±90°")
        if self.a_axis not in A_AXIS_SENSE:
            raise ValueError(f'a_axis must be "right-hand" or "left-hand", got {self.a_axis!r}')
        object.__setattr__(self, "tip_mm", tip)
        object.__setattr__(self, "a_deg", a)
        object.__setattr__(self, "b_deg", b)

    def __len__(self) -> int:
        return len(self.a_deg)


@dataclass(frozen=True)
class CylinderTool:
    """A flat end mill: ``radius_mm``, cutting length ``length_mm`` from the tip."""

    radius_mm: float
    length_mm: float

    def __post_init__(self) -> None:
        if not (self.radius_mm > 0 and self.length_mm > 0):
            raise ValueError(f"tool radius and length must be > 0, got {self.radius_mm!r}, {self.length_mm!r}")


# -- poses from text -----------------------------------------------------------------------
_WORD = re.compile(r"([A-Z])\s*([-+]?(?:\d+\.?\d*|\.\d+))")
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
        words = _WORD.findall(line)
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


def poses_from_canon(moves, a_axis: str = "right-hand") -> ToolPoses:
    """Tool poses from rs274's canonical moves (:func:`camcam.verify.rs274.run_rs274`)."""
    rows = []
    for m in moves:
        if m.kind == "arc":
            raise ValueError("arc move in an interpreted barrel-cam program")
        rows.append((m.x, m.y, m.z, m.a, float(getattr(m, "b", 0.0))))
    arr = np.array(rows)
    return ToolPoses(arr[:, :3], arr[:, 3], arr[:, 4], a_axis)
