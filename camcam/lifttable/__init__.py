"""Lift tables (seed 004): reading, cubic-spline and B-spline fits, bad points, fairing, curvature."""

from camcam.lifttable.table import LiftTable, load_lift_table, parse_lift_table
from camcam.lifttable.process import FairingOptions, FittedTable, fit_table
from camcam.lifttable.table_motion import table_law, table_program

__all__ = ["LiftTable", "load_lift_table", "parse_lift_table", "FairingOptions", "FittedTable", "fit_table", "table_law", "table_program"]
