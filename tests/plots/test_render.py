"""png_bytes writes the pixels Figure.savefig writes, as a smaller RGB PNG with no text chunks."""

import io

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from matplotlib.ticker import AutoLocator
from PIL import Image

from camcam.plots.render import InViewLocator, png_bytes, subplots, ticks_in_view


def sample_figure():
    fig, (ax0, ax1) = subplots(2, 1, figsize=(5, 4))
    x = np.linspace(0.0, 360.0, 721)
    ax0.axhspan(-0.5, 0.5, color="C2", alpha=0.12, label="band")
    ax0.plot(x, np.sin(np.radians(x)), lw=1.2, label="sin")
    ax0.legend(loc="upper right", fontsize=8)
    ax0.grid(True, alpha=0.3)
    ax1.plot(x[::20], np.cos(np.radians(x[::20])), ".", ms=3, color="C3")
    ax1.set_title("cos at 20° steps", fontsize=9)
    fig.suptitle("a title")
    return fig


def decoded(data: bytes) -> Image.Image:
    image = Image.open(io.BytesIO(data))
    image.load()
    return image


def test_same_pixels_as_savefig():
    fig = sample_figure()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=96, metadata={"Software": None})
    reference = decoded(buf.getvalue())
    ours = decoded(png_bytes(sample_figure()))
    assert (ours.mode, reference.mode) == ("RGB", "RGBA")
    ref = np.asarray(reference)
    assert (ref[..., 3] == 255).all()  # opaque: dropping alpha loses nothing
    np.testing.assert_array_equal(np.asarray(ours), ref[..., :3])


def test_reproducible_and_without_text_chunks():
    first, second = png_bytes(sample_figure()), png_bytes(sample_figure())
    assert first == second
    image = decoded(first)
    assert image.text == {}
    # pHYs holds whole pixels per metre (3780 for 96 dpi): read back as 96.012 dpi
    assert np.allclose(image.info["dpi"], (96, 96), atol=0.05)


def drawn_ticks(locator_class, lo: float, hi: float, height_in: float):
    """(locations, labels, offset text) of the y ticks matplotlib draws for the view [lo, hi]."""
    fig, ax = subplots(figsize=(4, height_in))
    ax.set_ylim(lo, hi)
    ax.yaxis.set_major_locator(locator_class())
    fig.canvas.draw()
    ticks = ax.yaxis._update_ticks()  # the ticks in view, as Axis.draw draws them
    return ([float(t.get_loc()) for t in ticks], [t.label1.get_text() for t in ticks],
            ax.yaxis.offsetText.get_text())


@settings(max_examples=60, deadline=None)
@given(lo=st.floats(-1e6, 1e6), width_exp=st.floats(-6.0, 6.0), height_in=st.sampled_from([1.2, 2.0, 4.0]))
def test_in_view_locator_draws_the_same_ticks_and_labels(lo, width_exp, height_in):
    hi = lo + 10.0 ** width_exp
    # views narrower than a millionth of their distance from 0 print digits in the last bits of a float:
    # there the formatter's decimals can follow ticks beyond the view (seen: 524288.04296875 + 1e-6)
    assume(hi - lo >= 1e-6 * max(1.0, abs(lo)))
    theirs = drawn_ticks(AutoLocator, lo, hi, height_in)
    ours = drawn_ticks(InViewLocator, lo, hi, height_in)
    assert ours == theirs


def test_in_view_locator_leaves_out_the_ticks_beyond_the_view():
    fig, ax = subplots(figsize=(4, 2))
    ax.plot([0, 1], [-1.0, 21.0])
    plain = list(ax.yaxis.get_major_locator()())
    ticks_in_view(fig)
    fig.canvas.draw()
    assert type(ax.yaxis.get_major_locator()) is InViewLocator
    assert plain[0] < -1.0 and plain[-1] > 21.0  # matplotlib's locator reaches past the view at both ends
    assert list(ax.yaxis.get_major_locator()()) == [x for x in plain if -2.1 <= x <= 22.1]
    assert len(ax.yaxis.majorTicks) == len(plain) - 2
