"""The NC second fitting: arcs (G1-continuous arc spline) or lines, deviation guaranteed.

Arcs.  A near-minimal G1 arc spline per G1 section of the curve (the whole
contour unless it has corners), marched on the printed numbers by
:mod:`camcam.toolpath.arcspline` (its docstring gives the method, the
literature and why it was chosen): joints on or near the curve, each arc
swinging across the whole band two-sided, a beam search over the joint
sequences, closed by a biarc onto the exact end tangent or, on a closed
contour, by one arc landing on an early arc's circle (or a biarc onto its
joint); a closed contour over 1.2·N_lb + 4 is marched again from further
starts in its dwells.  1.28–1.57·N_lb blocks on the disc samples at
0.01–0.0005 mm (38 of their 40 contour × tolerance cases within 1.2·N_lb + 4),
N_lb = ∫(|κ′|/192δ)^⅓ ds (:mod:`camcam.toolpath.lowerbound`).

Lines.  The seed paper's chordal method (Hu & Guo, eq. 8): a chord of length
L on curvature radius ρ errs by δ ≈ L²/(8ρ), so the step starts from
L = √(8ρδ) and is lengthened or shortened until the chord is within tolerance.

Guarantee.  Every node, arc end and centre is put on the post's printed grid
(:class:`~camcam.toolpath.quantizer.Quantizer`), each piece is rebuilt as the
controller cuts it and measured two-sided against the exact curve by
:func:`measure_deviation` (which adds its own between-sample bound).  The
shares of the tolerance and the one retry loop are
:class:`~camcam.toolpath.budget.FitBudget`'s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from camcam.errors import FitError, InputError
from camcam.toolpath.mapper import IN_PROCESS, Mapper
from camcam.geometry.curve import PlanarCurve, curvature, speed
from camcam.toolpath.arcspline import fit_arc_spline, g1_sections
from camcam.toolpath.arcsweep import parts_within
from camcam.toolpath.budget import DEFAULT_BUDGET, FitBudget
from camcam.toolpath.deviation import Deviation, measure_deviation
from camcam.toolpath.elements import Arc, Line
from camcam.toolpath.fitcore import Piece, greedy, lines_deviation, pieces
from camcam.toolpath.lowerbound import line_estimate_blocks, line_estimate_pieces, lower_bound_blocks, lower_bound_pieces
from camcam.toolpath.quantizer import Quantizer

__all__ = ["FitResult", "fit_contour", "lower_bound_blocks", "line_estimate_blocks"]


@dataclass(frozen=True, kw_only=True)
class FitResult:
    """A fitted contour: elements on the decimal grid, in the curve's direction."""

    elements: tuple
    mode: str
    tolerance_mm: float
    decimals: int
    deviation: Deviation
    lower_bound: float  # N_lb for arcs (∫(|κ′|/192δ)^⅓ ds), for lines ∫√(|κ|/8δ) ds
    piece_blocks: tuple[int, ...]
    piece_lower_bounds: tuple[float, ...]
    #: ``deviation`` was measured on the whole printed path over the whole curve (one section, nothing
    #: left out), so it is that path's deviation as it stands, not only the worst of its pieces'.
    measured_whole: bool = False
    #: arcs mode: the G1 sections (lo, hi, why) whose arc spline missed and that were fitted with lines
    #: instead (issue 43 C), so that a valid curve always has a program
    lines_sections: tuple = ()

    @property
    def line_blocks(self) -> int:
        return sum(isinstance(e, Line) for e in self.elements)

    @property
    def arc_blocks(self) -> int:
        return sum(isinstance(e, Arc) for e in self.elements)

    @property
    def max_deviation_mm(self) -> float:
        return self.deviation.max_deviation_mm


def _fit_lines_piece(piece, tolerance_mm):
    a, b = piece.a, piece.b
    k = np.abs(curvature(piece.curve, piece.grid))
    v = speed(piece.curve, piece.grid)

    def deviations(t0, ts):
        return lines_deviation(piece, t0, ts, tolerance_mm)

    nodes = [a]
    while nodes[-1] < b:
        t0 = nodes[-1]
        j = int(np.searchsorted(piece.grid, t0))
        j = min(j, len(piece.grid) - 1)
        step_mm = math.sqrt(8.0 * tolerance_mm / max(k[j], 1e-12))  # seed paper eq. (8): δ = L²/8ρ
        nodes.append(greedy(t0, b, deviations, tolerance_mm, step_mm / max(v[j], 1e-12)))
    pts = piece.point(np.array(nodes))
    return [Line(tuple(p), tuple(q)) for p, q in zip(pts[:-1], pts[1:])]


def _fit_arcs(curve, tolerance_mm, band, quantizer, max_sweep, a, b, exact, printed, budget, mapper) -> FitResult:
    """Arcs: one near-minimal printed G1 arc spline per G1 section (:mod:`camcam.toolpath.arcspline`).

    The march measures its candidates as printed, so its band leaves no
    rounding share for I/J posts (:meth:`FitBudget.spline_targets`); every
    section is printed, measured against the exact curve and refitted tighter
    if it misses (the one retry loop).
    """
    targets = tuple(budget.spline_targets(band, quantizer))
    sag = budget.sag_mm(targets[0], quantizer)  # arcs flatter than this print as lines
    margin = budget.margin_mm(tolerance_mm)
    edges = pieces(curve, a, b)
    sections = g1_sections(curve, edges[0][0], edges[-1][1])
    whole = bool(curve.closed) and len(sections) == 1 and edges[0][0] == curve.t_start and \
        edges[-1][1] == curve.t_end
    # a closed section's goal is on the exact curve's N_lb, the bound block counts are judged by, not on
    # the Chebyshev copy's (higher on a noisy curve); taken at the first band (N_lb ∝ δ^(-1/3)) for
    # every attempt, so a tighter retry does not loosen the goal
    lbs = lower_bound_pieces(exact, tolerance_mm, edges)
    band_lb = float(sum(lbs)) * float(np.cbrt(tolerance_mm / targets[0])) if whole else None
    elems, starts, worst, fallbacks = [], [], None, []
    for lo, hi in sections:
        for target in targets:
            try:
                spline = fit_arc_spline(curve, lo, hi, target, quantizer=quantizer, max_sweep=max_sweep, sag=sag,
                                        closed=whole, mapper=mapper, lower_bound=band_lb)
            except FitError as err:
                # no march closed (every start of a closed section, the one of an open one): a tighter band
                # would march the same way, so the section is fitted with lines (below)
                spline, missed = None, str(err)
                break
            # arcs planned at the post's limit may print a hair over it: cut into parts before measuring
            split = [parts_within(e, quantizer, math.degrees(max_sweep)) if isinstance(e, Arc) else (e,)
                     for e in spline.elements]
            elements = tuple(p for ps in split for p in ps)
            dev_s = measure_deviation(exact, printed(elements), lo, hi, margin_mm=margin)
            if dev_s.max_deviation_mm <= tolerance_mm:
                section_starts = [t for ps, t in zip(split, spline.starts) for _ in ps]  # a cut arc's parts count
                break                                                                    # where it began
            missed = (f"the printed path stays {dev_s.max_deviation_mm:.4g} mm off after {budget.attempts} "
                      f"attempts")
        else:
            spline = None
        if spline is None:
            # the last resort, so that a valid smooth curve always has a program (issue 43 C): the section's
            # analytic pieces fitted by the lines method at its own targets, printed and measured two-sided
            # like every fit; FitError only if that misses too
            elements, section_starts, dev_s = _lines_section(curve, exact, printed, quantizer, band, tolerance_mm,
                                                             lo, hi, budget, missed)
            fallbacks.append((lo, hi, missed))
        elems.extend(elements)
        starts.extend(section_starts)
        if worst is None or dev_s.max_deviation_mm > worst.max_deviation_mm:
            worst = dev_s
    starts = np.asarray(starts)
    last = edges[-1][1]
    blocks = [int(np.count_nonzero((starts >= lo) & ((starts < hi) | (hi == last))))
              for lo, hi in edges]  # each arc counts on the piece its start joint lies on
    measured_whole = len(sections) == 1 and sections[0] == (exact.t_start, exact.t_end)
    return FitResult(elements=tuple(elems), mode="arcs", tolerance_mm=tolerance_mm, decimals=quantizer.decimals,
                     deviation=worst, lower_bound=float(sum(lbs)),
                     piece_blocks=tuple(blocks), piece_lower_bounds=tuple(lbs), measured_whole=measured_whole,
                     lines_sections=tuple(fallbacks))


def _lines_section(curve, exact, printed, quantizer, band, tolerance_mm, lo, hi, budget, missed):
    """Section [lo, hi] of an arcs fit whose arc spline missed (``missed`` says how), fitted with lines.

    Each analytic piece of the section by the lines method (:func:`_fit_lines_piece`, seed 004's chords)
    at the budget's lines targets, snapped to the printed grid; the section's printed path is measured
    two-sided against the exact curve, and fitted again tighter while it misses.  Returns (elements, the
    curve parameter each starts at, deviation).
    """
    margin = budget.margin_mm(tolerance_mm)
    dev = None
    for target in budget.targets(band, quantizer):
        elements, starts = [], []
        for p_lo, p_hi in pieces(curve, lo, hi):
            piece = Piece(curve, p_lo, p_hi)
            lines = quantizer.snap_elements(_fit_lines_piece(piece, target))
            elements.extend(lines)
            starts.extend(np.linspace(p_lo, p_hi, len(lines), endpoint=False).tolist())
        dev = measure_deviation(exact, printed(tuple(elements)), lo, hi, margin_mm=margin)
        if dev.max_deviation_mm <= tolerance_mm:
            return tuple(elements), starts, dev
    raise FitError(f"cannot fit the curve on t ∈ [{lo:g}, {hi:g}] within {tolerance_mm:g} mm: {missed}; with "
                   f"lines the printed path stays {dev.max_deviation_mm:.4g} mm off after {budget.attempts} attempts")


def fit_contour(curve: PlanarCurve, tolerance_mm: float, *, mode: str = "arcs",
                quantizer: Quantizer = Quantizer(4), max_sweep_deg: float = 90.0,
                a: float | None = None, b: float | None = None, exact: PlanarCurve | None = None,
                printed: Callable[[tuple], tuple] | None = None, budget: FitBudget = DEFAULT_BUDGET,
                mapper: Mapper = IN_PROCESS) -> FitResult:
    """Fit lines/arcs to ``curve`` with a guaranteed two-sided deviation ≤ ``tolerance_mm`` as printed.

    Each analytic piece is fitted, put on the printed grid, rebuilt as the
    controller will cut it (``printed``) and measured two-sided against the
    exact curve; a piece that misses is fitted again at a tighter target
    (:meth:`FitBudget.targets`, the one retry loop).

    Parameters
    ----------
    curve : PlanarCurve
        The curve the march runs on: the exact curve, or a surrogate of it
        (with an ``error_mm`` attribute) when ``exact`` is given.
    tolerance_mm : float
        Two-sided deviation allowed on the program as printed.
    mode : {"arcs", "lines"}
    quantizer : Quantizer
        The post's printed rounding: nodes and centres are snapped to its grid.
    max_sweep_deg : float
        Largest arc sweep (≤ 180; also keeps arcs away from full circles).
    a, b : float, optional
        Parameter range (default the whole curve).
    exact : PlanarCurve, optional
        The curve the printed path is measured against (default ``curve``).
    printed : callable, optional
        Snapped elements → the path the controller cuts (default
        ``quantizer.printed_elements``; the rotary job passes its (X, A) model).
    budget : FitBudget
        How the tolerance is shared out.

    Returns
    -------
    FitResult
        Elements on the printed grid, in the curve's direction.

    Raises
    ------
    InputError
        When the tolerance is below the decimals' floor or the mode unknown.
    FitError
        When a piece still misses after the budget's last attempt.

    Examples
    --------
    >>> import numpy as np
    >>> from camcam.geometry.jet import Jet
    >>> from camcam.geometry.jetcurve import JetCurve
    >>> ellipse = JetCurve(lambda t, K, piece=None: (Jet.variable(t, K).cos() * 30.0, Jet.variable(t, K).sin() * 20.0),
    ...                    np.array([0.0, np.pi, 2 * np.pi]))
    >>> fit = fit_contour(ellipse, 0.01)
    >>> fit.arc_blocks > 0 and fit.max_deviation_mm <= 0.01
    True
    """
    if mode not in ("arcs", "lines"):
        raise InputError(f"mode: expected 'arcs' or 'lines', got {mode!r}")
    if not 0 < max_sweep_deg <= 180:
        raise InputError(f"max_sweep_deg: expected 0 < value ≤ 180, got {max_sweep_deg!r}")
    exact = curve if exact is None else exact
    printed = quantizer.printed_elements if printed is None else printed
    band = tolerance_mm - (getattr(curve, "error_mm", 0.0) if exact is not curve else 0.0)
    if not budget.holds(band, quantizer):
        raise InputError(f"tolerance {tolerance_mm:g} mm is too fine for {quantizer.decimals} decimals "
                         f"(rounding alone takes {budget.rounding_mm(quantizer):.2g} mm); use at least "
                         f"{budget.floor_mm(quantizer):.2g} mm or more decimals")
    if mode == "arcs":
        return _fit_arcs(curve, tolerance_mm, band, quantizer, math.radians(max_sweep_deg), a, b, exact, printed,
                         budget, mapper)
    targets = tuple(budget.targets(band, quantizer))  # lines: the sag and sweep limits concern arcs only
    margin = budget.margin_mm(tolerance_mm)
    edges = pieces(curve, a, b)
    lbs = line_estimate_pieces(exact, tolerance_mm, edges)

    def fit_piece(k):
        """Piece k's printed lines and their deviation, or its FitError (raised below in piece order)."""
        lo, hi = edges[k]
        piece = Piece(curve, lo, hi)
        for target in targets:
            elems = quantizer.snap_elements(_fit_lines_piece(piece, target))
            dev = measure_deviation(exact, printed(elems), lo, hi, margin_mm=margin)
            if dev.max_deviation_mm <= tolerance_mm:
                return elems, dev
        return FitError(f"cannot fit the curve on t ∈ [{lo:g}, {hi:g}] within {tolerance_mm:g} mm: the printed "
                        f"path stays {dev.max_deviation_mm:.4g} mm off after {budget.attempts} attempts")

    # the pieces are independent: shared out by ``mapper`` (camcam.toolpath.mapper), the dearest (most lines estimated) first
    # so that they end together (disc-oscillating-flat at 0.001 mm: 229, 192, 113 and 98 lines); each is the
    # same call as in a plain loop, so the same lines
    order = sorted(range(len(edges)), key=lambda k: -lbs[k])
    fitted = dict(zip(order, mapper(fit_piece, order)))
    all_elems, blocks = [], []
    worst = None
    for k in range(len(edges)):
        if isinstance(fitted[k], FitError):
            raise fitted[k]
        elems, dev = fitted[k]
        all_elems.extend(elems)
        blocks.append(len(elems))
        if worst is None or dev.max_deviation_mm > worst.max_deviation_mm:
            worst = dev
    return FitResult(elements=tuple(all_elems), mode=mode, tolerance_mm=tolerance_mm, decimals=quantizer.decimals,
                     deviation=worst, lower_bound=float(sum(lbs)),
                     piece_blocks=tuple(blocks), piece_lower_bounds=tuple(lbs))
