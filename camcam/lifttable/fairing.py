"""Fine fairing of a lift table: seed 004's mid-point re-interpolation, or a smoothing spline.

``mid-point`` (seed 004, 1.3.2, steps 1–5)
    (1) interpolate the table h_i at α_i; (2) take the mid-points β of every
    interval (plus the two end angles for a rise-only table; a full revolution
    wraps instead) with the interpolant's values there; (3) interpolate those;
    (4) evaluate the new interpolant at the original α_i: the corrected lifts;
    (5) repeat until no point moves by ξ or more in one round.  End points of a
    rise-only table stay fixed (the seed checks i = 1 … n−1).
``smoothing``
    scipy's ``make_smoothing_spline`` (a cubic smoothing spline with the
    penalty λ chosen by generalised cross-validation); a full revolution is
    padded by one period on each side so the fit wraps round 360°/0°, then
    sampled at the table angles.

Both return a faired table on the same angles; the motion law is then the
chosen fit through it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.interpolate import make_smoothing_spline

from camcam.lifttable.interpolate import interpolate
from camcam.lifttable.smoothing import GCV_MAX_POINTS, GCV_SUBSAMPLE, gcv_lambda, reinsch
from camcam.lifttable.table import LiftTable

__all__ = ["FairingResult", "METHODS", "DEFAULT_METHOD", "DEFAULT_XI", "midpoint_fairing", "smoothing_fairing", "fair"]

METHODS = ("mid-point", "smoothing")
#: The default for noisy tables: see docs/lift-tables-and-reverse.md ("Which fairing") for the comparison.
DEFAULT_METHOD = "smoothing"
#: Default ξ (mm or deg): a tenth of a micrometre.
DEFAULT_XI = 1e-4
DEFAULT_MAX_ITERATIONS = 1000


@dataclass(frozen=True, kw_only=True)
class FairingResult:
    """A faired table and how it was obtained.

    ``iterations`` is the number of mid-point rounds (1 for the smoothing
    spline); ``max_correction`` the largest |faired − input| lift;
    ``converged`` whether the last round moved every point by less than ξ;
    ``lam`` the smoothing penalty when one was given (None: chosen by GCV, or mid-point).
    """

    method: str
    table: LiftTable
    iterations: int
    max_correction: float
    converged: bool
    lam: float | None = None


def midpoint_fairing(
    table: LiftTable,
    fit: str,
    xi: float = DEFAULT_XI,
    max_iterations: int = DEFAULT_MAX_ITERATIONS,
    end_slopes: tuple[float, float] = (0.0, 0.0),
) -> FairingResult:
    """Seed 004's iterated mid-point re-interpolation (module docstring).

    Examples
    --------
    >>> ang = np.arange(0.0, 361.0, 1.0); h = 3 - 3 * np.cos(np.radians(ang))
    >>> h = h + 0.003 * (-1.0) ** np.arange(361); h[-1] = h[0]   # zig-zag noise
    >>> r = midpoint_fairing(LiftTable(tuple(ang), tuple(h)), "periodic")
    >>> r.converged, r.iterations, round(r.max_correction, 4)
    (True, 2, 0.003)
    """
    x, h0 = table.x, table.y
    periodic = fit == "periodic"
    h = h0.copy()
    mids = 0.5 * (x[:-1] + x[1:])
    if periodic:
        beta = np.concatenate([mids, [mids[0] + 360.0]])
    else:
        beta = np.concatenate([[x[0]], mids, [x[-1]]])
    inner = slice(None) if periodic else slice(1, -1)
    converged = False
    it = 0
    while it < max_iterations:
        it += 1
        f1 = interpolate(x, h, fit, end_slopes)
        hb = f1(beta)
        if periodic:
            hb[-1] = hb[0]
            xe = np.mod(x - beta[0], 360.0) + beta[0]  # the table angles inside [β_0, β_0 + 360]
        else:
            xe = x
        f2 = interpolate(beta, hb, fit, end_slopes)
        new = f2(xe)
        if periodic:
            new[-1] = new[0]
        else:
            new[0], new[-1] = h[0], h[-1]
        step = float(np.max(np.abs(new[inner] - h[inner])))
        h = new
        if step < xi:
            converged = True
            break
    return FairingResult(method="mid-point", table=table.with_lift(h), iterations=it,
                         max_correction=float(np.max(np.abs(h - h0))), converged=converged)


def smoothing_fairing(table: LiftTable, lam: float | None = None) -> FairingResult:
    """Cubic smoothing spline, λ by GCV unless given; periodic tables padded by a period each side.

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> ang = np.arange(0.0, 361.0, 1.0); truth = 3 - 3 * np.cos(np.radians(ang))
    >>> h = truth + rng.normal(0, 0.003, ang.size); h[-1] = h[0]
    >>> r = smoothing_fairing(LiftTable(tuple(ang), tuple(h)))
    >>> bool(np.max(np.abs(r.table.y - truth)) < 0.003)
    True
    """
    x, y = table.x, table.y
    periodic = table.full_revolution

    def padded(xx, yy):
        if not periodic:
            return xx, yy
        xu, yu = xx[:-1], yy[:-1]
        return np.concatenate([xu - 360.0, xu, xu + 360.0, [xx[-1] + 360.0]]), np.concatenate([yu, yu, yu, [yy[0]]])

    xs, ys = padded(x, y)
    if len(xs) <= GCV_MAX_POINTS:
        h = make_smoothing_spline(xs, ys, lam=lam)(x)
    else:  # a large table: Reinsch's banded solve, λ by GCV on every k-th point (camcam.lifttable.smoothing)
        if lam is None:
            n = len(x) - 1 if periodic else len(x)
            k = math.ceil(n / GCV_SUBSAMPLE)
            sub = np.arange(0, n, k)
            xk, yk = (np.append(x[sub], x[-1]), np.append(y[sub], y[-1])) if periodic else (x[sub], y[sub])
            lam = gcv_lambda(*padded(xk, yk)) * k ** 0.2
        g = reinsch(xs, ys, lam)
        h = g[len(x) - 1: 2 * len(x) - 1] if periodic else g
    faired = table.with_lift(h)
    return FairingResult(method="smoothing", table=faired, iterations=1,
                         max_correction=float(np.max(np.abs(faired.y - y))), converged=True, lam=lam)


def fair(
    table: LiftTable,
    method: str,
    fit: str,
    xi: float = DEFAULT_XI,
    end_slopes: tuple[float, float] = (0.0, 0.0),
    max_iterations: int = DEFAULT_MAX_ITERATIONS,
) -> FairingResult:
    """Fair ``table`` by ``method`` (one of :data:`METHODS`)."""
    if method == "mid-point":
        return midpoint_fairing(table, fit, xi, max_iterations, end_slopes)
    if method == "smoothing":
        return smoothing_fairing(table)
    raise ValueError(f"unknown fairing method {method!r}; known: {', '.join(METHODS)}")
