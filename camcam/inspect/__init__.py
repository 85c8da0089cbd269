"""Inspection (issue 46): the part as measured against the design, with a verdict.

Measured points or readings (:mod:`camcam.inspect.measured`) are aligned on the
built cam's exact surface (:mod:`camcam.inspect.alignment`,
:mod:`camcam.inspect.nominal`), each given its signed normal deviation and cam
angle, cleaned of outliers by seed 004's bad-point test and fitted back to a
motion by seed 002's reverse design (:mod:`camcam.inspect.part`).  No I/O.
"""

from camcam.inspect.alignment import MODES, Alignment
from camcam.inspect.measured import KINDS, MeasuredPart, parse_bore, parse_measured
from camcam.inspect.part import InspectOptions, Inspection, inspect_part

__all__ = ["MODES", "Alignment", "KINDS", "MeasuredPart", "parse_bore", "parse_measured", "InspectOptions",
           "Inspection", "inspect_part"]
