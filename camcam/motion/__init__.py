"""Motion stage: dimensionless laws, their exact characteristic values, and
motion programs over one cam revolution."""

from camcam.motion.catalog import LAWS, make_law
from camcam.motion.law import Characteristics, Extreme, MotionLaw, PiecewiseLaw
from camcam.motion.program import MotionProgram, Segment

__all__ = ["LAWS", "make_law", "Characteristics", "Extreme", "MotionLaw", "PiecewiseLaw", "MotionProgram", "Segment"]
