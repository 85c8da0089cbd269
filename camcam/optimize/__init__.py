"""Optimal cam curves (seed 000): uniform B-spline laws, the paper's Complex
method, and the exact optimum by linear programming."""

from camcam.optimize.bspline_law import BSplineLaw
from camcam.optimize.evaluation import EvaluationFunction, Problem
from camcam.optimize.space import BSplineSpace

__all__ = ["BSplineLaw", "BSplineSpace", "EvaluationFunction", "Problem"]
