"""A valid smooth curve always gets a program (issue 43 C): a march start that finds no closure is one start's
miss, not the contour's; a section no march closes is fitted with lines, measured two-sided like every fit.

The specs are the design-space campaign's (``tests/designspace.py``, seed 43): each ended in exit 1,
``FitError … the march found no printed arc spline``, before.
"""

from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

import camcam.toolpath.arcfit as arcfit
from camcam.errors import FitError
from camcam.geometry.build import build_cam
from camcam.nc.job import _disc_plan
from camcam.spec import load_spec
from camcam.toolpath.arcfit import fit_contour
from camcam.toolpath.contours import fit_printed
from camcam.toolpath.elements import Line
from camcam.toolpath.quantizer import Quantizer
from tests.nc_curves import ellipse
from tests.toolpath.test_arcspline import brute_two_sided

DATA = Path(__file__).parent / "data"


@lru_cache(maxsize=None)
def profile_fit(name: str):
    """(profile tool-centre curve, tolerance, quantizer, fit, printed path, deviation) of a campaign spec."""
    spec = load_spec(DATA / name)
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    m = spec.machining
    ((label, curve, *_),) = _disc_plan(built, m.tool_diameter_mm / 2, m.stepover_mm)
    q = m.post.quantizer
    fit, printed, dev, _ = fit_printed(curve, m.tolerance_mm, m.mode, q, m.post.max_arc_sweep_deg,
                                       q.printed_elements, label)
    return curve, m.tolerance_mm, q, fit, printed, dev


@pytest.mark.parametrize("name,decimals,arcs_at_most", [
    # fanuc, 3 decimals at 0.002 mm: the 5th of the 12 starts found no closure; the others 28-32 arcs
    ("fit-march-43-448.toml", 3, 32),
    # haas at 0.0021 mm, a 0.12 mm rise: the first start found no closure; the others 8-9 arcs
    ("fit-march-43-250.toml", 4, 9),
])
def test_a_start_without_closure_leaves_the_others(name, decimals, arcs_at_most):
    curve, tol, q, fit, printed, dev = profile_fit(name)
    assert q.decimals == decimals
    assert fit.lines_sections == ()  # an arc spline from another start: no lines needed
    assert 0 < fit.arc_blocks <= arcs_at_most  # the counts the other starts reach (measured march by march)
    assert dev.max_deviation_mm <= tol  # the fit's own two-sided measurement of the printed path
    # a second method: dense samples both ways, no Newton; its own error is below 1e-7 mm (its docstring)
    assert brute_two_sided(curve, printed) <= tol + 1e-7


def test_a_section_no_march_closes_is_fitted_with_lines(monkeypatch):
    curve = ellipse()
    tol, q = 0.002, Quantizer(3)

    def no_spline(*args, **kwargs):
        raise FitError("cannot fit the curve: the march found no printed arc spline from any of its 64 starts")

    monkeypatch.setattr(arcfit, "fit_arc_spline", no_spline)
    fit = fit_contour(curve, tol, mode="arcs", quantizer=q, max_sweep_deg=120)
    assert len(fit.lines_sections) == 1 and "no printed arc spline" in fit.lines_sections[0][2]
    assert fit.line_blocks > 0 and fit.arc_blocks == 0
    assert sum(fit.piece_blocks) == len(fit.elements)  # every line counted on its piece
    path = q.printed_elements(fit.elements)
    assert all(isinstance(e, Line) for e in path)
    assert np.allclose(path[0].start, path[-1].end, atol=0)  # closed on the printed grid
    assert fit.max_deviation_mm <= tol  # measured two-sided on the printed lines
    assert brute_two_sided(curve, path) <= tol + 1e-7  # its error below 1e-7 mm (its docstring)


def test_an_arcs_fit_that_closes_is_unchanged_by_the_fallback():
    # the fallback is reached only where no march closes: an ordinary contour has its arc spline as before
    fit = fit_contour(ellipse(), 0.01, quantizer=Quantizer(4), max_sweep_deg=120)
    assert fit.lines_sections == () and fit.arc_blocks > 0 and fit.max_deviation_mm <= 0.01
