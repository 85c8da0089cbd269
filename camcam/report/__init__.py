"""Reports for the machinist and the inspector: self-contained HTML and JSON.

The public names load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("JobReport", "job_report"), "camcam.report.job_page"),
    **dict.fromkeys(("FittedMotion", "fitted_motion"), "camcam.report.fitted_motion"),
    **dict.fromkeys(("InspectionTable", "inspection_table"), "camcam.report.inspection"),
    **dict.fromkeys(("render_html",), "camcam.report.html"),
})
