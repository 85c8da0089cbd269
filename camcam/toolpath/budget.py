"""The tolerance budget of the NC fit: every share of a contour's tolerance δ, named in one place.

A printed contour must stay within δ of the exact curve, both ways.  δ is
spent on four things:

=====================  ===========================================================
rounding               the post's grid step 10^−d: ends and centres each move by at
                       most (√2/2)·10^−d when printed (:mod:`camcam.toolpath.quantizer`)
sampling margin        ``sampling_share``·δ, twice: :func:`measure_deviation` adds it
                       for the deviation between its sample points (once per side)
surrogate              the Chebyshev copy the fitter marches on differs from the exact
                       curve by its own measured error (≤ 1e-7 mm in practice)
fit                    what is left: the band the arc spline or chords may use
=====================  ===========================================================

One more share is not spent on the fit but on measuring it: ``polygon_share``.
The material-removal check (:mod:`camcam.verify.removal`) holds the part, the
flanks, the blank and the bore as polygons (:func:`camcam.nc.stock.curve_polygon`),
whose chords lie off the exact curves; every such measuring polygon chooses its
vertices so that its chord error stays within ``polygon_share``·δ, whatever the
cam's size (δ ≈ ρΔφ²/8 gives the spacing), so the figures it yields are within
that of the figures of the exact curves.

The fit must keep at least ``min_fit_share``·δ, which sets the smallest
tolerance a post's decimals can hold (:meth:`FitBudget.floor_mm`: 10^−d/0.56
with the defaults).  The guarantee does not rest on the budget: every piece
is printed and measured against the exact curve, and a piece that misses is
fitted again at ``retry_factor`` × the previous target, at most ``attempts``
times (one retry loop).

Examples
--------
>>> from camcam.toolpath.quantizer import Quantizer
>>> b = FitBudget()
>>> round(b.floor_mm(Quantizer(4)), 6)   # the README's tolerance floor for 4 decimals
0.000179
>>> round(b.fit_target_mm(0.01, Quantizer(4)), 6)
0.0095
"""

from __future__ import annotations

from dataclasses import dataclass

from camcam.toolpath.quantizer import Quantizer

__all__ = ["FitBudget", "DEFAULT_BUDGET"]


@dataclass(frozen=True)
class FitBudget:
    """The shares of a contour's tolerance δ (fractions of δ unless a unit is named).

    Parameters
    ----------
    sampling_share : float
        Margin :func:`~camcam.toolpath.deviation.measure_deviation` adds for the
        deviation between its samples, per side (0.02·δ).
    min_fit_share : float
        Least share of δ the fit itself must keep; below it the tolerance is under
        the post's floor (0.4).
    sag_step_share, sag_fit_share : float
        An arc flatter than min(sag_step_share·10^−d, sag_fit_share·fit band) prints as a
        line (0.5 grid steps, 0.05 of the band).
    retry_factor : float
        A piece that misses is fitted again at this × the previous target (0.8).
    spline_sampling_share : float
        The arc spline's march (:mod:`camcam.toolpath.arcspline`) measures its
        candidates as printed, so its band is δ less this share only: the final
        measurement's margin (``sampling_share``) and the march's own sampling
        (at most half of it), and 2 % to spare (0.05).  The spare 2 % was first
        kept for the material-removal check, which counted its slab polygons'
        slivers as material left on disc-groove; that check now measures such
        pieces on the moves themselves.  Giving the 2 % back to the march (0.03)
        was measured on the 40 cases of ``benchmarks/run_nc.py --arcs``: 1021
        blocks against 1019, 38 cases within 1.2·N_lb + 4 against 39 (the counts
        move by ±1 either way), so the band stays at 0.95·δ.
    spline_retry_factor : float
        An arc-spline section that misses is marched again at this × the previous
        band (0.93: the arc count grows as band^−⅓, so small steps).
    attempts : int
        Fits of one piece at most before :class:`~camcam.errors.FitError` (6).
    polygon_share : float
        Largest chord error of a measuring polygon (the material check's part,
        flanks, blank and bore), as a share of δ (0.01): a chord of a curve whose
        radius of curvature is ρ errs by about h²/8ρ, so its vertices are placed at
        h = √(8ρ·0.01δ) (0.49 mm at ρ = 3000 mm, δ = 0.001 mm).  The material-left
        and overcut figures measured against such a polygon are within 1 % of δ of
        those against the exact curve.  A polygon needing more vertices than
        :data:`camcam.nc.stock.MAX_POLYGON_POINTS` is coarser and says so (its
        measured chord error is reported with the check).
    """

    sampling_share: float = 0.02
    min_fit_share: float = 0.4
    sag_step_share: float = 0.5
    sag_fit_share: float = 0.05
    retry_factor: float = 0.8
    attempts: int = 6
    spline_sampling_share: float = 0.05
    spline_retry_factor: float = 0.93
    polygon_share: float = 0.01

    def rounding_mm(self, quantizer: Quantizer) -> float:
        """Deviation reserved for printing: one grid step 10^−d.

        The worst case could reach 3 × 0.71·10^−d (both ends and the centre);
        the printed piece is measured afterwards, so the guarantee does not
        rest on this share.
        """
        return quantizer.step_mm

    def margin_mm(self, tolerance_mm: float) -> float:
        """The sampling margin of a deviation measurement at this tolerance."""
        return self.sampling_share * tolerance_mm

    def polygon_mm(self, tolerance_mm: float) -> float:
        """The chord error a measuring polygon may have at this tolerance: ``polygon_share``·δ."""
        return self.polygon_share * tolerance_mm

    def fit_target_mm(self, tolerance_mm: float, quantizer: Quantizer) -> float:
        """The band the first fit may use: δ − rounding − 2 · sampling margin."""
        return tolerance_mm - self.rounding_mm(quantizer) - 2 * self.margin_mm(tolerance_mm)

    def floor_mm(self, quantizer: Quantizer) -> float:
        """The smallest tolerance the post's decimals allow: rounding / (1 − 2·sampling − min_fit)."""
        return self.rounding_mm(quantizer) / (1.0 - 2 * self.sampling_share - self.min_fit_share)

    def holds(self, tolerance_mm: float, quantizer: Quantizer) -> bool:
        """Whether the fit keeps at least ``min_fit_share`` of ``tolerance_mm``."""
        return self.fit_target_mm(tolerance_mm, quantizer) >= self.min_fit_share * tolerance_mm

    def sag_mm(self, fit_mm: float, quantizer: Quantizer) -> float:
        """Arcs flatter than this (mm of sagitta) print as lines."""
        return min(self.sag_step_share * quantizer.step_mm, self.sag_fit_share * fit_mm)

    def spline_targets(self, tolerance_mm: float, quantizer: Quantizer):
        """The bands of the arc spline's retry loop: δ − sampling shares, then × ``spline_retry_factor``.

        The march puts every joint and centre on the grid and measures the
        printed arc, so no rounding share is reserved, except with R words
        (the controller rebuilds the centre from the rounded radius, which the
        march does not model): there one grid step is.

        Examples
        --------
        >>> b = FitBudget()
        >>> [round(t, 7) for t in list(b.spline_targets(0.01, Quantizer(4)))[:2]]
        [0.0095, 0.008835]
        """
        target = tolerance_mm * (1.0 - self.spline_sampling_share)
        if quantizer.arc_format == "r":
            target -= self.rounding_mm(quantizer)
        for _ in range(self.attempts):
            yield target
            target *= self.spline_retry_factor

    def targets(self, tolerance_mm: float, quantizer: Quantizer):
        """The fit targets of the retry loop: the first band, then × ``retry_factor`` each attempt."""
        target = self.fit_target_mm(tolerance_mm, quantizer)
        for _ in range(self.attempts):
            yield target
            target *= self.retry_factor


#: The budget every fit uses unless given another.
DEFAULT_BUDGET = FitBudget()
