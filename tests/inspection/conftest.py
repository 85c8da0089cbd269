"""Shared parts for the inspection tests: the samples' cams built once, and synthetic parts inspected.

The standard defect is issue 46's: a Gaussian bump of 0.03 mm at a chosen angle, a rotation of 0.7°,
a centre shift of 0.05 mm, noise of σ 0.002 mm and 3 outliers (0.1 mm, random sign).
"""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np

from camcam.geometry.build import build_cam
from camcam.inspect import InspectOptions, MeasuredPart, inspect_part
from camcam.inspect.synthetic import Defect, barrel_part, cmm_part, dial_part
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
SPECS = {"cmm": "disc-translating-roller.toml", "dial": "disc-translating-roller.toml",
         "barrel": "cylindrical-translating.toml"}
TOLERANCE = 0.01
PROBE = 5.0
NOISE = 0.002
BUMP = 0.03
ROTATION = 0.7
SHIFT = 0.05


@functools.lru_cache(maxsize=None)
def built(name: str):
    """(spec, program, BuiltCam) of ``samples/<name>``."""
    spec = load_spec(ROOT / "samples" / name)
    prog = spec.motion.program(spec.unit)
    return spec, prog, build_cam(spec.cam, spec.follower, prog)


def defect_for(mode: str, bump_mm: float = BUMP, bump_deg: float = 200.0, **kw) -> Defect:
    """The standard defect with the datum errors ``mode`` can fit: none → neither, rotation → the
    rotation, rigid → the rotation and the shift (0.05 mm along x, as a centre or an axial datum)."""
    rot = ROTATION if mode != "none" else 0.0
    shift = (SHIFT, 0.0, 0.0) if mode == "rigid" else (0.0, 0.0, 0.0)
    base = dict(bump_mm=bump_mm, bump_deg=bump_deg, rotation_deg=rot, shift_mm=shift, noise_mm=NOISE, outliers=3)
    base.update(kw)
    return Defect(**base)


def make_part(kind: str, defect: Defect, seed: int, size: int | None = None):
    """(MeasuredPart, outlier rows) of a synthetic part of ``kind``."""
    _, _, b = built(SPECS[kind])
    rng = np.random.default_rng(seed)
    if kind == "cmm":
        vals, idx = cmm_part(b.cam, size or 720, defect, rng)
    elif kind == "dial":
        vals, idx = dial_part(b.cam, PROBE, 360.0 / (size or 360), defect, rng)
    else:
        vals, idx = barrel_part(b.cam, size or 360, defect, rng)
    rows = tuple(range(2, len(vals) + 2))  # as a file with a header line
    return MeasuredPart(kind=kind, values=vals, rows=rows, source=f"{kind}.csv"), {rows[i] for i in idx}


def inspect(kind: str, part: MeasuredPart, mode: str, motion: bool = False, **kw):
    spec, prog, b = built(SPECS[kind])
    opts = InspectOptions(tolerance_mm=TOLERANCE, align=mode, probe_radius_mm=PROBE if kind == "dial" else None,
                          motion=motion, **kw)
    return inspect_part(b, spec.cam, spec.follower, prog, part, opts)
