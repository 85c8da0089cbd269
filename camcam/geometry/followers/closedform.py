"""Closed forms in s, s′, s″ for a block of designs at once (rows: designs, columns: cam angles).

The cam-frame pitch curve of a roller centre P(θ) (fixed frame) is R(−σθ)·P,
so with T = P′ − σJP (J: +90° turn) its convex-positive curvature is

    κc = (|T|² − σ T×T′)/|T|³,  T′ = P″ − σJP′,

and the pressure angle is atan2(T·u, σ T×u) with u the roller's direction of
motion.  For a translating roller (P = (e, y₀ + s), u = +Y) these are the
textbook forms

    φ = atan2(s′ − σe, y₀ + s),
    κc = (|T|² + s′(s′ − σe) − (y₀ + s)s″)/|T|³,  |T|² = (y₀ + s)² + (s′ − σe)²;

for a translating flat face the profile's radius is ρ = R_b + s + s″ and the
contact sits σs′ from the stem.  The profile of a roller follower is the pitch
curve offset inwards by r_r: convex radius 1/κc − r_r, concave radius
1/|κc| + r_r, undercut where r_r·κc ≥ 1.  Each figure is also given an
estimated grid bound, max|Δ²f|/8 (the error of a sampled extreme of f is at
most h²·max|f″|/8, and Δ²f ≈ h²f″), taken around the sampled extreme and doubled
(Δ²f averages f″ over two steps, so the estimate alone can fall a little short).

Each sized kind's :meth:`size_figures` is one of these, validated point by point against
:mod:`camcam.geometry.disc` in ``tests/sizing/test_kernels.py``; ``ps`` is the program's samples
(:class:`camcam.sizing.samples.ProgramSamples`: ``s``, ``s1``, ``s2`` per radian, ``inner``, ``lift_min``,
``lift_max``).
"""

from __future__ import annotations

import numpy as np

__all__ = ["grid_bound", "local_bound", "roller_figures", "blank", "blank_invalid"]


def grid_bound(f: np.ndarray, inner: np.ndarray) -> np.ndarray:
    """max over the samples with both neighbours in their segment of |Δ²f|/8, per row."""
    d2 = np.abs(f[:, 2:] - 2.0 * f[:, 1:-1] + f[:, :-2])
    d2 = np.where(inner[1:-1], d2, 0.0)
    return d2.max(axis=1) / 8.0


def local_bound(f, at: np.ndarray, inner: np.ndarray) -> np.ndarray:
    """|Δ²f|/8 around each row's sampled extreme (at the sample and its two neighbours, within a segment).

    ``f(rows, cols)`` returns the figure at those samples, so a costly figure
    (the pressure angle's arctan) is evaluated at five samples a row, not all.
    """
    n = inner.size
    rows = np.arange(at.size)
    worst = np.zeros(at.size)
    for shift in (-1, 0, 1):
        j = np.clip(at + shift, 1, n - 2)
        d2 = np.abs(f(rows, j + 1) - 2.0 * f(rows, j) + f(rows, j - 1))
        worst = np.maximum(worst, np.where(inner[j], d2, 0.0))
    return worst / 4.0  # twice the estimate max|Δ²f|/8: Δ²f averages f″ over two steps


def roller_figures(kc: np.ndarray, ratio: np.ndarray, rr: np.ndarray, ps, outer: np.ndarray, valid: np.ndarray) -> dict:
    """Figures from κc and tan φ (rows: designs); |φ| = arctan|tan φ| is monotone, so its maximum is taken on tan φ."""
    hi, lo = kc.argmax(axis=1), kc.argmin(axis=1)
    rows = np.arange(kc.shape[0])
    kmax, kmin = kc[rows, hi], kc[rows, lo]
    absr = np.abs(ratio)
    at = absr.argmax(axis=1)
    pa = np.arctan(absr[rows, at])
    dk = local_bound(lambda r, c: kc[r, c], hi, ps.inner)
    dphi = local_bound(lambda r, c: np.arctan(absr[r, c]), at, ps.inner)
    with np.errstate(divide="ignore", invalid="ignore"):
        rho = np.where(kmax > 0, 1.0 / kmax - rr, np.inf)
        rho_bound = np.where(kmax > 0, 1.0 / kmax - 1.0 / (kmax + dk), 0.0)
        concave = np.where(kmin < 0, 1.0 / np.abs(kmin) + rr, np.inf)
    out = {
        "valid": valid,
        "max_pressure_angle_deg": np.degrees(pa),
        "min_curvature_radius_mm": rho,
        "min_concave_radius_mm": concave,
        "undercut": valid & (rr * kmax >= 1.0),
        "outer_radius_mm": outer,
        "pressure_angle_bound_deg": np.degrees(dphi),
        "curvature_radius_bound_mm": rho_bound,
    }
    return blank_invalid(out, valid)


def blank(v: np.ndarray, valid: np.ndarray) -> np.ndarray:
    """``v`` with NaN in the rows of designs that cannot be built."""
    return np.where(valid, v, np.nan)


def blank_invalid(out: dict, valid: np.ndarray) -> dict:
    for k, v in out.items():
        if v.dtype.kind == "f":
            out[k] = np.where(valid, v, np.nan)
    return out
