"""Exporters: the bytes of every output file (program, DXF, STL, STEP, CSV tables, report JSON) and
the all-or-nothing writer.

The public names load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("OutputSet", "atomic_write"), "camcam.export.files"),
    **dict.fromkeys(("nc_files", "nc_dxf"), "camcam.export.nc"),
    **dict.fromkeys(("stl_bytes",), "camcam.export.stl"),
    **dict.fromkeys(("cam_step", "read_step", "cad_available"), "camcam.export.step"),
    **dict.fromkeys(("contour_dxf",), "camcam.export.dxf"),
    **dict.fromkeys(("cam_report",), "camcam.export.cam_report"),
    **dict.fromkeys(("motion_csv",), "camcam.export.motion_table"),
})
