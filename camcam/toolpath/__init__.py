"""Tool paths: the NC second fitting (arcs and lines with a guaranteed deviation on the printed
numbers), the printed rounding, the tolerance budget, two-sided deviation measurement, and the
neutral :class:`Toolpath` of :class:`Pass` records the posts print.

The public names load their module on first use (:mod:`camcam.lazy`): the spec reader needs only
:class:`Toolpath`'s settings and the :class:`Quantizer`, and ``camcam optimize`` reads specs without
importing the fitter's scipy.
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("FitResult", "fit_contour"), "camcam.toolpath.arcfit"),
    **dict.fromkeys(("line_estimate_blocks", "lower_bound_blocks"), "camcam.toolpath.lowerbound"),
    **dict.fromkeys(("FitBudget", "DEFAULT_BUDGET", "GrooveBudget", "DEFAULT_GROOVE_BUDGET", "FiveAxisBudget",
                     "DEFAULT_FIVE_AXIS_BUDGET"), "camcam.toolpath.budget"),
    **dict.fromkeys(("Quantizer",), "camcam.toolpath.quantizer"),
    **dict.fromkeys(("CutContour", "fit_printed"), "camcam.toolpath.contours"),
    **dict.fromkeys(("Deviation", "measure_deviation"), "camcam.toolpath.deviation"),
    **dict.fromkeys(("Line", "Arc"), "camcam.toolpath.elements"),
    **dict.fromkeys(("Toolpath", "Pass", "CutSettings", "Rapid", "Feed", "ArcMove", "contour_toolpath",
                     "slot_toolpath", "rotary_toolpath"), "camcam.toolpath.path"),
})
