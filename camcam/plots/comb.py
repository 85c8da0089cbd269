"""Curvature combs (as in UG, seed 004 figs. 3–4): the lift curve before/after fairing, and a profile."""

from __future__ import annotations

import numpy as np

from camcam.geometry.curve import PlanarCurve, curvature, left_normal
from camcam.lifttable.curvature import lift_curvature
from camcam.plots.render import png_bytes, subplots

__all__ = ["lift_comb_png", "profile_comb_png"]


def _comb(ax, x, y, kappa, scale, color):
    # hairs on the outside of the bend, as UG draws them; the envelope joins the tips
    tips = y - scale * kappa
    ax.vlines(x, y, tips, color=color, lw=0.5, alpha=0.7)
    ax.plot(x, tips, color=color, lw=0.8)
    ax.plot(x, y, color="k", lw=1.2)


def lift_comb_png(before, after, x0: float, x1: float, unit: str = "mm", title: str = "", step_deg: float = 0.5) -> bytes:
    """Combs of interpolants ``before`` and ``after`` (``f(x, nu)``) over [x0, x1], and κ(α) of both."""
    x = np.arange(x0, x1 + 1e-9, step_deg)
    yb, ya = before(x), after(x)
    kb, ka = lift_curvature(before, x), lift_curvature(after, x)
    span = max(np.ptp(yb), 1e-9)
    sb = 0.35 * span / max(np.max(np.abs(kb)), 1e-300)
    sa = 0.35 * span / max(np.max(np.abs(ka)), 1e-300)
    fig, axes = subplots(3, 1, figsize=(9, 9), sharex=True)
    _comb(axes[0], x, yb, kb, sb, "C3")
    axes[0].set_title(f"before fairing: max |κ| {np.max(np.abs(kb)):.3g}")
    _comb(axes[1], x, ya, ka, sa, "C2")
    axes[1].set_title(f"after fairing: max |κ| {np.max(np.abs(ka)):.3g} (comb magnified ×{sa / sb:.3g} against the one above)")
    for ax in axes[:2]:
        ax.set_ylabel(f"lift [{unit}]")
        ax.grid(True, alpha=0.3)
    axes[2].plot(x, kb, color="C3", lw=0.8, label="before")
    axes[2].plot(x, ka, color="C2", lw=1.2, label="after")
    axes[2].set_ylabel(f"curvature of h(α)\n[1/{unit}, 1° = 1 {unit}]")
    axes[2].grid(True, alpha=0.3)
    axes[2].legend(loc="upper right")
    axes[2].set_xlabel("cam angle [deg]")
    fig.suptitle(title or "Lift-curve curvature comb")
    fig.tight_layout()
    return png_bytes(fig)


def profile_comb_png(curve: PlanarCurve, title: str = "", per_piece: int = 32) -> bytes:
    """Comb of a planar profile: hairs along the outward normal, length ∝ κ, equal axes."""
    b = np.asarray(curve.breaks, dtype=float)
    t = np.unique(np.concatenate([np.linspace(lo, hi, per_piece) for lo, hi in zip(b[:-1], b[1:])]))
    p = curve.evaluate(t, 0)
    k = curvature(curve, t)
    n = left_normal(curve, t)
    size = max(np.ptp(p[:, 0]), np.ptp(p[:, 1]), 1e-9)
    scale = 0.15 * size / max(np.max(np.abs(k)), 1e-300)
    tips = p - scale * k[:, None] * n
    fig, ax = subplots(figsize=(7, 7))
    ax.plot(*p.T, color="k", lw=1.2)
    for a, c in zip(p, tips):
        ax.plot([a[0], c[0]], [a[1], c[1]], color="C0", lw=0.4)
    ax.plot(*tips.T, color="C0", lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.grid(True, alpha=0.3)
    ax.set_title(title or "Profile curvature comb")
    return png_bytes(fig)
