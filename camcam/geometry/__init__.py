"""Geometry stage: pitch curves, profiles and cams as exact parametric curves, their analysis and meshes.

The public names load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("CamSpec", "FollowerSpec", "CAM_KINDS", "FOLLOWER_KINDS"), "camcam.geometry.params"),
    **dict.fromkeys(("FOLLOWERS", "follower_kind"), "camcam.geometry.followers"),
    **dict.fromkeys(("BuiltCam", "build_cam"), "camcam.geometry.build"),
    **dict.fromkeys(("DiscCam",), "camcam.geometry.disc"),
    **dict.fromkeys(("GrooveCam",), "camcam.geometry.groove"),
    **dict.fromkeys(("CylindricalCam", "BarrelTranslatingRoller", "BarrelOscillatingRoller"), "camcam.geometry.cylindrical"),
    **dict.fromkeys(("DiscAnalysis", "analyse"), "camcam.geometry.analysis"),
    **dict.fromkeys(("Sizing", "size_cam"), "camcam.geometry.smallest_cam"),
    **dict.fromkeys(("cam_volume",), "camcam.geometry.exact_volume"),
})
