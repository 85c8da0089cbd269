"""The 3-D groove measurement gives the same figures whether one process or two share its work."""

import numpy as np

from camcam.geometry.cylindrical import BarrelTranslatingRoller, CylindricalCam
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.verify.groove3d import measure_groove
from camcam.verify.groove_motion import follower_poses
from camcam.toolpath.poses import CylinderTool, ToolPoses


def test_two_workers_same_measurement():
    law = make_law("cycloidal")
    prog = MotionProgram((Segment(law, 0, 180, 20.0), Segment(law, 180, 360, -20.0, base=20.0)), rpm=60)
    cam = CylindricalCam(BarrelTranslatingRoller(8.0), prog, 50.0, length=80.0, groove_depth=10.0)
    X, Y, Z, a, B = follower_poses(cam, np.radians(np.arange(0.0, 360.01, 0.5)))
    # a tool 0.2 mm smaller than the roller, posed like it: both walls left with material, refined
    poses = ToolPoses(np.stack([X, Y, Z + 30.0], axis=-1), np.degrees(a), np.degrees(B))
    one = measure_groove(cam, CylinderTool(7.8, 40.0), poses, radii=5, angle_step_deg=2.0, workers=1)
    two = measure_groove(cam, CylinderTool(7.8, 40.0), poses, radii=5, angle_step_deg=2.0, workers=2)
    # the same calls in a different process: bit-identical figures (no tolerance needed)
    assert np.array_equal(one.deviation_mm, two.deviation_mm)
    assert one.walls == two.walls and one.uncut_points == two.uncut_points
    assert one.max_deviation_mm > 0.1  # a real measurement: 0.2 mm less tool diameter leaves ~0.2 mm
