"""Figures of the 5-axis barrel-cam job (docs/barrel-cams.md, "5 axes for an oscillating roller"; the table in docs/benchmarks.md).

For seed 002's cam (samples/cylindrical-oscillating.toml) and each post: blocks, the fit's own error
model, the 3-D groove measurement (camcam.verify.groove3d) on the printed program and on the program as
LinuxCNC's rs274 interprets it, and the brute-force swept-tool check of tests/nc/swept.py.

    PYTHONPATH=. python benchmarks/fiveaxis.py
"""

from __future__ import annotations

import math
import sys
import tempfile
from dataclasses import replace
from pathlib import Path

import numpy as np

from camcam.geometry.build import build_cam
from camcam.toolpath.poses import CylinderTool
from camcam.verify.rs274 import poses_from_canon
from camcam.verify.groove3d import measure_groove
from camcam.verify import checked
from camcam.post.post import load_post
from camcam.spec import load_spec
from camcam.verify.rs274 import rs274_available, run_rs274, tcp_readable
from tests.nc.swept import parse_moves, part_poses, wall_deviation

ROOT = Path(__file__).resolve().parents[1]


def brute(built, moves, a_axis):
    cam = built.cam
    tips, axes, _ = part_poses(moves, a_axis, max_da_deg=0.05, max_step_mm=0.1)
    th = np.linspace(0.0, 2 * math.pi, 360, endpoint=False) + 0.001
    worst = 0.0
    for r in np.linspace(cam.bottom_radius, cam.base_radius, 5):
        for flank in (0, 1):
            d = wall_deviation(cam.flank_on_surface(th, flank, r), tips, axes, cam.roller_radius)
            worst = max(worst, float(np.abs(d).max()))
    return worst


def main(posts=("linuxcnc", "fanuc", "haas", "sinumerik", "heidenhain")) -> None:
    spec = load_spec(ROOT / "samples" / "cylindrical-oscillating.toml")
    rows = []
    cases = ([("ccw", "right-hand", p, 5) for p in posts]
             + [("cw", "right-hand", "linuxcnc", 5), ("ccw", "left-hand", "linuxcnc", 5), ("ccw", "right-hand", "linuxcnc", 4)])
    for rotation, a_axis, post, axes in cases:
        built = build_cam(replace(spec.cam, rotation=rotation), spec.follower, spec.motion.program(spec.unit))
        m = replace(spec.machining, post=load_post(post), a_axis=a_axis, axes=axes)
        r = checked(built, m, spec.name)
        interp = "—"
        if rs274_available() and post in ("linuxcnc", "fanuc", "haas"):
            with tempfile.TemporaryDirectory() as d:
                tcp = tuple(line.format(tool=m.tool_number) for line in r.post.tcp_on)
                prog, ini = tcp_readable(r.program.text, tcp, d)
                canon = run_rs274(prog, ini=ini)
            g = measure_groove(built.cam, CylinderTool(m.tool_diameter_mm / 2, m.flute_length_mm),
                               poses_from_canon(canon, a_axis))
            interp = f"{g.max_deviation_mm:.4f}"
        bf = f"{brute(built, parse_moves(r.program.text), a_axis):.4f}" if axes == 5 else "—"
        w = r.groove.walls
        model = f"{r.contours[0].deviation.max_deviation_mm:.4f}" if axes == 5 else "—"
        rows.append(f"| {post} | {axes} | {rotation} | {a_axis} | {r.contours[0].fit.line_blocks} | "
                    f"{model} | {r.groove.max_deviation_mm:.4f} | "
                    f"{max(w[0].overcut_mm, w[1].overcut_mm):.4f} / {max(w[0].material_left_mm, w[1].material_left_mm):.4f} | "
                    f"{interp} | {bf} |")
        print(rows[-1], file=sys.stderr)
    print("| post | axes | rotation | a_axis | blocks/pass | fit model mm | 3-D printed mm | overcut / left mm | "
          "3-D rs274 mm | brute force mm |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))


if __name__ == "__main__":
    main()
