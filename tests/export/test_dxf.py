import io

import ezdxf
import numpy as np
import pytest

from camcam.export.dxf import Circle, Polyline, Text, contour_dxf
from camcam.toolpath.arcfit import fit_contour
from camcam.toolpath.elements import circular
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
    # each DXF arc is the machined arc: its centre where the printed ends are on one circle; a printed spiral's
    # (end radius ≠ start radius, by ≤ 1.5e-4 mm at 4 decimals) the arc through its ends and its midpoint
    for a, e in zip(arcs, fit.elements):
        assert np.allclose(np.asarray(a.dxf.center)[:2], circular(e).centre, atol=1e-12)  # the file's float text
        assert abs(a.dxf.radius - e.radius) <= abs(e.end_radius - e.radius) + 1e-12
        ends = [np.asarray(a.start_point)[:2], np.asarray(a.end_point)[:2]]
        for p in (e.start, e.end):
            assert min(np.hypot(*(q - p)) for q in ends) < 1e-9  # both ends exactly (the DXF's text: 1e-9 mm)
    # the splines run through the exact curve: sample one and measure
    spl = msp.query("SPLINE")[0].construction_tool()
    pts = np.array(list(spl.points(np.linspace(0, spl.max_t, 50))))[:, :2]
    r = (pts[:, 0] / 30.0) ** 2 + (pts[:, 1] / 20.0) ** 2
    assert np.all(np.abs(r - 1) < 1e-5)  # on the ellipse within 1e-4 mm (radial-ish error / 20 mm)


def test_exact_splines_follow_the_curve_in_its_own_parameter():
    """Each EXACT spline read back from the file, evaluated by ezdxf's B-spline (not camcam's Bézier form, which made it), at
    the exact curve's parameter t (its knots run over the piece's [lo, hi]) lies within the stated deviation of
    the curve there, at 20 points per knot interval."""
    from ezdxf.math import BSpline

    E = ellipse()
    d = contour_dxf(fit_contour(E, 0.01).elements, E)
    doc = ezdxf.read(io.StringIO(d.data.decode()))
    splines = doc.modelspace().query("SPLINE[layer=='EXACT']")
    br = list(E.breaks)
    assert len(splines) == len(br) - 1
    for s, lo, hi in zip(splines, br, br[1:]):
        knots = np.array(s.knots)
        assert knots[0] == pytest.approx(lo, abs=1e-12) and knots[-1] == pytest.approx(hi, abs=1e-12)  # rounding
        t = np.linspace(lo, hi, 20 * len(knots))
        # ezdxf's B-spline runs from parameter 0: the knots and t shifted by lo alike, the same curve
        bs = BSpline(s.control_points, order=s.dxf.degree + 1, knots=knots - lo)
        got = np.array(list(bs.points(t - lo)))[:, :2]
        gap = np.hypot(*(got - E.evaluate(t, 0)).T)
        # the stated bound, checked at 8 points a span when drawn, plus 1e-6 mm of the sampling in between here
        assert gap.max() <= d.spline_deviation_mm + 1e-6


def test_a_curve_that_needs_twenty_thousand_points_is_drawn_in_bounded_memory():
    """Real failing data, design-space case 43:57 (tests/cli/test_small_wrongs.py): a profile piece that needs over
    20 000 spline points.  ezdxf's global interpolation, tried for issue 49, built the dense n × n matrix as Python
    lists (23 GB, the run killed); the Hermite spline camcam draws needs O(n).  Run in a child limited to 2 GB of
    address space, where the dense one fails at once with MemoryError."""
    import subprocess
    import sys

    code = (
        "import resource, numpy as np\n"
        "resource.setrlimit(resource.RLIMIT_AS, (2 << 30, 2 << 30))\n"
        "from camcam.export.dxf import spline_of_curve\n"
        "from camcam.geometry.curve import FunctionCurve\n"
        "def step(t, k):  # a 1 mm jump at t = 0: no cubic follows it within 1e-4 mm, the points grow past 20 000\n"
        "    t = np.asarray(t, float)\n"
        "    return np.stack([[t, 0.5 * np.sign(t)], [np.ones_like(t), 0 * t]][k], -1)\n"
        "C = FunctionCurve(step, -1.0, 1.0)\n"
        "spl, dev = spline_of_curve(C, -1.0, 1.0)\n"
        "print(len(spl.control_points), dev)\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-800:]
    points, dev = r.stdout.split()
    # it gave up past 20 000 points (the jump is never within 1e-4 mm) rather than running out of memory
    assert int(points) > 20000 and float(dev) > 1e-4
