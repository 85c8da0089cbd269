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
>>> from camcam.nc import machine_program
>>> spec = load_spec("samples/disc-translating-roller.toml")
>>> built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
>>> result = machine_program(built, spec.machining, spec.name, spec.stock)
>>> [(p.contour, p.kind, p.z) for p in result.passes]
[(0, 'rough', -6.0), (0, 'rough', -12.0), (0, 'finish', -12.0), (0, 'spring', -12.0)]
>>> result.max_deviation_mm <= result.tolerance_mm
True
"""

from camcam.lazy import lazy_exports

# lazy (camcam.lazy): the spec reader needs only the settings; the job pulls in shapely and the geometry
__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("machine_program",), "camcam.nc.job"),
    **dict.fromkeys(("MachiningResult", "Program", "GroovePlan", "deviation_checks"), "camcam.nc.result"),
    **dict.fromkeys(("MachiningSpec", "PostDialect", "StockSpec", "DEFAULT_STOCK"), "camcam.nc.settings"),
    **dict.fromkeys(("Blank", "blank_for"), "camcam.nc.stock"),
    **dict.fromkeys(("SAME_TOOL_MM", "check_profile_tool", "groove_passes", "job_title"), "camcam.nc.tools"),
})
