"""The design grid: every combination of the swept axes and law choices, numbered, cut in chunks.

Design numbers run law combination first (slowest), then the axes in
:func:`camcam.spec.size.sized_followers` order, the last axis fastest.  Chunks are fixed
slices of one law combination (:data:`CHUNK` designs), so the work a worker
gets, and the order results are put back in, never depend on how many
workers there are.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from camcam.spec.size import SizeSpec

__all__ = ["CHUNK", "Chunk", "DesignGrid"]

#: Designs per task: enough to amortise a task's overhead (~1 ms on Dask), few enough that a
#: sweep of 10,000 designs still gives each of a few workers several tasks.
CHUNK = 512


@dataclass(frozen=True)
class Chunk:
    """Designs ``start`` … ``stop − 1`` of law combination ``combo`` (offsets within the combination)."""

    combo: int
    start: int
    stop: int


@dataclass(frozen=True)
class DesignGrid:
    """The sweep's axes and law combinations.

    Examples
    --------
    >>> from camcam.spec.size import SizeAxis, SizeSpec
    >>> g = DesignGrid.of(SizeSpec(axes=(SizeAxis("base_radius", (30.0, 40.0)), SizeAxis("offset", (0.0, 5.0, 10.0))),
    ...                            laws=(), max_pressure_angle_deg=30.0, min_curvature_radius_mm=0.0,
    ...                            min_curvature_radius_rollers=None, tool_radius_mm=None, objective="outer-radius",
    ...                            samples=3600))
    >>> len(g), g.params(0, 2, 5)["offset"].tolist()
    (6, [10.0, 0.0, 5.0])
    """

    axes: tuple[tuple[str, tuple[float, ...]], ...]
    segments: tuple[int, ...]
    combos: tuple[tuple[str, ...], ...]

    @classmethod
    def of(cls, size: SizeSpec) -> "DesignGrid":
        combos = tuple(itertools.product(*(c.laws for c in size.laws))) if size.laws else ((),)
        return cls(tuple((a.name, a.values) for a in size.axes), tuple(c.segment for c in size.laws), combos)

    @property
    def per_combo(self) -> int:
        n = 1
        for _, v in self.axes:
            n *= len(v)
        return n

    def __len__(self) -> int:
        return self.per_combo * len(self.combos)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(v) for _, v in self.axes)

    def params(self, combo: int, start: int, stop: int) -> dict[str, np.ndarray]:
        """Axis values of designs ``start`` … ``stop − 1`` of one combination."""
        idx = np.unravel_index(np.arange(start, stop), self.shape)
        return {name: np.asarray(vals, float)[i] for (name, vals), i in zip(self.axes, idx)}

    def chunks(self, size: int = CHUNK) -> list[Chunk]:
        n = self.per_combo
        return [Chunk(c, a, min(a + size, n)) for c in range(len(self.combos)) for a in range(0, n, size)]

    def design(self, number: int) -> tuple[dict[str, float], dict[int, str]]:
        """(axis values, {segment: law}) of design ``number``."""
        combo, k = divmod(int(number), self.per_combo)
        p = {name: float(v[0]) for name, v in self.params(combo, k, k + 1).items()}
        return p, dict(zip(self.segments, self.combos[combo]))
