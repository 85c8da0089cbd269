import io

import ezdxf
import numpy as np
import pytest

from camcam.export.dxf import Circle, Polyline, Text, contour_dxf
from camcam.toolpath.arcfit import fit_contour
from tests.nc_curves import ellipse


def test_dxf_reads_back_and_audits_clean(tmp_path):
    E = ellipse()
    fit = fit_contour(E, 0.01)
    extras = {"BASE_CIRCLE": [Circle((0.0, 0.0), 15.0)], "PITCH": [Polyline(((0.0, 0.0), (5.0, 5.0), (9.0, 1.0)), True)],
              "MARKS": [Text("0°", (32.0, 0.0))]}
    d = contour_dxf(fit.elements, E, extras, title="ellipse 30×20, tol 0.01 mm")
    f = tmp_path / "e.dxf"
    f.write_bytes(d.data)
    doc = ezdxf.readfile(f)  # strict reader: the one that catches broken files
    auditor = doc.audit()
    assert not auditor.has_errors
    assert doc.header["$INSUNITS"] == 4  # millimetres
    msp = doc.modelspace()
    arcs = msp.query("ARC[layer=='CONTOUR']")
    assert len(arcs) + len(msp.query("LINE[layer=='CONTOUR']")) == len(fit.elements)
    assert len(msp.query("SPLINE[layer=='EXACT']")) == 4  # one per analytic piece
    assert len(msp.query("CIRCLE[layer=='BASE_CIRCLE']")) == 1
    assert d.spline_deviation_mm <= 1e-4
    # each DXF arc reproduces the machined arc: same centre and start radius; its end is within the
    # printed arc's start/end radius mismatch (≤ 1.5e-4 mm at 4 decimals) of the printed end
    for a, e in zip(arcs, fit.elements):
        assert np.allclose(np.asarray(a.dxf.center)[:2], e.centre, atol=1e-12)
        ends = [np.asarray(a.start_point)[:2], np.asarray(a.end_point)[:2]]
        for p in (e.start, e.end):
            assert min(np.hypot(*(q - p)) for q in ends) < 1.5e-4
    # the splines run through the exact curve: sample one and measure
    spl = msp.query("SPLINE")[0].construction_tool()
    pts = np.array(list(spl.points(np.linspace(0, spl.max_t, 50))))[:, :2]
    r = (pts[:, 0] / 30.0) ** 2 + (pts[:, 1] / 20.0) ** 2
    assert np.all(np.abs(r - 1) < 1e-5)  # on the ellipse within 1e-4 mm (radial-ish error / 20 mm)


def test_exact_splines_follow_the_curve_in_its_own_parameter():
    """Each EXACT spline read back from the file, evaluated by scipy's B-spline (not ezdxf's, which made it), at
    the exact curve's parameter t (its knots run over the piece's [lo, hi]) lies within the stated deviation of
    the curve there, at 20 points per knot interval."""
    from scipy.interpolate import BSpline

    E = ellipse()
    d = contour_dxf(fit_contour(E, 0.01).elements, E)
    doc = ezdxf.read(io.StringIO(d.data.decode()))
    splines = doc.modelspace().query("SPLINE[layer=='EXACT']")
    br = list(E.breaks)
    assert len(splines) == len(br) - 1
    for s, lo, hi in zip(splines, br, br[1:]):
        knots = np.array(s.knots)
        assert knots[0] == pytest.approx(lo, abs=1e-12) and knots[-1] == pytest.approx(hi, abs=1e-12)  # rounding
        spl = BSpline(knots, np.array(s.control_points)[:, :2], s.dxf.degree)
        t = np.linspace(lo, hi, 20 * len(knots))
        gap = np.hypot(*(spl(t) - E.evaluate(t, 0)).T)
        # the stated bound, checked at 8 points a span when drawn, plus 1e-6 mm of the sampling in between here
        assert gap.max() <= d.spline_deviation_mm + 1e-6
