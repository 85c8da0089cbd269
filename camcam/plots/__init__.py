"""Plots rendered to PNG bytes (matplotlib, Agg, deterministic metadata).

The public names load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("svaj_png",), "camcam.plots.svaj"),
    **dict.fromkeys(("cam_png",), "camcam.plots.profile"),
    **dict.fromkeys(("deviation_png", "fitted_motion_png"), "camcam.plots.report_plots"),
    **dict.fromkeys(("lift_comb_png", "profile_comb_png"), "camcam.plots.comb"),
    **dict.fromkeys(("reverse_png",), "camcam.plots.reverse"),
    **dict.fromkeys(("roughness_png",), "camcam.plots.roughness_plot"),
})
