"""png_bytes writes the pixels Figure.savefig writes, as a smaller RGB PNG with no text chunks."""

import io

import numpy as np
from PIL import Image

from camcam.plots.render import png_bytes, subplots


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
