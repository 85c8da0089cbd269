"""The tolerance budgets: every share of a tolerance the NC stage spends, named and explained in one place.

Three frozen budgets, each passed as a parameter (default: the module's
default object) to the code that spends it; none is a module-level setting:

=========================  ==========================================================
:class:`FitBudget`         a 2-D contour's tolerance δ (disc and face-groove contours,
                           the developed barrel passes' fits, the arc spline and its
                           chain optimiser): :mod:`camcam.toolpath.arcfit`,
                           :mod:`~camcam.toolpath.contours`, :mod:`~camcam.toolpath.arcseed`,
                           :mod:`~camcam.toolpath.arcpolish`, :mod:`camcam.export.nc`
:class:`GrooveBudget`      a barrel groove's tolerance T on 4 axes (the flank plan
                           against the fit, a tilting roller's fit) and the 3-D
                           measurement's pose sampling: :mod:`camcam.nc.rotary`,
                           :mod:`camcam.verify.groove3d`, :mod:`camcam.verify.groove_checks`
:class:`FiveAxisBudget`    a 5-axis groove's tolerance T: the share its pose fit holds
                           (:mod:`camcam.nc.fiveaxis`)
=========================  ==========================================================

The printed R word is not a share: the writer prints it through
:meth:`Quantizer.radius_word <camcam.toolpath.quantizer.Quantizer.radius_word>`,
the same code the fitter's model of the printed arc uses.

The 2-D budget, :class:`FitBudget`.  A printed contour must stay within δ of the exact curve, both ways.  δ is
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

import math
from dataclasses import dataclass

from camcam.toolpath.quantizer import Quantizer

__all__ = ["FitBudget", "DEFAULT_BUDGET", "GrooveBudget", "DEFAULT_GROOVE_BUDGET", "FiveAxisBudget",
           "DEFAULT_FIVE_AXIS_BUDGET"]


@dataclass(frozen=True, kw_only=True)
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
    chain_print_steps : float
        What printing an optimised chain (:mod:`camcam.toolpath.arcseed`,
        :mod:`camcam.toolpath.arcpolish`) may add to its error, in grid steps
        10^−d, not a share of δ: the chain optimiser works to the spline band less
        this (0.4: measured 0.0–0.35 steps on the 12 cases of ``benchmarks/run_nc.py
        --arcs`` whose first march missed the goal).  The printed chain is measured
        afterwards, so the guarantee does not rest on it.
    chain_min_share : float
        The chain optimiser is tried only where the band less the print allowance
        keeps more than this share of the band (0.5); on a grid that coarse the
        rounding dominates and the march, which places every joint on the grid,
        is left to it.
    chain_gap_share : float
        Largest G1 gap × chord (mm) an optimised chain may keep at its joints, as
        a share of the band (0.001): the printed form is G1 up to the rounding,
        rebuilt from the chain's joints and tangents
        (:func:`~camcam.toolpath.arcprint.printed_spline`), so a gap left in the
        chain moves the printed arcs by about that much, which the chain's own
        error does not show (the printed form is measured again).
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
    chain_print_steps: float = 0.4
    chain_min_share: float = 0.5
    chain_gap_share: float = 1e-3
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

    def chain_band_mm(self, band_mm: float, quantizer: Quantizer) -> float:
        """The error an optimised chain may have within a spline band: band − ``chain_print_steps`` grid steps."""
        return band_mm - self.chain_print_steps * quantizer.step_mm

    def chain_holds(self, band_mm: float, quantizer: Quantizer) -> bool:
        """Whether the chain optimiser is worth trying: :meth:`chain_band_mm` above ``chain_min_share`` of the band."""
        return self.chain_band_mm(band_mm, quantizer) > self.chain_min_share * band_mm

    def chain_gap_mm(self, band_mm: float) -> float:
        """The largest G1 gap × chord (mm) an optimised chain may keep: ``chain_gap_share`` of the band."""
        return self.chain_gap_share * band_mm

    def targets(self, tolerance_mm: float, quantizer: Quantizer):
        """The fit targets of the retry loop: the first band, then × ``retry_factor`` each attempt."""
        target = self.fit_target_mm(tolerance_mm, quantizer)
        for _ in range(self.attempts):
            yield target
            target *= self.retry_factor


#: The budget every fit uses unless given another.
DEFAULT_BUDGET = FitBudget()


@dataclass(frozen=True, kw_only=True)
class GrooveBudget:
    """The shares of a barrel groove's tolerance T on 4 axes, and of its 3-D measurement (fractions of T).

    A 4-axis barrel program (:mod:`camcam.nc.rotary`) is fitted in the developed
    plane, each pass within a share of T; what it cuts is measured in 3-D from the
    printed program (:mod:`camcam.verify.groove3d`), and that figure is held to T.

    Parameters
    ----------
    flank_share : float
        A tool thinner than the roller cuts each wall with a flank pass whose
        first-order error e depends on the tool (:mod:`camcam.nc.flank`): the
        smallest tool the note and the advice name is the one whose balanced
        flank error holds this share of T (0.5).
    flank_fit_share : float
        The flank passes' fit keeps T − e, and at least this share of T where e
        takes more than the rest (0.5): :meth:`flank_fit_mm`.  With
        ``flank_share`` it splits T: a tool from the smallest one up leaves the
        fit at least ``flank_fit_share``·T.
    tilt_fit_share : float
        A tilting roller axis (an oscillating roller) on 4 axes: the radial
        tool's error e is the machine's, not the fit's, so every pass's fit is
        held to this share of T (0.25).  Then a plan at T measures at most
        e + share·T (a fit held in the developed plane at the outer radius moves
        the cut at most that much at every depth), and e is at most the measured
        D + share·T: the tolerance the advice names,
        (D + share·T) / (1 − share − ``sampling_share``), holds when accepted
        (:meth:`tilt_tolerance_mm`; issue 43: it named D itself, and a plan fitted
        to the wider tolerance measured more again: 0.0623 → 0.1103 → 0.1559 mm
        on campaign case 43:426).
    sampling_share : float
        The 3-D measurement's motion-sampling bound h²/(8 r) between tool poses
        may take at most this share of T (0.02, as the 2-D measurement's margin
        :attr:`FitBudget.sampling_share`): :meth:`pose_step_mm`, used by
        :func:`camcam.verify.groove3d.pose_step_for` for 4- and 5-axis programs.
    pose_step_mm : float
        The largest step of a tool section between motion samples (mm, 0.5), a
        resolution cap rather than a share: below it the step is the one whose
        bound takes ``sampling_share``·T, the share the plans leave the
        measurement (issue 49: the cap was 0.1 mm, where the bound took 0.4 to
        0.8 % of T at the barrel samples' tolerances and the measurement sampled
        1.4 to 2.2 times as many poses as its share needs, for figures that moved
        by less than 1e-8 mm; the cap binds from T = 0.5²/(0.16 r), 0.2 mm for
        r = 8 mm).

    Examples
    --------
    >>> g = GrooveBudget()
    >>> g.flank_fit_mm(0.01, 0.002), g.flank_fit_mm(0.01, 0.007)
    (0.008, 0.005)
    >>> round(g.tilt_tolerance_mm(0.0623, 0.05), 6)  # 0.0623 mm measured at T = 0.05 mm: what holds
    0.102466
    """

    flank_share: float = 0.5
    flank_fit_share: float = 0.5
    tilt_fit_share: float = 0.25
    sampling_share: float = 0.02
    pose_step_mm: float = 0.5

    def flank_tool_mm(self, tolerance_mm: float) -> float:
        """The flank error the smallest tool must hold: ``flank_share``·T."""
        return self.flank_share * tolerance_mm

    def flank_fit_mm(self, tolerance_mm: float, flank_error_mm: float) -> float:
        """The flank passes' fit band: max(T − e, ``flank_fit_share``·T)."""
        return max(tolerance_mm - flank_error_mm, self.flank_fit_share * tolerance_mm)

    def flank_tolerance_mm(self, measured_mm: float, tolerance_mm: float, flank_error_mm: float) -> float | None:
        """The least tolerance a thinner tool's 4-axis plan provably holds, from the figure D measured at T with
        first-order flank error e; None where no tolerance is certain to.

        The walls' error beyond the fit is at most D + b(T), b = :meth:`flank_fit_mm` (the fit may have offset
        that much of it).  At a tolerance T′ ≤ 2e the flank fit band is ``flank_fit_share``·T′, so a plan at T′
        measures at most D + b(T) + (``flank_fit_share`` + ``sampling_share``)·T′: T′ = (D + b(T)) / (1 −
        ``flank_fit_share`` − ``sampling_share``) holds when it is at most 2e.  Above 2e the band is T′ − e and
        grows with T′ as fast as T′ does: no tolerance there is certain to hold (campaign case 43:48: "accept a
        tolerance of at least 0.2506 mm" measured 0.2812 mm at 0.2506), and the advice names the tool alone.

        Examples
        --------
        >>> b = GrooveBudget()
        >>> round(b.flank_tolerance_mm(0.2506, 0.0031, 0.30), 4)  # e = 0.30: T′ = 0.25215 / 0.48 ≤ 0.6
        0.5253
        >>> b.flank_tolerance_mm(0.2506, 0.0031, 0.25) is None  # 0.5253 > 2 × 0.25
        True
        """
        held = (measured_mm + self.flank_fit_mm(tolerance_mm, flank_error_mm)) / (
            1.0 - self.flank_fit_share - self.sampling_share)
        return held if self.flank_fit_mm(held, flank_error_mm) <= self.flank_fit_share * held else None

    def fit_factor(self, tilts: bool) -> float:
        """The factor on a pass's fit band: ``tilt_fit_share`` where the roller's axis tilts, else 1."""
        return self.tilt_fit_share if tilts else 1.0

    def tilt_tolerance_mm(self, measured_mm: float, tolerance_mm: float) -> float:
        """The least tolerance a tilting roller's 4-axis plan holds, from the figure D measured at T:
        (D + ``tilt_fit_share``·T) / (1 − ``tilt_fit_share`` − ``sampling_share``)."""
        return (measured_mm + self.tilt_fit_share * tolerance_mm) / (1 - self.tilt_fit_share - self.sampling_share)

    def pose_step_for(self, tolerance_mm: float, tool_radius_mm: float) -> float:
        """The pose step (mm) whose sampling bound h²/(8 r) is at most ``sampling_share``·T, at most
        ``pose_step_mm``."""
        return min(self.pose_step_mm, math.sqrt(8.0 * tool_radius_mm * self.sampling_share * tolerance_mm))


#: The budget every barrel plan and 3-D groove measurement uses unless given another.
DEFAULT_GROOVE_BUDGET = GrooveBudget()


@dataclass(frozen=True)
class FiveAxisBudget:
    """The share of a 5-axis groove's tolerance T its pose fit holds (:mod:`camcam.nc.fiveaxis`).

    Parameters
    ----------
    fit_share : float
        The fit holds its error model, max(|n·ΔT|, |n·ΔT − L·ΔB|) on the printed
        nodes, within this share of T (0.8).  The rest is left to what the model
        does not see: its samples per block (24 while fitting, 96 when reporting),
        the second-order terms of the pose error it drops, and the 3-D
        measurement's pose sampling (:attr:`GrooveBudget.sampling_share`, 0.02).
        The printed program is measured in 3-D and held to T, so the guarantee
        does not rest on this share.

    Examples
    --------
    >>> FiveAxisBudget().target_mm(0.01)
    0.008
    """

    fit_share: float = 0.8

    def target_mm(self, tolerance_mm: float) -> float:
        """The band the pose fit holds: ``fit_share``·T."""
        return self.fit_share * tolerance_mm


#: The budget every 5-axis fit uses unless given another.
DEFAULT_FIVE_AXIS_BUDGET = FiveAxisBudget()
