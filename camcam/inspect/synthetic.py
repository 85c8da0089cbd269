"""Synthetic measured parts: the exact profile with a stated defect, datum error, noise and outliers.

Used by the samples (``samples/inspect/make_parts.py``) and the tests: a part
whose defect is known exactly, to check that inspection finds it.

The defect is a Gaussian bump of the surface along its normal, ``bump_mm`` high
(+ material left, − overcut) at cam angle ``bump_deg`` with standard deviation
``bump_width_deg`` in cam angle; noise is Gaussian of σ ``noise_mm`` along the
normal; ``outliers`` points get ± ``outlier_mm`` more (random sign).  The datum
error turns the part by ``rotation_deg`` about the cam axis and shifts it by
``shift_mm`` (a CMM's x, y; a dial's dividing-head axis offset; a barrel's x, y, z),
so inspection should fit a rotation of −``rotation_deg``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.inspect.nominal import BarrelWalls, DialProfile
from camcam.reverse.synth import uneven_angles

__all__ = ["Defect", "cmm_part", "dial_part", "barrel_part", "bump"]


@dataclass(frozen=True, kw_only=True)
class Defect:
    """What is wrong with a synthetic part (module docstring); ``wall`` the barrel wall the bump is on."""

    bump_mm: float = 0.0
    bump_deg: float = 0.0
    bump_width_deg: float = 4.0
    rotation_deg: float = 0.0
    shift_mm: tuple[float, ...] = (0.0, 0.0, 0.0)
    noise_mm: float = 0.0
    outliers: int = 0
    outlier_mm: float = 0.1
    wall: int = 0


def bump(defect: Defect, angle_deg) -> np.ndarray:
    """The bump's height (mm) at cam angles ``angle_deg``."""
    d = np.mod(np.asarray(angle_deg, dtype=float) - defect.bump_deg + 180.0, 360.0) - 180.0
    return defect.bump_mm * np.exp(-0.5 * (d / defect.bump_width_deg) ** 2)


def _errors(defect: Defect, angle_deg: np.ndarray, rng: np.random.Generator, on: np.ndarray | None = None):
    """Normal offsets: bump + noise + outliers; and the outliers' indices."""
    n = len(angle_deg)
    e = bump(defect, angle_deg) * (1.0 if on is None else on) + rng.normal(0.0, defect.noise_mm, n)
    idx = rng.choice(n, defect.outliers, replace=False) if defect.outliers else np.array([], dtype=int)
    e[idx] += defect.outlier_mm * rng.choice([-1.0, 1.0], len(idx))
    return e, np.sort(idx)


def cmm_part(cam, n: int, defect: Defect, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """(n, 2) CMM points on a disc cam's profile, and the outliers' indices."""
    th = uneven_angles(n, rng, 0.3)
    e, idx = _errors(defect, np.degrees(th), rng)
    P = cam.profile.evaluate(th) + e[:, None] * cam.normal(th)
    a = math.radians(defect.rotation_deg)
    R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    return P @ R.T + np.asarray(defect.shift_mm[:2]), idx


def dial_part(cam, probe_radius: float, step_deg: float, defect: Defect, rng: np.random.Generator,
              zero_mm: float = 0.25) -> tuple[np.ndarray, np.ndarray]:
    """(n, 2) dial readings (angle_deg, reading_mm) every ``step_deg`` with the dividing head's angle off by
    ``rotation_deg`` (read angle = true cam angle + rotation) and its axis at ``shift_mm`` (part frame); readings from the zero ``zero_mm`` below
    the design's; and the outliers' indices."""
    model = DialProfile(cam, probe_radius)
    ang = np.arange(0.0, 360.0, step_deg)
    c = np.asarray(defect.shift_mm[:2], dtype=float)
    u = np.array([-math.radians(defect.rotation_deg), c[0], c[1], 0.0])
    ev = model.evaluate(u, np.stack([ang, np.zeros_like(ang)], axis=-1))  # deviation = −h·cos at zero reading
    cos = ev.jacobian[:, 3]
    h = -ev.deviation / cos
    e, idx = _errors(defect, np.degrees(ev.angle), rng)
    return np.stack([ang, h + e / cos - zero_mm], axis=-1), idx


def barrel_part(cam, n_per_wall: int, defect: Defect, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """(2·n, 3) points on both groove walls (bump on ``defect.wall``), at random depths between 1 mm below
    the outer radius and 1 mm above the groove bottom; and the outliers' indices."""
    model = BarrelWalls(cam)
    th = np.concatenate([uneven_angles(n_per_wall, rng, 0.3) for _ in (0, 1)])
    walls = np.repeat([0, 1], n_per_wall)
    rho = rng.uniform(cam.bottom_radius + 1.0, cam.base_radius - 1.0, th.size)
    S, N_in = model.surface(th, rho, walls)
    e, idx = _errors(defect, np.degrees(th), rng, on=(walls == defect.wall).astype(float))
    P = S - e[:, None] * N_in  # + material left: into the wall
    a = math.radians(defect.rotation_deg)
    R = np.array([[1.0, 0.0, 0.0], [0.0, math.cos(a), -math.sin(a)], [0.0, math.sin(a), math.cos(a)]])
    return P @ R.T + np.asarray(defect.shift_mm[:3]), idx
