"""The NC stage: a built cam and its ``[machining]`` settings → a machining job.

Owns the job: the settings it reads (:class:`MachiningSpec`, the post seen as
a :class:`PostDialect`), the blank (:class:`StockSpec` → :class:`Blank`), the
tool-size rules (:mod:`camcam.nc.tools`), the disc roughing
(:mod:`camcam.nc.roughing`), the disc and rotary jobs, the material-removal
check of the printed program (:func:`check_program`), the pass records they cut (:class:`~camcam.toolpath.path.Pass`)
and the result (:class:`MachiningResult`, with its :class:`Program` and its
checks).  It takes fitted paths from :mod:`camcam.toolpath`; the post that it
is handed prints them.

Examples
--------
>>> from camcam.spec import load_spec
>>> from camcam.geometry.build import build_cam
>>> spec = load_spec("samples/disc-translating-roller.toml")
>>> built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
>>> result = machine(built, spec.machining, spec.name, spec.stock)
>>> [(p.contour, p.kind, p.z) for p in result.passes]
[(0, 'rough', -6.0), (0, 'rough', -12.0), (0, 'finish', -12.0), (0, 'spring', -12.0)]
>>> result.max_deviation_mm <= result.tolerance_mm
True
"""

from camcam.nc.job import machine
from camcam.nc.readback import Move, read_program
from camcam.nc.removal import RemovalReport, check_moves, check_program, design_keep
from camcam.nc.result import MachiningResult, Program, deviation_checks
from camcam.nc.settings import MachiningSpec, PostDialect
from camcam.nc.stock import DEFAULT_STOCK, Blank, StockSpec, blank_for
from camcam.nc.tools import SAME_TOOL_MM, check_profile_tool, groove_passes, job_title

__all__ = ["machine", "MachiningResult", "Program", "MachiningSpec", "PostDialect", "deviation_checks",
           "SAME_TOOL_MM", "check_profile_tool", "groove_passes", "job_title", "StockSpec", "DEFAULT_STOCK", "Blank",
           "blank_for", "RemovalReport", "check_moves", "check_program", "design_keep", "Move", "read_program"]
