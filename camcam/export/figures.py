"""Printed figures without rounding noise: no ``-0``, no ``-3.55271e-15`` for a figure that is zero.

A figure computed in floating point can come out as ``-1.08e-18`` where the exact value is 0 (a lift at the
start of a rise, S(0) = 0), and a small negative figure printed to a few decimals reads ``-0.0000``.  The
console summaries, the report's tables and their CSV print through these helpers.

Examples
--------
>>> clean(-3.552713678800501e-15, scale=20.0), clean(-0.0), clean(1e-4, scale=20.0)
(0.0, 0.0, 0.0001)
>>> fixed(-0.00001, 4), fixed(-0.00006, 4), fixed(2.5, 3)
('0.0000', '-0.0001', '2.500')
>>> f"{clean(-1.0842e-18, scale=20.0):+12.6g}"
'          +0'
"""

from __future__ import annotations

import math

__all__ = ["clean", "fixed", "NOISE"]

#: A figure this small against the scale of its kind (the largest of its kind printed beside it, or 1) is rounding
#: noise: double precision carries 16 digits, and no figure camcam prints is meant to 9.
NOISE = 1e-9


def clean(value: float, scale: float = 0.0) -> float:
    """``value``, or 0.0 where it is rounding noise: |value| ≤ :data:`NOISE` × max(|scale|, 1); never -0.0."""
    if not math.isfinite(value):
        return value
    if abs(value) <= NOISE * max(abs(scale), 1.0) if math.isfinite(scale) else abs(value) <= NOISE:
        return 0.0
    return value


def fixed(value: float, decimals: int) -> str:
    """``value`` to ``decimals`` decimals, without the sign of a figure that prints as zero ("-0.0000")."""
    text = f"{value:.{decimals}f}"
    if text.startswith("-") and not any(c in "123456789" for c in text):
        return text[1:]
    return text
