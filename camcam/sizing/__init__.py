"""Sizing sweeps (`camcam size`): thousands of disc-cam designs evaluated with closed forms, the best one checked exactly.

Everything of the sweep is here, in the order it runs:

- ``samples``: one motion program evaluated once on the cam-angle grid the sweep shares;
- ``grid``: the designs (swept axes × law choices), numbered and cut in chunks;
- ``kernels``: the closed-form figures of a block of designs (each follower kind's ``size_figures``);
- ``contact``: the ``[size]`` dynamics constraints (contact stress, jump speed) with the ``[dynamics]`` train;
- ``sweep``: the sweep itself (:func:`run_sweep`), on a :mod:`camcam.dask_batch` executor;
- ``exact_check``: one design's figures by the full geometry, the check of the best candidates;
- ``chart``: the sizing chart (PNG);
- ``outputs``: the files `camcam size` writes (tables, best design, spec, chart, page).

The ``[size]`` table of a spec is read with the rest of the spec document, by
:mod:`camcam.spec.size` (``SizeSpec``, re-exported here); the command line is
:mod:`camcam.cli.size`.  One cam sized on its own (no sweep) is the geometry stage's
:func:`camcam.geometry.smallest_cam.size_cam`.

The public names load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("run_sweep", "SizingResult", "Limits", "evaluate_chunk"), "camcam.sizing.sweep"),
    **dict.fromkeys(("DesignGrid", "Chunk"), "camcam.sizing.grid"),
    **dict.fromkeys(("exact_figures", "ExactFigures", "design_cam", "outer_radius"), "camcam.sizing.exact_check"),
    **dict.fromkeys(("sample_program", "ProgramSamples"), "camcam.sizing.samples"),
    **dict.fromkeys(("block_figures",), "camcam.sizing.kernels"),
    **dict.fromkeys(("sizing_png",), "camcam.sizing.chart"),
    **dict.fromkeys(("sizing_files", "parquet_available"), "camcam.sizing.outputs"),
    **dict.fromkeys(("SizeSpec", "SizeAxis"), "camcam.spec.size"),
})
