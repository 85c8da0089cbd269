"""Reverse design (seed 002): from measured points on a cam back to its motion law."""

from camcam.reverse.design import ReverseOptions, ReverseResult, design_motion, reverse_design
from camcam.reverse.points import MeasuredPoints, load_points, parse_points

__all__ = ["ReverseOptions", "ReverseResult", "reverse_design", "design_motion", "MeasuredPoints", "load_points", "parse_points"]
