"""The values advice names: a limit rounded to the 0.01 mm grid on its safe side.

An error that says ``expected at most 38.59 mm`` is followed by users and by the design-space campaign
(``benchmarks/anycam.py``) literally: the value must pass the check that gave it.

Examples
--------
>>> largest_below_mm(38.6), largest_below_mm(38.601)
(38.59, 38.6)
>>> smallest_above_mm(40.41), smallest_above_mm(40.4145)
(40.42, 40.42)
"""

from __future__ import annotations

import math

__all__ = ["largest_below_mm", "smallest_above_mm"]


def largest_below_mm(limit_mm: float) -> float:
    """The largest value on the 0.01 mm grid strictly below ``limit_mm`` (a bore that must stay inside a circle)."""
    return math.floor(limit_mm * 100.0 - 1e-6) / 100.0


def smallest_above_mm(limit_mm: float) -> float:
    """The smallest value on the 0.01 mm grid strictly above ``limit_mm`` (a radius or distance that must exceed
    a bound)."""
    return math.ceil(limit_mm * 100.0 + 1e-9) / 100.0
