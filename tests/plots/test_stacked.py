"""Stacked axes drawn by camcam.plots.stacked are the same pixels as matplotlib's shared x axis draws."""

import numpy as np
import pytest

from camcam.plots.render import subplots
from camcam.plots.stacked import angle_axis, vertical_lines


def pixels(fig) -> np.ndarray:
    fig.set_dpi(96)
    fig.canvas.draw()
    return np.asarray(fig.canvas.buffer_rgba()).copy()


def stacked(cheap: bool, n: int, step_deg: float, grid: bool) -> np.ndarray:
    """A stack of ``n`` axes over one revolution: through :func:`angle_axis` or matplotlib's ``sharex``."""
    fig, axes = subplots(n, 1, figsize=(6, 1.6 * n), sharex=not cheap)
    ang = np.linspace(0.0, 360.0, 721)
    for k, ax in enumerate(axes):
        ax.plot(ang, (k + 1) * np.sin(np.radians(ang) * (k + 1)), lw=1.2, label="curve")
        ax.axvline(120.0, color="0.5", ls="--", lw=0.8)
        ax.set_ylabel(f"value {k}")
        if grid:
            ax.grid(True, alpha=0.3)
    axes[0].legend(loc="upper right")
    if cheap:
        angle_axis(axes, step_deg=step_deg, grid_alpha=0.3 if grid else None)
    else:
        axes[-1].set_xlim(0, 360)
        axes[-1].set_xticks(np.arange(0, 361, step_deg))
        axes[-1].set_xlabel("cam angle [deg]")
    fig.subplots_adjust(left=0.15, right=0.95, bottom=0.1, top=0.95, hspace=0.3)
    return pixels(fig)


@pytest.mark.parametrize("n, step_deg, grid", [(4, 30.0, True), (2, 30.0, False), (2, 60.0, True)])
def test_same_pixels_as_a_shared_axis(n, step_deg, grid):
    np.testing.assert_array_equal(stacked(True, n, step_deg, grid), stacked(False, n, step_deg, grid))


def test_the_comparison_sees_missing_grid_lines():
    # the check above must be able to fail: the same stack without the upper axes' grid differs
    with_grid, without = stacked(True, 2, 30.0, True), stacked(True, 2, 30.0, False)
    assert np.count_nonzero(np.any(with_grid != without, axis=2)) > 100


def test_upper_axes_make_no_ticks_and_keep_the_legend_clean():
    fig, axes = subplots(3, 1, figsize=(6, 5))
    axes[0].plot([0, 360], [0, 1], label="only")
    angle_axis(axes, grid_alpha=0.3)
    pixels(fig)
    assert [len(ax.xaxis.get_major_ticks()) for ax in axes] == [0, 0, 13]
    assert [t.get_text() for t in axes[0].legend().get_texts()] == ["only"]
    assert all(ax.get_xlim() == (0.0, 360.0) for ax in axes)


def test_vertical_lines_span_the_axes_and_leave_the_data_limits_alone():
    fig, (a, b) = subplots(2, 1, figsize=(4, 3))
    for ax in (a, b):
        ax.plot([0, 360], [100.0, 200.0])
    a.add_collection(vertical_lines(a, [120.0, 300.0], color="0.5", ls="--", lw=0.8), autolim=False)
    for ax in (a, b):
        ax.axvline(120.0, color="0.5", ls="--", lw=0.8)  # the same as the collection's first line
    pixels(fig)
    assert a.get_ylim() == b.get_ylim()  # no data limit stretched to y = 0..1
    lines = a.collections[0]
    assert [seg[:, 0].tolist() for seg in lines.get_segments()] == [[120.0, 120.0], [300.0, 300.0]]
