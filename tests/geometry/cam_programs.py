
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.motion.standard import dwell


def program(unit="mm", rise=20.0):
    """Modified-sine rise, dwell, cycloidal return, dwell (the demo sample's program)."""
    return MotionProgram(
        (
            Segment(make_law("modified-sine"), 0, 120, rise, base=0.0),
            Segment(dwell(), 120, 180, 1.0, base=rise),
            Segment(make_law("cycloidal"), 180, 300, -rise, base=rise),
            Segment(dwell(), 300, 360, 1.0, base=0.0),
        ),
        rpm=60,
        unit=unit,
    )


