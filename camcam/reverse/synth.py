"""Simulated measurements: points on a cam from the forward geometry, unevenly spaced, with noise.

Used by the samples, the round-trip tests and the benchmark: the reverse
design is checked against cams whose motion is known exactly.

Examples
--------
>>> import numpy as np
>>> cams = uneven_angles(8, np.random.default_rng(0), jitter=0.3)
>>> bool(np.all(np.diff(cams) > 0)), bool(cams[0] >= 0), bool(cams[-1] < 2 * np.pi)
(True, True, True)
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.cylindrical import CylindricalCam
from camcam.geometry.disc import DiscCam

__all__ = ["uneven_angles", "measure_disc", "measure_cylindrical"]


def uneven_angles(n: int, rng: np.random.Generator, jitter: float = 0.35) -> np.ndarray:
    """n cam angles (rad, increasing, in [0, 2π)): the even step 2π/n, each moved by up to ±``jitter`` steps."""
    step = 2 * math.pi / n
    return np.sort(np.mod((np.arange(n) + rng.uniform(-jitter, jitter, n)) * step, 2 * math.pi))


def _noisy(points: np.ndarray, rng: np.random.Generator, noise_mm: float, shuffle: bool) -> np.ndarray:
    out = points + rng.uniform(-noise_mm, noise_mm, points.shape) if noise_mm else points.copy()
    return out[rng.permutation(out.shape[0])] if shuffle else out


def measure_disc(cam: DiscCam, n: int, rng: np.random.Generator, noise_mm: float = 0.0,
                 jitter: float = 0.35, shuffle: bool = False) -> np.ndarray:
    """(n, 2) profile points at uneven cam angles, each coordinate moved by up to ±``noise_mm``."""
    return _noisy(cam.profile.evaluate(uneven_angles(n, rng, jitter)), rng, noise_mm, shuffle)


def measure_cylindrical(cam: CylindricalCam, n: int, rng: np.random.Generator, noise_mm: float = 0.0,
                        jitter: float = 0.35, flank: int = 0, radius_mm: float | None = None,
                        on_surface: bool = True, shuffle: bool = False) -> np.ndarray:
    """(n, 3) flank points: on the cylinder of ``radius_mm`` (a probe at constant depth) when
    ``on_surface``, else on the roller cross-section of that radius (seed 002's measuring line);
    default radius: the cam's reference radius (seed 002's d − r)."""
    rho = cam.reference_radius if radius_mm is None else radius_mm
    theta = uneven_angles(n, rng, jitter)
    pts = cam.flank_on_surface(theta, flank, rho) if on_surface else cam.flank(flank, rho).evaluate(theta)
    return _noisy(pts, rng, noise_mm, shuffle)
