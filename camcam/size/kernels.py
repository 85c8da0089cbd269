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

These are validated point by point against :mod:`camcam.geometry.disc` in
``tests/size/test_kernels.py``.
"""

from __future__ import annotations

import math

import numpy as np

from camcam.size.samples import ProgramSamples

__all__ = ["FIGURES", "block_figures"]

#: The figure columns every kernel returns, in table order.
FIGURES = ("valid", "max_pressure_angle_deg", "min_curvature_radius_mm", "min_concave_radius_mm", "undercut",
           "outer_radius_mm", "pressure_angle_bound_deg", "curvature_radius_bound_mm")


def _bound(f: np.ndarray, inner: np.ndarray) -> np.ndarray:
    """max over the samples with both neighbours in their segment of |Δ²f|/8, per row."""
    d2 = np.abs(f[:, 2:] - 2.0 * f[:, 1:-1] + f[:, :-2])
    d2 = np.where(inner[1:-1], d2, 0.0)
    return d2.max(axis=1) / 8.0


def _local_bound(f, at: np.ndarray, inner: np.ndarray) -> np.ndarray:
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


def _roller_figures(kc: np.ndarray, ratio: np.ndarray, rr: np.ndarray, ps: ProgramSamples, outer: np.ndarray, valid: np.ndarray) -> dict:
    """Figures from κc and tan φ (rows: designs); |φ| = arctan|tan φ| is monotone, so its maximum is taken on tan φ."""
    hi, lo = kc.argmax(axis=1), kc.argmin(axis=1)
    rows = np.arange(kc.shape[0])
    kmax, kmin = kc[rows, hi], kc[rows, lo]
    absr = np.abs(ratio)
    at = absr.argmax(axis=1)
    pa = np.arctan(absr[rows, at])
    dk = _local_bound(lambda r, c: kc[r, c], hi, ps.inner)
    dphi = _local_bound(lambda r, c: np.arctan(absr[r, c]), at, ps.inner)
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
    return _blank_invalid(out, valid)


def _blank_invalid(out: dict, valid: np.ndarray) -> dict:
    for k, v in out.items():
        if v.dtype.kind == "f":
            out[k] = np.where(valid, v, np.nan)
    return out


def translating_roller(ps: ProgramSamples, sigma: int, base_radius, offset, roller_radius) -> dict:
    """Figures of translating-roller designs (arrays of equal length)."""
    rb, e, rr = (np.asarray(a, float) for a in (base_radius, offset, roller_radius))
    rp = rb + rr
    valid = np.abs(e) < rp
    y0 = np.sqrt(np.where(valid, rp * rp - e * e, 1.0))
    valid &= (y0 + ps.lift_min) > 0
    Y = y0[:, None] + ps.s
    q = ps.s1 - sigma * e[:, None]
    T2 = Y * Y + q * q
    kc = (T2 + ps.s1 * q - Y * ps.s2) / (T2 * np.sqrt(T2))
    outer = np.sqrt(e * e + (y0 + ps.lift_max) ** 2) - rr
    return _roller_figures(kc, q / Y, rr, ps, outer, valid)


def oscillating_roller(ps: ProgramSamples, sigma: int, base_radius, pivot_distance, arm_length, roller_radius) -> dict:
    """Figures of oscillating-roller designs; the program's samples are the swing in radians."""
    rb, a, L, rr = (np.asarray(v, float) for v in (base_radius, pivot_distance, arm_length, roller_radius))
    rp = rb + rr
    valid = (np.abs(a - L) < rp) & (rp < a + L)
    x0 = (a * a + rp * rp - L * L) / (2 * a)
    y0 = np.sqrt(np.where(valid, rp * rp - x0 * x0, 1.0))
    beta0 = np.arctan2(y0, x0 - a)
    cb0, sb0 = np.cos(beta0)[:, None], np.sin(beta0)[:, None]
    cp, sp = np.cos(ps.s), np.sin(ps.s)
    cb = cb0 * cp + sb0 * sp  # β = β₀ − ψ
    sb = sb0 * cp - cb0 * sp
    L2 = L[:, None]
    b1, b2 = -ps.s1, -ps.s2
    px, py = a[:, None] + L2 * cb, L2 * sb
    p1x, p1y = -L2 * sb * b1, L2 * cb * b1
    p2x = L2 * (-sb * b2 - cb * b1 * b1)
    p2y = L2 * (cb * b2 - sb * b1 * b1)
    tx, ty = p1x + sigma * py, p1y - sigma * px
    t1x, t1y = p2x + sigma * p1y, p2y - sigma * p1x
    T2 = tx * tx + ty * ty
    kc = (T2 - sigma * (tx * t1y - ty * t1x)) / (T2 * np.sqrt(T2))
    # tan φ = (T·u)/(σ T×u), u = (sin β, −cos β); the denominator stays > 0 on a working cam
    ratio = (tx * sb - ty * cb) / (sigma * (-tx * cb - ty * sb))
    outer = np.sqrt(px * px + py * py).max(axis=1) - rr
    return _roller_figures(kc, ratio, rr, ps, outer, valid)


def translating_flat(ps: ProgramSamples, sigma: int, base_radius) -> dict:
    """Figures of translating flat-faced designs: ρ = R_b + s + s″, no pressure angle, no concave part."""
    rb = np.asarray(base_radius, float)
    n = rb.size
    rho_prog = ps.s + ps.s2
    rho = rb + rho_prog.min()
    d_rho = _bound(rho_prog[None, :], ps.inner)[0]
    r = np.sqrt(ps.s1[None, :] ** 2 + (rb[:, None] + ps.s) ** 2)
    valid = np.ones(n, bool)
    out = {
        "valid": valid,
        "max_pressure_angle_deg": np.zeros(n),
        "min_curvature_radius_mm": rho,
        "min_concave_radius_mm": np.full(n, math.inf),
        "undercut": rho <= 0,
        "outer_radius_mm": r.max(axis=1),
        "pressure_angle_bound_deg": np.zeros(n),
        "curvature_radius_bound_mm": np.full(n, d_rho),
    }
    return out


def block_figures(kind: str, ps: ProgramSamples, sigma: int, params: dict) -> dict:
    """The figures of one block of designs of follower ``kind``; ``params`` maps axis names to arrays."""
    if kind == "translating-roller":
        return translating_roller(ps, sigma, params["base_radius"], params["offset"], params["roller_radius"])
    if kind == "oscillating-roller":
        return oscillating_roller(ps, sigma, params["base_radius"], params["pivot_distance"], params["arm_length"],
                                  params["roller_radius"])
    if kind == "translating-flat":
        return translating_flat(ps, sigma, params["base_radius"])
    raise ValueError(f"no closed form for a {kind} follower")
