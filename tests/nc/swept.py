"""An independent brute-force check of a 5-axis groove: the tool swept by the printed words vs the walls.

Nothing here comes from :mod:`camcam.nc.fiveaxis`: the program text (or
rs274's canonical moves) gives the poses, the machine-frame contract is
written out again with explicit rotation matrices, and the designed walls
come from :meth:`CylindricalCam.flank_on_surface` (the roller's contact
line solved onto each cylinder r = const).

* Poses: every feed move's X Y Z A B interpolated linearly, sampled every
  ≤ 0.02° of A and ≤ 0.05 mm of tip travel.  The tool: a flat end mill of
  radius r_t, its side a cylinder from the tip up along the axis.
* A wall point's deviation: the smallest, over all poses, of (distance from
  the tool axis − r_t) where the point lies beside the flute (negative: the
  tool went past the wall, an overcut; positive: material left); a point
  below every tip counts as left.  The sampling in A moves the tool by ≤
  0.02° · 80 mm = 0.028 mm along the groove; the distance near its minimum
  changes by ≤ s²/(2·r_t) ≈ 3e-5 mm between samples.
"""

from __future__ import annotations

import math
import re

import numpy as np


def rx(a_rad: float) -> np.ndarray:
    c, s = math.cos(a_rad), math.sin(a_rad)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def ry(b_rad: float) -> np.ndarray:
    c, s = math.cos(b_rad), math.sin(b_rad)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def parse_moves(text: str) -> list[tuple[str, tuple[float, float, float, float, float]]]:
    """(kind, (X, Y, Z, A, B)) of every G0/G1 (or Klartext L) block, modal, as printed."""
    pos = dict(X=0.0, Y=0.0, Z=0.0, A=0.0, B=0.0)
    out, motion = [], None
    for raw in text.splitlines():
        line = re.sub(r"\(.*?\)|;.*$", "", raw).strip()
        words = line.split()
        if words and re.fullmatch(r"N?\d+", words[0]):
            words = words[1:]
        if not words:
            continue
        if words[0] == "L":
            kind = "rapid" if "FMAX" in words else "feed"
            axes = words[1:]
        else:
            g = [w for w in words if re.fullmatch(r"G0?[01]", w)]
            if g:
                motion = "rapid" if g[0] in ("G0", "G00") else "feed"
            kind, axes = motion, words
        moved = False
        for w in axes:
            if w[0] in "XYZAB" and re.fullmatch(r"[XYZAB][+-]?\d+\.?\d*", w):
                pos[w[0]] = float(w[1:])
                moved = True
        if moved and kind is not None:
            out.append((kind, tuple(pos[k] for k in "XYZAB")))
    return out


def part_poses(moves, a_axis: str = "right-hand", max_da_deg: float = 0.02, max_step_mm: float = 0.05):
    """Tool tip and axis in the part frame, (n, 3) each, sampled along the feed moves.

    Contract: a part point p sits at machine position Rx(±A)·p, so the tool's machine tip T and axis
    Ry(B)·e_z are Rx(±A)ᵀ·T and Rx(±A)ᵀ·Ry(B)·e_z in the part."""
    s = 1.0 if a_axis == "right-hand" else -1.0
    tips, axes, a_out = [], [], []
    prev = None
    for kind, p in moves:
        if kind == "feed" and prev is not None:
            q0, q1 = np.array(prev), np.array(p)
            n = max(1, int(math.ceil(max(abs(q1[3] - q0[3]) / max_da_deg,
                                         np.linalg.norm(q1[:3] - q0[:3]) / max_step_mm))))
            for t in np.linspace(0.0, 1.0, n + 1):
                x, y, z, a, b = q0 + (q1 - q0) * t
                R = rx(s * math.radians(a)).T
                tips.append(R @ np.array([x, y, z]))
                axes.append(R @ ry(math.radians(b)) @ np.array([0.0, 0.0, 1.0]))
                a_out.append(a)
        prev = p
    return np.array(tips), np.array(axes), np.array(a_out)


def wall_deviation(points: np.ndarray, tips: np.ndarray, axes: np.ndarray, r_t: float,
                   flute_mm: float = 60.0, window_deg: float = 25.0) -> np.ndarray:
    """Signed deviation (mm) of each part-frame wall point: < 0 overcut, > 0 material left.

    Only poses whose tip lies within ``window_deg`` of the point's angle about X are tried (the tool
    touches a wall point when it is above it; a wall point sits ≤ asin(r_t/r) = 12.4° (r_t = 15, r ≥ 70) from the tip it touches)."""
    ang_p = np.degrees(np.arctan2(points[:, 1], points[:, 2]))
    ang_t = np.degrees(np.arctan2(tips[:, 1], tips[:, 2]))
    order = np.argsort(ang_t)
    ang_sorted = np.concatenate([ang_t[order] - 360, ang_t[order], ang_t[order] + 360])
    idx_sorted = np.concatenate([order, order, order])
    out = np.empty(len(points))
    for i, (p, a) in enumerate(zip(points, ang_p)):
        lo, hi = np.searchsorted(ang_sorted, [a - window_deg, a + window_deg])
        k = idx_sorted[lo:hi]
        w = p - tips[k]
        h = np.einsum("ij,ij->i", w, axes[k])
        radial = np.linalg.norm(w - h[:, None] * axes[k], axis=1)
        side = (h >= 0) & (h <= flute_mm)
        d = np.where(side, radial - r_t, np.hypot(np.minimum(h, 0.0), np.maximum(radial - r_t, 0.0)))
        out[i] = d.min() if len(d) else np.inf
    return out


def rapid_clearance(moves, radius_mm: float, r_t: float, a_axis: str = "right-hand") -> float:
    """Smallest height of the tool's low edge above the cylinder ``radius_mm`` over every rapid's end and
    start (rapids move X, Z or A/B only above the cam: the low edge's distance from the axis ≥ radius)."""
    worst = math.inf
    prev = None
    for kind, p in moves:
        if kind == "rapid" and prev is not None:
            for q in (prev, p):
                x, y, z, a, b = q
                low = z - r_t * abs(math.sin(math.radians(b)))
                worst = min(worst, low - radius_mm)
        prev = p
    return worst
