"""A sizing sweep: every design on the grid by closed forms, the best one checked by the full geometry.

1. Each law combination's motion program is sampled once (:func:`sample_program`)
   and broadcast against the design parameters in chunks (:mod:`camcam.sizing.grid`),
   on whatever :class:`~camcam.dask_batch.engine.Executor` is given.
2. A design is *feasible on the grid* when its sampled figures meet every
   constraint.  A sampled maximum can only be lower than the true one (and a
   sampled minimum only higher), so the grid's feasible set contains every
   truly feasible design; the grid is never on the unsafe side of a *rejection*.
3. The feasible designs are ranked by the objective (smallest outer radius, or
   smallest pressure angle), ties by pressure angle, then by design number.
   Candidates are taken in that order and checked with the exact geometry
   (:func:`camcam.sizing.exact_check.exact_figures`) until one passes and no later
   candidate's grid objective (a lower bound of its exact one) can beat it.

Examples
--------
>>> from pathlib import Path
>>> from camcam.spec import load_spec
>>> from camcam.dask_batch.engine import InProcess
>>> spec = load_spec(Path(__file__).parents[2] / "samples" / "size" / "translating-roller.toml")
>>> r = run_sweep(spec, InProcess())                      # doctest: +SKIP
>>> r.best is not None                                    # doctest: +SKIP
True
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from camcam.errors import SpecError
from camcam.geometry.disc import SIGMA
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram
from camcam.dask_batch.engine import Executor
from camcam.sizing.contact import SweepDynamics
from camcam.sizing.exact_check import ExactFigures, exact_figures
from camcam.sizing.grid import Chunk, DesignGrid
from camcam.sizing.kernels import FIGURES, block_figures
from camcam.sizing.samples import ProgramSamples, sample_program
from camcam.spec.size import SizeSpec

__all__ = ["SweepContext", "Limits", "SizingResult", "evaluate_chunk", "run_sweep", "combo_program", "MAX_EXACT_CHECKS",
           "LIMIT_RTOL"]

#: Exact checks (each a full analysis, ~1 s) before the search for the best gives up.
MAX_EXACT_CHECKS = 60

#: Objectives and pressure angles within this are a tie (float noise of the closed forms).
TIE = 1e-9

#: A figure within this of its limit meets it (mm or degrees): the float noise of the
#: analyses (~1e-14), so that a limit met with equality (ρ = R_b on a dwell) is met.
LIMIT_ATOL = 1e-9

#: The dynamics limits (MPa, rpm) are met within this, relative: the float noise of their chains (~1e-15).
LIMIT_RTOL = 1e-9


@dataclass(frozen=True)
class SweepContext:
    """What every chunk needs, sent to each worker once."""

    kind: str
    sigma: int
    grid: DesignGrid
    samples: tuple[ProgramSamples, ...]
    contact: SweepDynamics | None = field(default=None, kw_only=True)  # the [size] dynamics constraints' train


#: Designs evaluated together inside a chunk: (32 × ~3600 samples) arrays stay in cache, about
#: twice as fast per design as (512 × 3600) ones; every figure is per row, so the blocking
#: changes no bit of the result.
BLOCK = 32


def evaluate_chunk(chunk: Chunk, ctx: SweepContext) -> dict[str, np.ndarray]:
    """Figures of one chunk of designs (a pure function: the same chunk gives the same bytes anywhere)."""
    parts = []
    for a in range(chunk.start, chunk.stop, BLOCK):
        params = ctx.grid.params(chunk.combo, a, min(a + BLOCK, chunk.stop))
        parts.append(block_figures(ctx.kind, ctx.samples[chunk.combo], ctx.sigma, params, ctx.contact))
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


@dataclass(frozen=True, kw_only=True)
class Limits:
    """The constraints as numbers (``None``: not applied)."""

    max_pressure_angle_deg: float | None
    min_curvature_radius_mm: float
    min_curvature_radius_rollers: float | None
    tool_radius_mm: float | None
    bore_mm: float = 0.0  # the bore must fit inside the base circle minus the roller (as `camcam run` requires)
    max_contact_stress_mpa: float | None = None  # with the [dynamics] train at the spec's rpm
    min_jump_rpm: float | None = None

    @classmethod
    def of(cls, size: SizeSpec, bore_mm: float = 0.0) -> "Limits":
        return cls(max_pressure_angle_deg=size.max_pressure_angle_deg,
                   min_curvature_radius_mm=size.min_curvature_radius_mm,
                   min_curvature_radius_rollers=size.min_curvature_radius_rollers, tool_radius_mm=size.tool_radius_mm,
                   bore_mm=bore_mm, max_contact_stress_mpa=size.max_contact_stress_mpa, min_jump_rpm=size.min_jump_rpm)

    def stress_ok(self, stress):
        """Contact stress within its limit; relative 1e-9: the float noise of the Hertz chain (~1e-15), so a
        limit met with equality is met."""
        return np.asarray(stress) <= self.max_contact_stress_mpa * (1 + LIMIT_RTOL)

    def jump_ok(self, jump_rpm):
        """Jump speed at least the limit, relative 1e-9 as :mod:`camcam.dynamics.checks` holds overspeed × rpm."""
        return np.asarray(jump_rpm) >= self.min_jump_rpm * (1 - LIMIT_RTOL)

    def bore_fits(self, base_radius, roller_radius):
        return np.asarray(base_radius) - np.asarray(roller_radius) >= self.bore_mm / 2 - LIMIT_ATOL

    def curvature_limit(self, roller_radius):
        if self.min_curvature_radius_rollers is not None:
            return self.min_curvature_radius_rollers * np.asarray(roller_radius, float)
        return self.min_curvature_radius_mm

    def feasible(self, valid, undercut, pa, rho, concave, roller_radius, base_radius, stress=None, jump_rpm=None) -> np.ndarray:
        """Element-wise: every constraint met (NaN figures never are)."""
        with np.errstate(invalid="ignore"):
            ok = np.asarray(valid, bool) & ~np.asarray(undercut, bool) & (np.asarray(rho) > 0)
            ok &= self.bore_fits(base_radius, roller_radius)
            if self.max_pressure_angle_deg is not None:
                ok &= np.asarray(pa) <= self.max_pressure_angle_deg + LIMIT_ATOL
            ok &= np.asarray(rho) >= self.curvature_limit(roller_radius) - LIMIT_ATOL
            if self.tool_radius_mm is not None:
                ok &= np.asarray(concave) >= self.tool_radius_mm - LIMIT_ATOL
            if self.max_contact_stress_mpa is not None:
                ok &= self.stress_ok(stress)
            if self.min_jump_rpm is not None:
                ok &= self.jump_ok(jump_rpm)
        return ok

    def failures(self, ex: ExactFigures, roller_radius: float, base_radius: float = math.inf) -> list[str]:
        """The constraints an exactly evaluated design misses, in words (empty: it meets them all)."""
        if not ex.valid:
            return [ex.problem]
        if not self.bore_fits(base_radius, roller_radius):
            return [f"the bore Ø{self.bore_mm:g} mm does not fit inside the base circle minus the roller"]
        if ex.undercut:
            return ["undercut (or a cusp)"]
        out = []
        if self.max_pressure_angle_deg is not None and not ex.max_pressure_angle_deg <= self.max_pressure_angle_deg + LIMIT_ATOL:
            out.append(f"pressure angle {ex.max_pressure_angle_deg:.4f}° > {self.max_pressure_angle_deg:g}°")
        lim = float(self.curvature_limit(roller_radius))
        if not (ex.min_curvature_radius_mm >= lim - LIMIT_ATOL and ex.min_curvature_radius_mm > 0):
            out.append(f"radius of curvature {ex.min_curvature_radius_mm:.4f} mm < {lim:g} mm")
        if self.tool_radius_mm is not None and not ex.min_concave_radius_mm >= self.tool_radius_mm - LIMIT_ATOL:
            out.append(f"smallest concave radius {ex.min_concave_radius_mm:.4f} mm < tool radius {self.tool_radius_mm:g} mm")
        if (self.max_contact_stress_mpa is not None or self.min_jump_rpm is not None) and ex.dynamics_problem:
            out.append(ex.dynamics_problem)
            return out
        if self.max_contact_stress_mpa is not None and not self.stress_ok(ex.max_contact_stress_mpa):
            out.append(f"contact stress {ex.max_contact_stress_mpa:.4f} MPa > {self.max_contact_stress_mpa:g} MPa")
        if self.min_jump_rpm is not None and not self.jump_ok(ex.jump_rpm):
            out.append(f"jump speed {ex.jump_rpm:.4f} rpm < {self.min_jump_rpm:g} rpm")
        return out


@dataclass(frozen=True, kw_only=True)
class SizingResult:
    """The whole table (columns in order), the feasible set ranked, and the best design."""

    kind: str
    rotation: str
    grid: DesignGrid
    limits: Limits
    objective: str
    table: dict[str, np.ndarray]
    ranked: np.ndarray  # feasible design numbers, best first (grid figures)
    best: int | None
    best_exact: ExactFigures | None
    checked: tuple[tuple[int, ExactFigures], ...]  # every exact check, in order
    programs: tuple[MotionProgram, ...]
    samples_per_rev: int
    note: str = ""

    @property
    def objective_column(self) -> str:
        return "outer_radius_mm" if self.objective == "outer-radius" else "max_pressure_angle_deg"

    def params(self, number: int) -> dict[str, float]:
        return self.grid.design(number)[0]

    def laws(self, number: int) -> dict[int, str]:
        return self.grid.design(number)[1]


def combo_program(motion, unit: str, segments: tuple[int, ...], laws: tuple[str, ...]) -> MotionProgram:
    """The motion program with segment ``segments[i]``'s law replaced by ``laws[i]``."""
    segs = list(motion.segments)
    for k, name in zip(segments, laws):
        segs[k] = replace(segs[k], law_name=name, law=make_law(name))
    return replace(motion, segments=tuple(segs)).program(unit)


def _table(grid: DesignGrid, blocks: list[dict], chunks: list[Chunk], feasible_fn, jump=None) -> dict[str, np.ndarray]:
    n = len(grid)
    cols: dict[str, np.ndarray] = {"design": np.arange(n)}
    combo_of = np.repeat(np.arange(len(grid.combos)), grid.per_combo)
    for j, seg in enumerate(grid.segments):
        names = np.array([c[j] for c in grid.combos])
        cols[f"law_segment_{seg}"] = names[combo_of]
    for name, _ in grid.axes:
        cols[f"{name}_mm"] = np.empty(n)
    figures = FIGURES + (("max_contact_stress_mpa",) if "max_contact_stress_mpa" in blocks[0] else ())
    for name in figures:
        cols[name] = np.empty(n, bool if name in ("valid", "undercut") else float)
    for chunk, block in zip(chunks, blocks):
        lo = chunk.combo * grid.per_combo + chunk.start
        hi = chunk.combo * grid.per_combo + chunk.stop
        for name, vals in grid.params(chunk.combo, chunk.start, chunk.stop).items():
            cols[f"{name}_mm"][lo:hi] = vals
        for name in figures:
            cols[name][lo:hi] = block[name]
    if jump is not None:
        cols["jump_rpm"] = jump(cols)
    cols["feasible"] = feasible_fn(cols)
    return cols


def _jump_column(contact: SweepDynamics, programs, grid: DesignGrid, cols) -> np.ndarray:
    """Each design's exact jump speed (rpm): one :func:`~camcam.dynamics.cycle.program_jump_speed` per law
    combination and lever (the arm length, for an oscillating roller without load_arm_mm), spread over the rows."""
    combo = cols["design"] // grid.per_combo
    arm = cols["arm_length_mm"] if contact.oscillating and contact.spec.load_arm_mm is None else np.zeros(combo.size)
    out = np.empty(combo.size)
    keys = np.stack([combo.astype(float), arm], axis=1)
    uniq, inverse = np.unique(keys, axis=0, return_inverse=True)
    values = [contact.jump_rpm(programs[int(c)], a if contact.oscillating else None) for c, a in uniq]
    out[:] = np.asarray(values)[inverse.ravel()]
    return out


def run_sweep(spec, executor: Executor) -> SizingResult:
    """Run ``spec``'s ``[size]`` sweep on ``executor``; see the module docstring."""
    size: SizeSpec = spec.need("size", "size")
    kind, rotation = spec.follower.kind, spec.cam.rotation
    grid = DesignGrid.of(size)
    if len(grid) == 0:
        raise SpecError("size", "the sweep is empty")
    programs = tuple(combo_program(spec.motion, spec.unit, grid.segments, c) for c in grid.combos)
    samples = tuple(sample_program(p, size.samples) for p in programs)
    contact = SweepDynamics.of(spec) if size.dynamic else None
    ctx = SweepContext(kind, SIGMA[rotation], grid, samples, contact=contact)
    chunks = grid.chunks()
    blocks = executor.map(evaluate_chunk, chunks, what=f"{len(grid):,} designs", ctx=ctx)
    limits = Limits.of(size, spec.cam.bore)

    def feasible(c):
        rr = c["roller_radius_mm"] if "roller_radius_mm" in c else np.zeros(len(c["design"]))
        return limits.feasible(c["valid"], c["undercut"], c["max_pressure_angle_deg"], c["min_curvature_radius_mm"],
                               c["min_concave_radius_mm"], rr, c["base_radius_mm"], c.get("max_contact_stress_mpa"),
                               c.get("jump_rpm"))

    table = _table(grid, blocks, chunks, feasible, None if contact is None else lambda c: _jump_column(contact, programs, grid, c))
    obj_col = "outer_radius_mm" if size.objective == "outer-radius" else "max_pressure_angle_deg"
    feas = np.flatnonzero(table["feasible"])
    key_obj = np.round(table[obj_col][feas] / TIE) * TIE
    key_pa = np.round(table["max_pressure_angle_deg"][feas] / TIE) * TIE
    ranked = feas[np.lexsort((feas, key_pa, key_obj))]
    best, best_ex, best_key, checked, note = None, None, None, [], ""
    for number in ranked:
        grid_obj = float(table[obj_col][number])
        if best_key is not None and grid_obj >= best_key[0] - TIE:
            break
        if len(checked) >= MAX_EXACT_CHECKS:
            note = f"stopped after {MAX_EXACT_CHECKS} exact checks; the best design may be a little larger than shown"
            break
        params, laws = grid.design(int(number))
        combo = int(number) // grid.per_combo
        ex = exact_figures(kind, programs[combo], params, rotation, contact and (contact, spec.cam))
        checked.append((int(number), ex))
        if limits.failures(ex, params.get("roller_radius", 0.0), params["base_radius"]):
            continue
        value = ex.outer_radius_mm if size.objective == "outer-radius" else ex.max_pressure_angle_deg
        key = (round(value / TIE) * TIE, round(ex.max_pressure_angle_deg / TIE) * TIE, int(number))
        if best_key is None or key < best_key:
            best, best_ex, best_key = int(number), ex, key
    return SizingResult(kind=kind, rotation=rotation, grid=grid, limits=limits, objective=size.objective, table=table,
                        ranked=ranked, best=best, best_exact=best_ex, checked=tuple(checked),
                        programs=programs, samples_per_rev=size.samples, note=note)


def grid_bounds(result: SizingResult) -> tuple[float, float]:
    """The largest estimated grid bounds over the feasible set: (pressure angle °, radius of curvature mm)."""
    f = result.table["feasible"]
    if not f.any():
        f = result.table["valid"]
    pa = result.table["pressure_angle_bound_deg"][f]
    rho = result.table["curvature_radius_bound_mm"][f]
    return (float(np.nanmax(pa)) if pa.size else math.nan, float(np.nanmax(rho)) if rho.size else math.nan)
