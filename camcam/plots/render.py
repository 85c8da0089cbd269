"""Turning a matplotlib figure into PNG bytes, the same bytes for the same figure."""

from __future__ import annotations

import io

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

__all__ = ["plt", "png_bytes"]


def png_bytes(fig, dpi: int = 96) -> bytes:
    """Render and close ``fig``; no timestamp or software tag, so output is reproducible."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, metadata={"Software": None})
    plt.close(fig)
    return buf.getvalue()
