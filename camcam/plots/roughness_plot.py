"""Seed 004's roughness picture: second difference quotients before and after fairing."""

from __future__ import annotations

from camcam.lifttable.roughness import Roughness
from camcam.plots.render import png_bytes, subplots

__all__ = ["roughness_png"]


def roughness_png(before: Roughness, after: Roughness, bad_deg=(), unit: str = "mm", title: str = "") -> bytes:
    """First and second difference quotients of the raw and the faired table; bad points marked."""
    fig, axes = subplots(2, 1, figsize=(9, 6.5), sharex=True)
    for ax, attr, lab in ((axes[0], "first", f"{unit}/deg"), (axes[1], "second", f"{unit}/deg²")):
        ax.plot(before.angles_deg, getattr(before, attr), color="C3", lw=0.7, label="table as read")
        ax.plot(after.angles_deg, getattr(after, attr), color="C2", lw=1.3, label="faired")
        ax.set_ylabel(f"{attr} difference\nquotient [{lab}]")
        ax.grid(True, alpha=0.3)
        for a in bad_deg:
            ax.axvline(a, color="C1", ls=":", lw=1.0)
    axes[1].legend(loc="upper right")
    axes[1].set_xlabel("cam angle [deg]" + ("   (dotted: bad points removed)" if len(bad_deg) else ""))
    fig.suptitle(title or f"Roughness: max |second difference| {before.max_abs_second:.3g} → {after.max_abs_second:.3g} {unit}/deg²")
    fig.tight_layout()
    return png_bytes(fig)
