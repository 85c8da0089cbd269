"""Tool paths: the NC second fitting (arcs and lines with a guaranteed deviation on the printed
numbers), the printed rounding, the tolerance budget, two-sided deviation measurement, and the
neutral :class:`Toolpath` of :class:`Pass` records the posts print."""

from camcam.toolpath.arcfit import FitResult, fit_contour
from camcam.toolpath.lowerbound import line_estimate_blocks, lower_bound_blocks
from camcam.toolpath.budget import FitBudget, DEFAULT_BUDGET
from camcam.toolpath.quantizer import Quantizer
from camcam.toolpath.contours import CutContour, fit_printed
from camcam.toolpath.deviation import Deviation, measure_deviation
from camcam.toolpath.elements import Line, Arc
from camcam.toolpath.path import Toolpath, Pass, CutSettings, Rapid, Feed, ArcMove, contour_toolpath, slot_toolpath, rotary_toolpath

__all__ = ["FitResult", "fit_contour", "lower_bound_blocks", "line_estimate_blocks", "FitBudget", "DEFAULT_BUDGET", "Quantizer", "CutContour", "fit_printed", "Deviation", "measure_deviation", "Line", "Arc", "Toolpath", "Pass", "CutSettings", "Rapid", "Feed", "ArcMove", "contour_toolpath", "slot_toolpath", "rotary_toolpath"]
