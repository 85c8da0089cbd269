"""Built cams of every follower and cam kind for the dynamics tests (the samples' geometry, built once)."""

from __future__ import annotations

import functools
from pathlib import Path

from camcam.dynamics.train import DynamicsSpec
from camcam.geometry.build import build_cam
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]

#: Each sample's cam, by name: one per follower kind, the face groove and both barrels.
SAMPLES = ("disc-translating-roller", "disc-translating-flat", "disc-oscillating-roller", "disc-oscillating-flat",
           "disc-groove", "cylindrical-translating", "cylindrical-oscillating")


@functools.lru_cache(maxsize=None)
def built(name: str):
    """(built cam, rpm) of ``samples/<name>.toml``."""
    spec = load_spec(ROOT / "samples" / f"{name}.toml")
    program = spec.motion.program(spec.unit)
    return build_cam(spec.cam, spec.follower, program), program.rpm


def train(name: str, **over) -> DynamicsSpec:
    """A follower train that suits the sample: a spring on open cams, none on grooved ones."""
    cam, _ = built(name)
    osc = cam.cam.program.unit == "deg"
    kw = dict(inertia_kgm2=0.002, load_arm_mm=60.0) if osc else dict(mass_kg=0.5)
    if cam.spec.kind == "disc":
        kw.update(spring_rate_n_per_mm=1.0, preload_n=30.0)
    kw.update(roller_width_mm=10.0)
    kw.update(over)
    return DynamicsSpec(**kw)
