"""One cut contour of a cam: its exact tool-centre curve, the fit, the printed path and its deviation.

:func:`fit_printed` fits a curve at the spec's tolerance with the post's
decimals and sweep limit, rebuilds what the post prints (``printed``), and
measures the two-sided deviation of that printed path from the exact curve;
if it is over the tolerance the fit is repeated at a tighter target.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from camcam.errors import FitError, GeometryError, InputError
from camcam.geometry.jet import hypot
from camcam.toolpath.arcfit import FitResult, fit_contour
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.toolpath.deviation import Deviation, measure_deviation
from camcam.toolpath.fitcore import pieces
from camcam.toolpath.mapper import IN_PROCESS, Mapper
from camcam.toolpath.quantizer import Quantizer
from camcam.toolpath.surrogate import chebyshev_curve

__all__ = ["SegmentBlocks", "CutContour", "fit_printed", "OffsetCurve"]


@dataclass(frozen=True)
class SegmentBlocks:
    """Blocks on one motion segment (an analytic piece of the curve) beside the lower bound there."""

    from_deg: float
    to_deg: float
    blocks: int
    lower_bound: float

    @property
    def target(self) -> float:
        """The arc count a near-minimal spline keeps within: 1.2·N_lb + 4 (issue 13's bound)."""
        return 1.2 * self.lower_bound + 4.0


@dataclass(frozen=True, kw_only=True)
class CutContour:
    """One contour the tool follows.

    ``curve`` is the exact tool-centre curve (XY for disc cams; the developed
    plane (u, x) at the reference radius for cylindrical cams), ``printed``
    the path as the program prints it (same plane), ``deviation`` measured
    between the two.  ``offset_mm`` is the tool centre's distance from the
    surface the pass finishes (the tool radius; for a groove centre pass the
    roller radius from each flank).  A barrel cam's cut is measured in 3-D
    by :mod:`camcam.verify.groove3d`, not here.
    """

    label: str
    curve: object
    fit: FitResult
    printed: tuple
    deviation: Deviation
    offset_mm: float
    leads: bool
    segments: tuple[SegmentBlocks, ...]
    stock_side: str = "right"

    @property
    def lower_bound(self) -> float:
        return float(sum(s.lower_bound for s in self.segments))


def fit_printed(curve, tolerance_mm: float, mode: str, quantizer: Quantizer, max_sweep_deg: float,
                printed: Callable[[tuple], tuple], label: str, budget: FitBudget = DEFAULT_BUDGET, mapper: Mapper = IN_PROCESS):
    """Fit ``curve``; return (fit, printed elements, deviation on the printed path, segments).

    ``printed(elements)`` rebuilds the path the program prints from the fitted
    elements.  The march runs on a Chebyshev copy of the curve (within 1e-7
    mm, :mod:`camcam.toolpath.surrogate`); each printed piece is measured
    against the exact ``curve``, both ways (:func:`fit_contour`), and the
    whole printed path once more for the figure reported.

    Raises
    ------
    FitError
        A piece that misses after the budget's last attempt, named by ``label``.
    """
    fast = chebyshev_curve(curve)
    try:
        fit = fit_contour(fast, tolerance_mm, mode=mode, quantizer=quantizer, max_sweep_deg=max_sweep_deg,
                          exact=curve, printed=printed, budget=budget, mapper=mapper)
    except FitError as err:
        raise FitError(f"{label}: {err}") from None
    except InputError as err:
        raise GeometryError(f"{label}: {err}") from None
    path = printed(fit.elements)
    if fit.measured_whole:  # the fit measured this very path over the whole curve already
        dev = fit.deviation
    else:
        dev = measure_deviation(curve, path, margin_mm=budget.margin_mm(tolerance_mm))
    if dev.max_deviation_mm > tolerance_mm:  # every piece passed, so the whole can only pass too
        raise FitError(f"{label}: the printed path stays {dev.max_deviation_mm:.4g} mm from the exact curve, "
                       f"above the tolerance {tolerance_mm:g} mm")
    segs = tuple(SegmentBlocks(math.degrees(lo), math.degrees(hi), n, lb)
                 for (lo, hi), n, lb in zip(pieces(curve), fit.piece_blocks, fit.piece_lower_bounds))
    return fit, path, dev, segs


@dataclass(frozen=True)
class OffsetCurve:
    """``base`` (a jet curve) offset by ``distance_mm`` to its left (negative: right), exact.

    Derivatives to order 2 (they take the base's order 3).

    Examples
    --------
    >>> from camcam.geometry.jet import Jet
    >>> from camcam.geometry.jetcurve import JetCurve
    >>> circle = JetCurve(lambda t, K, piece=None: (Jet.variable(t, K).cos() * 5.0, Jet.variable(t, K).sin() * 5.0),
    ...                   np.array([0.0, 2 * np.pi]))
    >>> [round(float(v), 12) for v in OffsetCurve(circle, 1.0).evaluate([0.0])[0]]  # inward for a ccw circle
    [4.0, 0.0]
    """

    base: object
    distance_mm: float

    @property
    def breaks(self):
        return self.base.breaks

    @property
    def inner(self) -> tuple | np.ndarray:
        """The base's corners inside its pieces (:attr:`~camcam.geometry.jetcurve.JetCurve.inner`), where an
        offset may jump."""
        return getattr(self.base, "inner", ())

    @property
    def t_start(self) -> float:
        return self.base.t_start

    @property
    def t_end(self) -> float:
        return self.base.t_end

    @property
    def closed(self) -> bool:
        return self.base.closed

    def distance(self, t: np.ndarray, order: int, piece: int | None):
        """The offset at ``t`` (a number here; a jet in subclasses whose offset varies)."""
        return self.distance_mm

    def evaluate(self, t, order: int = 0, piece: int | None = None) -> np.ndarray:
        if not 0 <= order <= 2:
            raise ValueError(f"an offset curve gives derivatives up to order 2, asked {order}")
        t = np.atleast_1d(np.asarray(t, float))
        x, y = self.base.jets(t, order + 1, piece)
        tx, ty = x.derivative(), y.derivative()
        v = hypot(tx, ty)
        d = self.distance(t, order, piece)
        ox = x.truncate(order) + (-ty) / v * d
        oy = y.truncate(order) + tx / v * d
        return np.stack([ox.d[order], oy.d[order]], axis=-1)
