"""The settings of a machining job: the validated ``[machining]`` and ``[stock]`` tables as the NC stage reads them.

:func:`camcam.spec.machining.read_machining` builds a :class:`MachiningSpec`
from a spec file; the NC stage takes it from there.  The post is reached
through :class:`PostDialect` only (what a job needs of a controller dialect),
so the NC stage does not depend on the post package that prints its result.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Protocol

from camcam.errors import InputError

if TYPE_CHECKING:  # annotations only: reading a spec does not import the tool-path modules
    from camcam.toolpath.path import CutSettings, Toolpath
    from camcam.toolpath.quantizer import Quantizer

__all__ = ["MachiningSpec", "PostDialect", "ProgramSetup", "WORK_OFFSETS", "COOLANTS", "DIRECTIONS", "StockSpec",
           "DEFAULT_STOCK", "DEFAULT_OVERSIZE_MM", "STOCK_KINDS"]

#: The work offsets a spec may name; a post prints each in its own words (``Post.work_offsets``).
WORK_OFFSETS = ("G54", "G55", "G56", "G57", "G58", "G59")

#: The coolant a spec may ask for.
COOLANTS = ("flood", "mist", "off")

#: The values of ``[machining] direction`` (:mod:`camcam.nc.direction`); the first is the default.
DIRECTIONS = ("climb", "conventional")


@dataclass(frozen=True)
class ProgramSetup:
    """What a program states besides its moves: work offset, coolant, program number, source.

    ``program_number`` None takes the post's; ``source`` is the spec's file
    name for the generator line.
    """

    work_offset: str = "G54"
    coolant: str = "flood"
    program_number: int | None = None
    source: str = ""

    def check(self, post) -> None:
        """Raise :class:`InputError` naming the field when ``post`` (a :class:`camcam.post.Post`) cannot print this."""
        if self.work_offset not in WORK_OFFSETS:
            raise InputError(f"work_offset: expected one of {', '.join(WORK_OFFSETS)}, got {self.work_offset!r}")
        if self.coolant not in COOLANTS:
            raise InputError(f"coolant: expected one of {', '.join(COOLANTS)}, got {self.coolant!r}")
        if not post.coolant_word(self.coolant):
            raise InputError(f"coolant: post {post.name} has no word for {self.coolant} coolant")
        if self.program_number is not None:
            if not post.uses_program_number:
                raise InputError(f"program_number: post {post.name} does not print a program number")
            if not 1 <= self.program_number <= post.program_number_max:
                raise InputError(f"program_number: expected 1–{post.program_number_max} for post {post.name}, "
                                 f"got {self.program_number}")


STOCK_KINDS = ("round", "offset")

#: The default blank's radius over the cam's largest radius (mm).
DEFAULT_OVERSIZE_MM = 2.0


@dataclass(frozen=True, kw_only=True)
class StockSpec:
    """The validated ``[stock]`` table.

    ``diameter_mm`` is set for ``kind = "round"`` (``None``: the default blank,
    :data:`DEFAULT_OVERSIZE_MM` over the cam's largest radius), ``allowance_mm``
    for ``kind = "offset"``.  ``stated`` is False when the spec has no ``[stock]``.
    """

    kind: str = "round"
    diameter_mm: float | None = None
    allowance_mm: float | None = None
    top_allowance_mm: float = 0.0
    stated: bool = False


#: The blank when a spec has no ``[stock]`` table.
DEFAULT_STOCK = StockSpec()


class PostDialect(Protocol):
    """What a machining job needs of a controller dialect (:class:`camcam.post.Post` provides it)."""

    name: str
    max_arc_sweep_deg: float
    inverse_time: bool
    five_axis: bool  # has tool-centre-point control (5-axis programs)
    rotary_rapid: bool  # moves its rotary axes in G0 (a barrel pass's A unwind; else the shortest way, A counting on)
    five_axis_feed_note: str  # what the F word of a 5-axis move means (header comment of a 5-axis program)
    rapid_mm_min: float  # the rapid traverse rate the cycle time assumes
    max_feed_mm_min: float | None  # the machine's fastest feed (None: not stated)

    def tcp_comment(self, tool_number: int) -> str:
        """The blocks that switch tool-centre-point control on (header comment of a 5-axis program)."""

    @property
    def quantizer(self) -> Quantizer:
        """The printed rounding."""

    def write_program(self, toolpath: Toolpath, name: str, setup: ProgramSetup = ...):
        """The printed program (:class:`camcam.post.Program`) with the work offset, coolant and number of ``setup``."""


@dataclass(frozen=True, kw_only=True)
class MachiningSpec:
    """The validated ``[machining]`` table (lengths in mm, feeds in mm/min).

    ``post`` is the controller dialect (a :class:`camcam.post.Post`): the job
    reads its :class:`PostDialect` face only.
    """

    post: PostDialect
    tool_diameter_mm: float
    tolerance_mm: float
    mode: str
    feed_mm_min: float
    spindle_rpm: float
    depth_mm: float
    stepdown_mm: float
    plunge_feed_mm_min: float
    safe_z_mm: float
    clearance_z_mm: float
    lead_radius_mm: float
    finish_allowance_mm: float
    spring_pass: bool
    tool_number: int
    accept_out_of_tolerance: bool = False
    setup: ProgramSetup = ProgramSetup()
    flute_length_mm: float = 0.0  # the tool's cutting length (barrel cams' 3-D check)
    flute_stated: bool = True  # False: the spec gave no flute_length (flute_length_mm is then 2 × the tool): flute_for
    holder_diameter_mm: float | None = None  # the tool holder's diameter (with stick_out_mm: the holder check)
    stick_out_mm: float | None = None  # tool tip to the holder's face
    a_axis: str = "right-hand"  # barrel cams: a positive A turns the part by the right-hand rule about +X
    axes: int = 3  # 3 (disc), 4 (barrel: X A) or 5 (barrel, oscillating roller: X Y Z A B, tool on the roller axis)
    stepover: float = 0.4
    ramp_angle_deg: float = 3.0
    bore: bool = False
    dowel: bool = False  # cut the cam's dowel hole as a helical bore (camcam.nc.bore)
    direction: str = "climb"  # or "conventional": which way round every contour runs (camcam.nc.direction)
    cutting: tuple = ()  # rough, finish, spring CuttingData (camcam.nc.cutting_data); () the single feed/spindle

    def cutting_for(self, pass_kind: str):
        """The :class:`~camcam.nc.cutting_data.CuttingData` a pass of ``pass_kind`` cuts with, or None (the single
        ``feed_mm_min`` and ``spindle_rpm``)."""
        if not self.cutting:
            return None
        from camcam.nc.cutting_data import CUT_KINDS, KIND_DATA

        return self.cutting[CUT_KINDS.index(KIND_DATA[pass_kind])]

    @property
    def stepover_mm(self) -> float:
        """The largest radial engagement of a roughing pass (mm): ``stepover`` × the tool diameter."""
        return self.stepover * self.tool_diameter_mm

    def flute_for(self, wanted_mm: float) -> float:
        """The tool's cutting length (mm) a barrel program's checks model, where the printed cut asks for a flute of
        ``wanted_mm`` (:func:`camcam.verify.reach.flute_to_buy_mm`, the setup sheet's): the spec's ``flute_length``;
        where the spec gives none, twice the tool's diameter or, where the cut wants more, that.  Campaign case
        43:34 of the translating barrels (an 8 mm tool, a groove 16.3 mm deep) left the top 0.3 mm of its groove
        uncut with a 16 mm flute nobody asked for, and measured 23.2 mm of material left.

        >>> from camcam.post.post import load_post
        >>> m = MachiningSpec(post=load_post("linuxcnc"), tool_diameter_mm=8.0, tolerance_mm=0.01, mode="lines",
        ...                   feed_mm_min=300.0, spindle_rpm=2000.0, depth_mm=16.3, stepdown_mm=8.15,
        ...                   plunge_feed_mm_min=100.0, safe_z_mm=25.0, clearance_z_mm=2.0, lead_radius_mm=4.0,
        ...                   finish_allowance_mm=0.0, spring_pass=False, tool_number=1, flute_length_mm=16.0,
        ...                   flute_stated=False)
        >>> m.flute_for(10.3), m.flute_for(16.31)
        (16.0, 16.31)
        >>> from dataclasses import replace
        >>> replace(m, flute_stated=True).flute_for(16.31)  # a flute the spec states is the tool's
        16.0
        """
        if self.flute_stated:
            return self.flute_length_mm
        return max(self.flute_length_mm, wanted_mm)

    def cut_settings(self, stock_side: str = "right") -> CutSettings:
        """Settings for :func:`camcam.toolpath.path.contour_toolpath`."""
        from camcam.toolpath.path import CutSettings

        return CutSettings(depth_mm=self.depth_mm, stepdown_mm=self.stepdown_mm, feed_mm_min=self.feed_mm_min,
                           spindle_rpm=self.spindle_rpm, plunge_feed_mm_min=self.plunge_feed_mm_min,
                           safe_z_mm=self.safe_z_mm, clearance_z_mm=self.clearance_z_mm,
                           lead_radius_mm=self.lead_radius_mm, stock_side=stock_side,
                           finish_allowance_mm=self.finish_allowance_mm, spring_pass=self.spring_pass,
                           tool_number=self.tool_number, tool_diameter_mm=self.tool_diameter_mm)
