"""Does the tool holder clear the blank at every move of the printed program (issue 47)?

The holder is a cylinder of ``[machining] holder_diameter`` on the tool axis, from its face
``[machining] stick_out`` above the tool tip upward (the shank between is no wider than the
holder, so the holder is what hits first).  It is checked against the blank, which holds the
part and every state of the material between (a conservative test: material the program has
already removed counts as still there):

* a disc or face-groove job (tool axis +Z): the holder's face is at Z = tip + stick-out; it
  hits the blank when, on some move, that face is below the blank's top (Z0 plus any face
  stock) while the holder's footprint (a disc of the holder's radius about the tool, swept
  along the move's XY path) overlaps the blank's outline.  A move is taken at its lowest
  tip (a line or helix changes Z linearly, so the lowest is at an end); an arc's XY path is
  sampled with a chord sag under 0.001 mm.
* a barrel job (the cam axis along X, the tool axis (sin B, 0, cos B)): the blank is the
  cam's cylinder, radius R from X0 to the cam's length, the same at every A.  The holder's
  face, a disc of the holder's radius about tip + stick-out·axis normal to the axis, hits it
  when a point of that disc lies inside the cylinder (y² + z² < R² and 0 ≤ x ≤ length); the
  face is the holder's part nearest the cam axis for the tilts a barrel program uses
  (|B| < 90°, tip above the axis).  Each printed pose and the mid-point of each move are
  tested; the face is sampled at 72 angles on 5 radii.

A holder that hits is refused before anything is written (``SpecError`` on
``machining.stick_out``, exit 2): a collision is no tolerance matter a machinist would accept
with a FAIL report; the spec's tool set-up cannot run this program, and the one line names
the first move that hits and the stick-out that clears every move.
"""

from __future__ import annotations

import math

import numpy as np
import shapely
from shapely.geometry import LineString, Point

from camcam.errors import SpecError
from camcam.post.readback import read_program

__all__ = ["disc_holder_clash", "barrel_holder_clash", "check_holder"]

#: Largest chord sag of an arc's sampled XY path (mm).
ARC_SAG_MM = 0.001


def _arc_points(start, move) -> np.ndarray:
    cx, cy = move.centre
    r = math.hypot(start[0] - cx, start[1] - cy)
    a0 = math.atan2(start[1] - cy, start[0] - cx)
    a1 = math.atan2(move.y - cy, move.x - cx)
    sweep = (a1 - a0) % (2 * math.pi) if move.ccw else -((a0 - a1) % (2 * math.pi))
    if abs(sweep) < 1e-12:
        sweep = 2 * math.pi if move.ccw else -2 * math.pi  # a full circle
    step = 2 * math.acos(max(-1.0, 1 - ARC_SAG_MM / r)) if r > ARC_SAG_MM else math.pi
    n = max(2, int(math.ceil(abs(sweep) / step)) + 1)
    a = a0 + sweep * np.linspace(0.0, 1.0, n)
    return np.column_stack([cx + r * np.cos(a), cy + r * np.sin(a)])


def disc_holder_clash(text: str, post, blank, holder_diameter_mm: float, stick_out_mm: float) -> tuple[str, float] | None:
    """The first move of a disc program whose holder hits ``blank`` (its description), with the stick-out that
    clears every move (mm); None if the holder clears them all.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> from shapely.geometry import Point
    >>> from camcam.post.post import load_post
    >>> blank = SimpleNamespace(region=Point(0, 0).buffer(50), top_z_mm=0.0)
    >>> prog = "G0 X70 Y0 Z5\\nG1 Z-12 F100\\nG1 X40\\nM2\\n"
    >>> disc_holder_clash(prog, load_post("linuxcnc"), blank, 40.0, 30.0) is None
    True
    >>> disc_holder_clash(prog, load_post("linuxcnc"), blank, 40.0, 10.0)
    ('move 3 (G1 to X40 Y0 Z-12): holder face at Z-2', 12.0)
    """
    r_h = holder_diameter_mm / 2
    region, top = blank.region, blank.top_z_mm
    shapely.prepare(region)
    pos, label, n = None, "", 0
    first, need = None, 0.0
    for ev in read_program(text, post):
        if isinstance(ev, str):
            label = ev.split(":")[0] if ev.startswith("pass ") else label
            continue
        n += 1
        start = pos if pos is not None else (ev.x, ev.y, ev.z)
        pos = (ev.x, ev.y, ev.z)
        low = min(start[2], ev.z)
        if low + stick_out_mm >= top and low + need >= top:
            continue  # neither this holder nor the stick-out needed so far can reach the blank's top here
        if ev.kind == "arc":
            xy = _arc_points(start, ev)
        else:
            xy = np.array([start[:2], (ev.x, ev.y)])
        path = LineString(xy) if len(xy) > 1 and np.ptp(xy, axis=0).max() > 0 else Point(xy[0])
        if path.distance(region) >= r_h:
            continue
        need = max(need, top - low)
        if first is None and low + stick_out_mm < top:
            word = {"rapid": "G0", "line": "G1", "arc": "G3" if ev.ccw else "G2"}[ev.kind]
            where = f"{label}, " if label else ""
            first = (f"move {n} ({where}{word} to X{ev.x:g} Y{ev.y:g} Z{ev.z:g}): holder face at "
                     f"Z{low + stick_out_mm:g}")
    return None if first is None else (first, need)


def _face_points(r_h: float) -> tuple[np.ndarray, np.ndarray]:
    phi = np.linspace(0.0, 2 * math.pi, 72, endpoint=False)
    rho = r_h * np.linspace(0.0, 1.0, 5)
    p, f = np.meshgrid(rho, phi)
    return (p * np.cos(f)).ravel(), (p * np.sin(f)).ravel()


def _inside(tip: np.ndarray, b_deg: np.ndarray, s: float, u1: np.ndarray, u2: np.ndarray, radius: float,
            length: float) -> np.ndarray:
    """Per pose: does the holder face (stick-out ``s``) reach into the cylinder?"""
    b = np.radians(b_deg)[:, None]
    cx = tip[:, 0:1] + s * np.sin(b)
    cz = tip[:, 2:3] + s * np.cos(b)
    x = cx + u1 * np.cos(b)  # the face's in-plane directions: (cos B, 0, −sin B) and (0, 1, 0)
    y = tip[:, 1:2] + u2
    z = cz - u1 * np.sin(b)
    return ((y * y + z * z < radius * radius) & (x >= 0.0) & (x <= length)).any(axis=1)


def barrel_holder_clash(poses, radius_mm: float, length_mm: float, holder_diameter_mm: float,
                        stick_out_mm: float) -> tuple[str, float] | None:
    """The first pose (or move mid-point) of a barrel program whose holder face enters the cam's cylinder, with the
    stick-out that clears every move (mm, to 0.01 mm); None if the holder clears them all.

    Examples
    --------
    >>> from camcam.toolpath.poses import ToolPoses
    >>> p = ToolPoses([[10.0, 0.0, 60.0], [10.0, 0.0, 42.0], [50.0, 0.0, 42.0]], [0.0, 0.0, 90.0], [0.0] * 3)
    >>> barrel_holder_clash(p, 50.0, 100.0, 30.0, 20.0) is None
    True
    >>> barrel_holder_clash(p, 50.0, 100.0, 30.0, 5.0)
    ('pose 2 (X10 Y0 Z42 A0 B0): holder face 47 mm from the cam axis, inside the blank R50', 8.0)
    """
    tip, a, b = poses.tip_mm, poses.a_deg, poses.b_deg
    mid_tip, mid_a, mid_b = (tip[1:] + tip[:-1]) / 2, (a[1:] + a[:-1]) / 2, (b[1:] + b[:-1]) / 2
    all_tip = np.concatenate([tip, mid_tip])
    all_b = np.concatenate([b, mid_b])
    u1, u2 = _face_points(holder_diameter_mm / 2)
    hit = _inside(all_tip, all_b, stick_out_mm, u1, u2, radius_mm, length_mm)
    if not hit.any():
        return None
    # the first in program order: pose i, or the move from pose i to i + 1 (order 2i, 2i + 1)
    order = np.concatenate([2 * np.arange(len(tip)), 2 * np.arange(len(mid_tip)) + 1])
    k = int(np.argmin(np.where(hit, order, np.iinfo(np.int64).max)))
    i, is_mid = order[k] // 2, order[k] % 2 == 1
    t, aa, bb = all_tip[k], (mid_a if is_mid else a)[i], all_b[k]
    bk = math.radians(bb)
    c = t + stick_out_mm * np.array([math.sin(bk), 0.0, math.cos(bk)])
    what = f"move from pose {i + 1} to {i + 2} at its middle" if is_mid else f"pose {i + 1}"
    where = (f"{what} (X{t[0]:.4g} Y{t[1]:.4g} Z{t[2]:.4g} A{aa:.4g} B{bb:.4g}): holder face "
             f"{math.hypot(c[1], c[2]):.4g} mm from the cam axis, inside the blank R{radius_mm:g}")
    lo, hi = stick_out_mm, stick_out_mm + 2 * radius_mm + holder_diameter_mm
    while hi - lo > 0.005:  # the least clearing stick-out, by bisection (clearing grows with the stick-out)
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if _inside(all_tip, all_b, mid, u1, u2, radius_mm, length_mm).any() else (lo, mid)
    need = math.ceil(lo * 100) / 100  # the 0.01 mm grid value at or above the last stick-out that hits
    while _inside(all_tip, all_b, need, u1, u2, radius_mm, length_mm).any():
        need = round(need + 0.01, 2)
    return where, need


def check_holder(result, built, m) -> None:
    """Refuse (``SpecError`` on ``machining.stick_out``) a printed program whose holder would hit the blank, when
    the spec gives ``holder_diameter`` and ``stick_out``."""
    if m.holder_diameter_mm is None or m.stick_out_mm is None:
        return
    holder = f"the holder Ø{m.holder_diameter_mm:g} mm hits the blank at "
    if result.groove_plan is not None:
        from camcam.post.readback import read_poses

        poses = read_poses(result.program.text, result.post, m.a_axis)
        clash = barrel_holder_clash(poses, built.cam.base_radius, built.cam.length, m.holder_diameter_mm,
                                    m.stick_out_mm)
    elif result.blank is not None:
        clash = disc_holder_clash(result.program.text, result.post, result.blank, m.holder_diameter_mm,
                                  m.stick_out_mm)
    else:
        return
    if clash is not None:
        where, need = clash
        raise SpecError("machining.stick_out", f"{m.stick_out_mm:g} mm: {holder}{where}; a stick-out of at least "
                                               f"{need:g} mm clears every move (or cut less deep)")
