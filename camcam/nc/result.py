"""The result of a machining job: contours, passes, program, figures and checks (no files)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

from camcam.nc.settings import PostDialect
from camcam.nc.stock import Blank
from camcam.toolpath.contours import CutContour
from camcam.toolpath.path import Pass, Toolpath
from camcam.verdict import Check

if TYPE_CHECKING:  # what camcam.verify measures on the printed program (camcam.verify.job_checks)
    from camcam.verify.cycle_time import CycleTime
    from camcam.verify.motion_time import MotionTime
    from camcam.verify.groove3d import GrooveMeasurement
    from camcam.verify.reach import ToolReach
    from camcam.verify.removal import RemovalReport

__all__ = ["MachiningResult", "Program", "GroovePlan", "deviation_checks"]


@dataclass(frozen=True, kw_only=True)
class Program:
    """A printed program and its block counts (moves only), as a post writes it."""

    text: str
    extension: str
    line_blocks: int
    arc_blocks: int
    rapid_blocks: int
    #: every move as printed, in order: ("rapid", start, end), ("line", start, end, feed mm/min, A0°, A1°),
    #: ("inverse", start, end, F 1/min, A0°, A1°), ("arc", start, end, centre, ccw, feed mm/min),
    #: ("tool change", seconds), ("comment", text) (a pass's name between its moves); positions in mm from
    #: the printed numbers (:mod:`camcam.post.gcode`)
    printed_moves: tuple = ()
    #: the cycle time of the printed moves (:func:`camcam.verify.cycle_time.cycle_time`), set by the job's
    #: checks (:func:`camcam.verify.with_checks`)
    cycle_time: CycleTime | None = None
    #: the cycle time from the motion model, per pass beside the feed-only figure
    #: (:func:`camcam.verify.motion_time.motion_time`), set with ``cycle_time``
    motion_time: MotionTime | None = None


def deviation_checks(contours, tolerance_mm: float) -> tuple[Check, ...]:
    """One check per contour: its two-sided deviation on the printed program against the tolerance."""
    return tuple(Check(f"NC deviation ({c.label})", c.deviation.max_deviation_mm, tolerance_mm, "mm",
                       ok=c.deviation.max_deviation_mm <= tolerance_mm, where="two-sided, on the printed program",
                       advice="this is a fault of the fitter: please report it")
                 for c in contours)


@dataclass(frozen=True, kw_only=True)
class GroovePlan:
    """What a barrel job's plan tells the 3-D check of its printed program (:mod:`camcam.verify.job_checks`).

    ``axes`` is 4 (a radial tool, :mod:`camcam.nc.rotary`) or 5 (the tool on the roller's axis,
    :mod:`camcam.nc.fiveaxis`); ``reach_radius_mm`` the deepest radius the plan takes the tool to (the groove
    floor less the dip it plans below it), ``reach_why`` why it dips; ``cut_length_mm`` (5 axes) how far up
    the tool from its tip the plan's cut reaches; ``flank_error_mm`` (4 axes, a tool thinner than the roller)
    the flank passes' first-order error e the plan balanced (:mod:`camcam.nc.flank`), 0 without flank passes.
    """

    axes: int
    reach_radius_mm: float
    reach_why: str = ""
    cut_length_mm: float | None = None
    flank_error_mm: float = 0.0


@dataclass(frozen=True, kw_only=True)
class MachiningResult:
    """Everything the NC step made for one cam (no files: exporters write them).

    ``toolpath.passes`` are the pass records (:class:`~camcam.toolpath.path.Pass`):
    which contour each pass follows, its kind and depth, in the order the
    program cuts them.  ``checks`` are the job's figures held to their limits
    (:mod:`camcam.verdict`).  ``blank`` (disc and face-groove jobs): the
    blank the job starts from; ``groove_plan`` (barrel jobs): what the 3-D
    check needs from the plan.

    :mod:`camcam.nc` plans and prints; the figures measured on the printed
    program are added by :func:`camcam.verify.job_checks.with_checks`:
    ``removal`` (the material-removal check of a disc or face-groove job),
    ``groove`` and ``reach`` (a barrel job's 3-D check and tool reach) and
    their checks.
    """

    name: str
    cam_kind: str
    follower_kind: str
    post: PostDialect
    tool_diameter_mm: float
    tolerance_mm: float
    mode: str
    contours: tuple[CutContour, ...]
    toolpath: Toolpath
    program: Program
    reference_radius_mm: float | None = None
    notes: tuple[str, ...] = ()
    checks: tuple[Check, ...] = ()
    groove: GrooveMeasurement | None = None
    smallest_tool_mm: float | None = None
    blank: Blank | None = None
    removal: RemovalReport | None = None
    reach: ToolReach | None = None  # barrel programs: how deep the printed tool goes, the flute it needs
    groove_plan: GroovePlan | None = None

    @property
    def rotary(self) -> bool:
        return self.toolpath.rotary

    @property
    def passes(self) -> tuple[Pass, ...]:
        return self.toolpath.passes

    @property
    def program_filename(self) -> str:
        return f"{self.name}.{self.program.extension}"

    @property
    def max_deviation_mm(self) -> float:
        """Largest two-sided deviation of a printed contour from its exact tool-centre curve.

        Barrel cams: the 3-D groove figure (:mod:`camcam.verify.groove3d`), both walls, every radius.
        """
        if self.groove is not None:
            return self.groove.max_deviation_mm
        return max(c.deviation.max_deviation_mm for c in self.contours)

    @property
    def line_blocks(self) -> int:
        """Line blocks on the contours (one pass each; leads and depth repeats not counted)."""
        return sum(c.fit.line_blocks for c in self.contours)

    @property
    def arc_blocks(self) -> int:
        return sum(c.fit.arc_blocks for c in self.contours)

    @property
    def lower_bound_blocks(self) -> float:
        """N_lb = ∫(|κ′|/192δ)^⅓ ds (arcs) or ∫√(|κ|/8δ) ds (lines), summed over the contours."""
        return float(sum(c.lower_bound for c in self.contours))

    def figures(self) -> dict:
        """The NC figures of ``<name>-report.json`` (block counts of one pass per contour)."""
        contours = []
        for c in self.contours:
            contours.append({
                "label": c.label, "offset_mm": c.offset_mm, "max_deviation_mm": c.deviation.max_deviation_mm,
                "line_blocks": c.fit.line_blocks, "arc_blocks": c.fit.arc_blocks, "lower_bound_blocks": c.lower_bound,
                "segments": [{"from_deg": s.from_deg, "to_deg": s.to_deg, "blocks": s.blocks,
                              "lower_bound_blocks": s.lower_bound} for s in c.segments],
            })
        out = {
            "post": self.post.name, "program": self.program_filename, "tool_diameter_mm": self.tool_diameter_mm,
            "tolerance_mm": self.tolerance_mm, "mode": self.mode, "max_deviation_mm": self.max_deviation_mm,
            "line_blocks": self.line_blocks, "arc_blocks": self.arc_blocks,
            "lower_bound_blocks": self.lower_bound_blocks,
            "lower_bound_kind": "arcs: ∫(|κ′|/192δ)^⅓ ds" if self.mode == "arcs" else "lines: ∫√(|κ|/8δ) ds",
            "program_blocks": {"line": self.program.line_blocks, "arc": self.program.arc_blocks,
                               "rapid": self.program.rapid_blocks},
            "reference_radius_mm": self.reference_radius_mm, "contours": contours, "notes": list(self.notes),
            **({"cycle_time_s": self.program.cycle_time.total_s, "cycle_time": self.program.cycle_time.as_dict()}
               if self.program.cycle_time is not None else {}),
            **({"motion_time_s": self.program.motion_time.total_s, "motion_time": self.program.motion_time.as_dict()}
               if self.program.motion_time is not None else {}),
            **({"material": self.material_figures()} if self.removal is not None else {}),
        }
        if self.groove is not None:
            g = self.groove.as_dict()
            out["flank_deviation"] = g.pop("walls")
            out["groove_3d"] = g
            if self.smallest_tool_mm is not None:
                out["smallest_tool_diameter_mm"] = self.smallest_tool_mm
        if self.reach is not None:
            out["tool_reach"] = self.reach.as_dict()
        return out

    def material_figures(self) -> dict:
        """The blank, the passes and the material-removal figures (disc and face-groove jobs)."""
        b = self.blank
        passes = [{"kind": p.kind, "z_mm": p.z, "contour": self.contours[p.contour].label} for p in self.passes]
        return {
            "blank": {"kind": b.kind, "diameter_mm": b.diameter_mm, "allowance_mm": b.allowance_mm,
                      "top_allowance_mm": b.top_z_mm, "stated": b.stated, "description": b.describe(),
                      "cam_largest_radius_mm": b.cam_radius_mm, "top": b.top_note(), "bore": b.bore_note()},
            "passes": passes, **self.removal.as_dict(),
        }
