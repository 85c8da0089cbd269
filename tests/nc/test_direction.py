"""Climb or conventional milling (``[machining] direction``), read back from the printed program.

Each pass's sense is measured on the moves the program prints (:func:`camcam.post.readback.read_program`):
the angle its feed moves wind about the cam axis (arcs sampled), negative clockwise.  With the M3
spindle, climb puts the material on the right of travel: clockwise round material inside the path (a
disc's profile and its roughing spiral, a groove's inner wall and the rings toward it), counter-clockwise
round material outside it (the bore, a groove's outer wall and its rings); conventional the reverse.
"""

from pathlib import Path

import numpy as np
import pytest

from camcam.geometry.build import build_cam
from camcam.nc import machine_program
from camcam.nc.direction import orient, reverse_elements
from camcam.post.readback import read_program
from camcam.spec import load_spec
from camcam.toolpath.elements import Arc, Line

ROOT = Path(__file__).resolve().parents[2]
DISC = ROOT / "samples" / "disc-translating-roller.toml"
GROOVE = Path(__file__).parent / "data" / "groove-rough-bend-43-140.toml"


def _job(tmp_path, source: Path, *, rotation: str | None = None, extra: str = ""):
    text = source.read_text()
    if rotation is not None:
        text = text.replace('rotation = "ccw"', f'rotation = "{rotation}"').replace(
            'rotation = "cw"', f'rotation = "{rotation}"')
    text = text.replace("bore = 12.0\n", "bore = 24.0\n")  # wider than the Ø16 tool: a helical bore fits
    text = text.replace("[machining]\n", "[machining]\n" + extra)
    path = tmp_path / source.name
    path.write_text(text)
    spec = load_spec(path)
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    return machine_program(built, spec.machining, spec.name, spec.stock)


def _windings(result) -> list[tuple[str, float]]:
    """(pass comment, angle its feed moves wind about X0 Y0 in rad) for each pass of the printed program."""
    out, cur, pts, at = [], None, [], None
    for ev in read_program(result.program.text, result.post):
        if isinstance(ev, str):
            if ev.startswith("pass "):
                if cur is not None:
                    out.append((cur, pts))
                cur, pts = ev, []
            continue
        if ev.kind == "arc" and at is not None:
            c = np.array(ev.centre)
            a0 = np.arctan2(at[1] - c[1], at[0] - c[0])
            sweep = (np.arctan2(ev.y - c[1], ev.x - c[0]) - a0) % (2 * np.pi)
            sweep = sweep if ev.ccw else sweep - 2 * np.pi
            r = np.hypot(at[0] - c[0], at[1] - c[1])
            t = a0 + sweep * np.linspace(0, 1, 17)[1:]
            pts += list(zip(c[0] + r * np.cos(t), c[1] + r * np.sin(t)))
        elif ev.kind == "line" and cur is not None:
            pts.append((ev.x, ev.y))
        at = (ev.x, ev.y)
    out.append((cur, pts))
    return [(name, float(np.sum(np.diff(np.unwrap(np.arctan2(*np.array(p)[:, ::-1].T)))))) for name, p in out]


def _inside(name: str) -> bool:
    """Whether the pass's material lies inside its path (toward the cam axis)."""
    return not ("bore" in name or "outer" in name)


@pytest.mark.parametrize("rotation", ["ccw", "cw"])
@pytest.mark.parametrize("direction", ["climb", "conventional"])
def test_disc_profile_spiral_spring_and_bore_run_as_asked(tmp_path, rotation, direction):
    extra = f'bore = true\ndirection = "{direction}"\n'
    result = _job(tmp_path, DISC, rotation=rotation, extra=extra)
    windings = _windings(result)
    kinds = {name.split(":")[1].split(",")[0].strip() for name, _ in windings}
    assert kinds == {"rough", "finish", "spring", "bore"}
    for name, turn in windings:
        # each pass winds about the axis at least once (a spiral several times): ±2π within 1 rad is the sense
        assert abs(turn) > 2 * np.pi - 1.0, name
        clockwise = turn < 0
        assert clockwise == ((direction == "climb") == _inside(name)), (name, turn)
        assert name.endswith(direction) or f", {direction}, " in name  # the comment says it


@pytest.mark.parametrize("direction", ["climb", "conventional"])
def test_grooved_disc_walls_and_rings_run_as_asked(tmp_path, direction):
    result = _job(tmp_path, GROOVE, extra=f'direction = "{direction}"\n')
    windings = _windings(result)
    sided = [(n, t) for n, t in windings if "slot" not in n.split(",")[0]]
    labels = {n.split(",")[1].strip() for n, _ in sided}
    assert {"inner flank", "outer flank", "groove rough inner 1", "groove rough outer 1"} <= labels
    for name, turn in sided:
        # a groove pass ramps in over part of a turn and then laps once: beyond π either way is the sense
        assert abs(turn) > np.pi, name
        assert (turn < 0) == ((direction == "climb") == _inside(name)), (name, turn)
        assert f", {direction}" in name
    slots = [n for n, _ in windings if "slot" in n.split(",")[0]]
    assert slots and all(", both" in n for n in slots)  # a full-width pass is both


def test_orient_turns_a_chain_round_only_when_asked():
    chain = (Line((0.0, 0.0), (1.0, 0.0)), Arc((1.0, 0.0), (0.0, 1.0), (0.0, 0.0), True))
    assert orient(chain, "right", "climb") == (chain, "right")
    assert orient(chain, "right", "conventional") == (reverse_elements(chain), "left")
    assert orient(chain, "both", "conventional") == (chain, "both")
    assert reverse_elements(reverse_elements(chain)) == chain


BARREL = ROOT / "samples" / "cylindrical-translating-small-tool.toml"


def _barrel_passes(text: str) -> list[tuple[str, np.ndarray]]:
    """(pass comment, its G1 moves' (X, A) in printed order) from a 4-axis program (modal X and A words)."""
    out, x, a = [], None, None
    for line in text.splitlines():
        if line.startswith("(pass "):
            out.append((line.strip("()"), []))
            continue
        if not line.startswith(("G0", "G1")):
            continue
        words = dict((w[0], w[1:]) for w in line.split()[1:] if w[0] in "XA")
        x, a = float(words.get("X", x or 0.0)), float(words.get("A", a or 0.0))
        if line.startswith("G1") and out:
            out[-1][1].append((x, a))
    return [(name, np.array(p)) for name, p in out]


def _rx(deg: float) -> np.ndarray:
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


@pytest.mark.parametrize("a_axis", ["right-hand", "left-hand"])
@pytest.mark.parametrize("direction", ["climb", "conventional"])
def test_barrel_walls_run_as_asked(tmp_path, direction, a_axis):
    result = _job(tmp_path, BARREL, extra=f'direction = "{direction}"\na_axis = "{a_axis}"\n')
    passes = _barrel_passes(result.program.text)
    centre = next(p for n, p in passes if "slot" in n.split(",")[0])
    rho = result.reference_radius_mm
    k = 1 if a_axis == "right-hand" else -1  # a part point p sits at machine Rx(k·A)·p
    flanks = [(n, p) for n, p in passes if "flank" in n]
    assert {n.split(",")[1].strip() for n, _ in flanks} == {"flank 0 [-X wall]", "flank 1 [+X wall]"}
    for name, p in flanks:
        cut = p[1:]  # after the plunge
        # the wall's side from the program: the flank pass's X against the centre pass's at the same A
        x_centre = np.interp(cut[:, 1] % 360.0, centre[1:, 1] % 360.0, centre[1:, 0], period=360.0)
        wall_x = np.sign(np.median(cut[:, 0] - x_centre))
        # the tool's travel over the part, in the machine frame under the tool (looking down −Z, M3 clockwise):
        # the contact point in the part is Rx(−k·A)·(X, 0, ρ); its change, turned back by Rx(k·A)
        right = []
        for (x0, a0), (x1, a1) in zip(cut[:-1], cut[1:]):
            p0 = _rx(-k * a0) @ (x0, 0.0, rho)
            p1 = _rx(-k * a1) @ (x1, 0.0, rho)
            v = _rx(k * a0) @ (p1 - p0)
            right.append(v[1] * wall_x > 0)  # the wall (wall_x, 0) is right of (vx, vy): vx·0 − vy·wall_x < 0
        share = np.mean(right)
        assert share == (1.0 if direction == "climb" else 0.0), (name, share)
        assert f", {direction}" in name
