"""Making matplotlib figures and turning them into PNG bytes, the same bytes for the same figure.

Figures are :class:`matplotlib.figure.Figure` objects made directly, not through pyplot: nothing
here needs pyplot's figure registry or an interactive backend, each figure gets an Agg canvas
of its own, and pyplot's import is the dearer one (0.33 against
0.29 CPU s for matplotlib.figure with the Agg backend, best of 5 on the 2-core benchmark
machine, numpy and shapely loaded first).

:func:`png_bytes` draws the canvas and writes its pixels with Pillow itself: RGB (the figures are
opaque; matplotlib writes RGBA) at zlib level 3 (Pillow's default is 6): 0.012 instead of 0.022 CPU s
for the SVAJ plot's 768 × 816 pixels, and 76 instead of 78 kB (best of 5); the pixels are those
``Figure.savefig`` makes (``tests/plots/test_render.py``).
"""

from __future__ import annotations

import io

import numpy as np
from PIL import Image

from camcam.plots.mpl_import import load_matplotlib

load_matplotlib()  # before matplotlib's modules below: the cheap import (camcam.plots.mpl_import)

from matplotlib.backends.backend_agg import FigureCanvasAgg  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.patches import Circle, Rectangle  # noqa: E402
from matplotlib.ticker import AutoLocator  # noqa: E402

__all__ = ["subplots", "figure", "png_bytes", "ticks_in_view", "InViewLocator", "Circle", "Line2D", "Rectangle",
           "PNG_COMPRESS_LEVEL", "TITLE_Y"]


def figure(figsize: tuple[float, float]) -> Figure:
    """A new figure of ``figsize`` inches (width, height) on an Agg canvas (as pyplot's Agg backend gives)."""
    fig = Figure(figsize=figsize)
    FigureCanvasAgg(fig)
    return fig


def subplots(nrows: int = 1, ncols: int = 1, *, figsize: tuple[float, float], **kwargs):
    """(figure, axes): a new figure of ``figsize`` inches and its grid of axes, as ``pyplot.subplots``.

    Examples
    --------
    >>> fig, axes = subplots(2, 1, figsize=(4, 3), sharex=True)
    >>> len(axes), png_bytes(fig)[:4]
    (2, b'\\x89PNG')
    """
    fig = figure(figsize)
    return fig, fig.subplots(nrows, ncols, **kwargs)


class InViewLocator(AutoLocator):
    """matplotlib's default tick locator, less the ticks outside the view.

    :class:`~matplotlib.ticker.AutoLocator` gives a tick beyond each end of the view, and matplotlib makes a
    tick object of three lines and two texts for each, formats its label, and does not draw it: two an axes,
    26 in a disc cam's four report plots.  The ticks drawn and their labels are the same
    (``tests/plots/test_render.py``).
    """

    def __call__(self):
        locs = super().__call__()
        lo, hi = sorted(self.axis.get_view_interval())
        slack = 1e-10 * (hi - lo)  # matplotlib's own test of a tick in view (transforms._interval_contains_close)
        return locs[(locs >= lo - slack) & (locs <= hi + slack)]


def ticks_in_view(fig: Figure) -> None:
    """Give every axis of ``fig`` that has matplotlib's default tick locator an :class:`InViewLocator`."""
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            if type(axis.get_major_locator()) is AutoLocator:
                axis.set_major_locator(InViewLocator())


#: The height of axes titles, given explicitly (``ax.set_title(..., y=TITLE_Y)``, where matplotlib puts them
#: anyway): matplotlib then skips lifting a title over tick labels or an offset text at its axes' top, a pass
#: that lays out every tick label of the axes once more at each draw (camcam's plots have none there).
TITLE_Y = 1.0

#: zlib level of the PNGs (module notes).
PNG_COMPRESS_LEVEL = 3


def png_bytes(fig: Figure, dpi: int = 96) -> bytes:
    """Render ``fig`` at ``dpi`` (which it keeps; its default tick locators become :class:`InViewLocator`) as an RGB
    PNG; no timestamp or software tag, so output is reproducible."""
    ticks_in_view(fig)
    fig.set_dpi(dpi)
    fig.canvas.draw()
    rgb = np.asarray(fig.canvas.buffer_rgba())[..., :3]
    buf = io.BytesIO()
    Image.fromarray(np.ascontiguousarray(rgb)).save(buf, format="png", compress_level=PNG_COMPRESS_LEVEL, dpi=(dpi, dpi))
    return buf.getvalue()
