"""The run's plots use fixed margins (no tight_layout, which draws each figure twice): nothing may be cut
off at the figure's edge and no axes' labels may run into the next axes, also with wide tick labels."""

import numpy as np
import pytest
from matplotlib.transforms import Bbox

from camcam.geometry.build import build_cam
from camcam.motion.catalog import make_law
from camcam.motion.program import MotionProgram, Segment
from camcam.spec import load_spec
from tests.hostile.harness import SAMPLES

#: Slack at the canvas edge and between axes (pixels at 96 dpi): antialiasing of a glyph's edge.
SLACK_PX = 1.0


def captured(module, draw):
    """The figure ``draw()`` makes through ``module.png_bytes``, drawn but not closed."""
    figs = []

    def keep(fig, dpi=96):
        fig.set_dpi(dpi)
        fig.canvas.draw()
        figs.append(fig)
        return b""

    original = module.png_bytes
    module.png_bytes = keep
    try:
        draw()
    finally:
        module.png_bytes = original
    return figs[0]


def assert_laid_out(fig):
    r = fig.canvas.get_renderer()
    whole = fig.get_tightbbox(r).transformed(fig.dpi_scale_trans)  # pixels
    w, h = fig.bbox.width, fig.bbox.height
    assert whole.x0 >= -SLACK_PX and whole.y0 >= -SLACK_PX, whole
    assert whole.x1 <= w + SLACK_PX and whole.y1 <= h + SLACK_PX, (whole, w, h)
    boxes = [ax.get_tightbbox(r) for ax in fig.axes]
    for i in range(len(boxes)):
        for j in range(i + 1, len(boxes)):
            a, b = boxes[i], boxes[j]
            inter = Bbox.intersection(a, b)
            overlap = 0.0 if inter is None else min(inter.width, inter.height)
            assert overlap <= SLACK_PX, (i, j, a, b)


def wide_program():
    """Values whose tick labels are as wide as the formatter prints (offsets, minus signs, 7 characters)."""
    law = make_law("modified-trapezoid")
    return MotionProgram((Segment(law, 0, 100, 1234.5), Segment(law, 100, 360, -1234.5, base=1234.5)), rpm=3000)


@pytest.mark.parametrize("program", ["sample", "wide"])
def test_svaj_plot_fits(program):
    from camcam.plots import svaj

    prog = wide_program() if program == "wide" else load_spec(SAMPLES / "disc-translating-roller.toml").motion.program("mm")
    assert_laid_out(captured(svaj, lambda: svaj.svaj_png(prog, "a title of ordinary length for a cam")))


@pytest.mark.parametrize("sample", ["disc-translating-roller", "disc-oscillating-flat", "cylindrical-oscillating"])
def test_cam_plot_fits(sample):
    from camcam.plots import profile

    spec = load_spec(SAMPLES / f"{sample}.toml")
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    assert_laid_out(captured(profile, lambda: profile.cam_png(built, f"{sample}: a cam")))


@pytest.mark.parametrize("tol", [0.1, 0.0005])
def test_deviation_plot_fits(tol):
    from camcam.plots import report_plots

    ang = np.linspace(0.0, 360.0, 721)
    fig = captured(report_plots, lambda: report_plots.deviation_png(ang, -tol * np.sin(np.radians(ang)), tol, "t"))
    assert_laid_out(fig)


@pytest.mark.parametrize("big", [1.0, -123456.0])
def test_fitted_motion_plot_fits(big):
    from camcam.plots import report_plots

    ang = np.linspace(0.0, 360.0, 721)
    design = np.vstack([big * np.sin(np.radians(ang) * k) for k in range(1, 5)])
    fig = captured(report_plots, lambda: report_plots.fitted_motion_png(ang, design, 1.01 * design,
                                                                        ["mm", "mm/s", "m/s²", "m/s³"], "title"))
    assert_laid_out(fig)
