"""Sizing sweeps: thousands of disc-cam designs evaluated with closed forms, the best one checked exactly.

The public names load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("run_sweep", "SizingResult", "Limits", "evaluate_chunk"), "camcam.size.sweep"),
    **dict.fromkeys(("DesignGrid", "Chunk"), "camcam.size.grid"),
    **dict.fromkeys(("exact_figures", "ExactFigures", "design_cam", "outer_radius"), "camcam.size.exact"),
    **dict.fromkeys(("sample_program", "ProgramSamples"), "camcam.size.samples"),
    **dict.fromkeys(("block_figures",), "camcam.size.kernels"),
})
