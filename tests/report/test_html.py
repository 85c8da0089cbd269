"""The HTML report renders in a real browser (headless Chromium)."""

import shutil
import subprocess

import pytest

from camcam.plots.render import png_bytes, subplots
from camcam.report.html import DataTable, Figure, KeyValues, Paragraph, Section, render_html

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")


def sample_page() -> str:
    fig, ax = subplots(figsize=(4, 2))
    ax.plot([0, 1, 2], [0, 1, 0])
    return render_html(
        "demo cam",
        "report",
        [
            Section("Job", (KeyValues((("tolerance", "0.010 mm"), ("post", "linuxcnc"))),)),
            Section("Plot", (Figure(png_bytes(fig), "a plot"),)),
            Section("Table", (DataTable(("angle [deg]", "r [mm]"), (("0", "40.000"), ("1", "40.001"))), Paragraph("<b>&</b>"))),
        ],
    )


def test_escaping_and_self_contained():
    page = sample_page()
    assert "&lt;b&gt;&amp;&lt;/b&gt;" in page  # user text never becomes markup
    assert "data:image/png;base64," in page
    assert "http" not in page  # nothing fetched from the network


def test_deterministic():
    assert sample_page() == sample_page()


def screenshot(html_path, png_path, tmp_path):
    """Headless Chromium screenshot of a local file; flags per the machine notes (no network)."""
    cmd = [
        CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync",
        f"--user-data-dir={tmp_path / 'chrome-profile'}", "--window-size=1200,1600",
        f"--screenshot={png_path}", f"file://{html_path}",
    ]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=60)


@pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (Debian package chromium); .ci/run installs it")
def test_renders_in_chromium(tmp_path):
    import numpy as np
    from PIL import Image

    page = tmp_path / "r.html"
    page.write_text(sample_page())
    shot = tmp_path / "shot.png"
    r = screenshot(page, shot, tmp_path)
    assert shot.exists(), r.stderr[-2000:]
    img = np.asarray(Image.open(shot).convert("L"), dtype=float)
    assert img.shape[1] == 1200
    # a rendered page has text and a plot: many dark pixels, not a blank white sheet
    assert (img < 128).mean() > 0.002
