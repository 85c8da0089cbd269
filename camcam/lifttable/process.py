"""From a raw lift table to a motion law: bad points, fairing, fit, roughness before and after."""

from __future__ import annotations

from dataclasses import dataclass

from camcam.lifttable.badpoints import DEFAULT_MIN_SIZE, DEFAULT_THRESHOLD, BadPointReport, find_bad_points
from camcam.lifttable.fairing import DEFAULT_MAX_ITERATIONS, DEFAULT_METHOD, DEFAULT_XI, FairingResult, fair
from camcam.lifttable.interpolate import interpolate
from camcam.lifttable.table_motion import table_law
from camcam.lifttable.roughness import Roughness, difference_quotients
from camcam.lifttable.table import LiftTable
from camcam.motion.law import MotionLaw

__all__ = ["FairingOptions", "FittedTable", "fit_table"]


@dataclass(frozen=True, kw_only=True)
class FairingOptions:
    """How to fair a table (``[motion.fairing]`` in a spec, options of ``camcam fit``)."""

    method: str = DEFAULT_METHOD
    xi: float = DEFAULT_XI
    bad_points: bool = True
    threshold: float = DEFAULT_THRESHOLD
    min_size: float = DEFAULT_MIN_SIZE
    max_iterations: int = DEFAULT_MAX_ITERATIONS


@dataclass(frozen=True, kw_only=True)
class FittedTable:
    """Every stage of a table's treatment; ``table`` is what the law interpolates."""

    raw: LiftTable
    fit: str
    bad: BadPointReport | None
    fairing: FairingResult | None
    table: LiftTable
    law: MotionLaw
    roughness_before: Roughness
    roughness_after: Roughness

    def interpolant(self, which: str = "final"):
        """``f(x, nu)`` through the final table (``"final"``) or the raw one (``"raw"``)."""
        t = self.table if which == "final" else self.raw
        return interpolate(t.x, t.y, self.fit, self.end_slopes)

    end_slopes: tuple[float, float] = (0.0, 0.0)


def fit_table(
    raw: LiftTable,
    fit: str,
    fairing: FairingOptions | None = None,
    end_slopes: tuple[float, float] = (0.0, 0.0),
) -> FittedTable:
    """Remove bad points and fair (when ``fairing`` is given), then fit ``fit`` and make the law.

    Examples
    --------
    >>> import numpy as np
    >>> ang = np.arange(0.0, 361.0, 2.0); h = 4 - 4 * np.cos(np.radians(ang))
    >>> ft = fit_table(LiftTable(tuple(ang), tuple(h)), "periodic")
    >>> round(float(ft.law.evaluate(0.25)), 6), ft.bad is None
    (4.0, True)
    """
    bad = fair_result = None
    table = raw
    if fairing is not None:
        if fairing.bad_points:
            bad = find_bad_points(table, fairing.threshold, fairing.min_size)
            table = bad.table
        fair_result = fair(table, fairing.method, fit, fairing.xi, end_slopes, fairing.max_iterations)
        table = fair_result.table
    law = table_law(table, fit, end_slopes)
    return FittedTable(raw=raw, fit=fit, bad=bad, fairing=fair_result, table=table, law=law,
                       roughness_before=difference_quotients(raw), roughness_after=difference_quotients(table),
                       end_slopes=end_slopes)
