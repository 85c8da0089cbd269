"""Shared cams for the reverse-design tests: built from the samples' specs with the geometry stage."""

from __future__ import annotations

from pathlib import Path

import pytest

from camcam.geometry.cylindrical import CylindricalCam
from camcam.geometry.disc import DiscCam
from camcam.geometry.followers import follower_kind
from camcam.reverse.disc import disc_follower
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]


def spec_cam(name: str):
    """(spec, design program, forward cam) of ``samples/<name>``."""
    spec = load_spec(ROOT / "samples" / name)
    prog = spec.motion.program(spec.unit)
    c, f = spec.cam, spec.follower
    if c.kind == "cylindrical":
        fol = follower_kind(f.kind).barrel_from_spec(f)
        cam = CylindricalCam(fol, prog, c.base_radius, length=c.length, groove_depth=c.groove_depth,
                             rotation=c.rotation, bore=c.bore)
    else:
        cam = DiscCam(disc_follower(f), prog, c.base_radius, c.rotation)
    return spec, prog, cam


@pytest.fixture(scope="session")
def seed002():
    return spec_cam("reverse/seed002.toml")
