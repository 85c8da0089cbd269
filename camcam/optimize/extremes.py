"""Exact extremes of many polynomial pieces at once.

The optimisers evaluate thousands of candidate curves; each is a stack of
polynomial pieces (lowest coefficient first, local variable u ∈ [0, h]).  The
extreme of a derivative on a piece is at an end or at a real root of the next
derivative inside the piece; the roots of all pieces come from one batched
eigenvalue call on their companion matrices (what ``numpy.roots`` does for one
polynomial).  :class:`camcam.motion.law.PiecewiseLaw` computes the same
extremes piece by piece with ``numpy.polynomial.polyroots``; the tests compare
the two.
"""

from __future__ import annotations

import numpy as np

__all__ = ["derivative_coefficients", "piece_extremes", "polyval_rows"]


def derivative_coefficients(C: np.ndarray, order: int) -> np.ndarray:
    """Coefficients (lowest first) of the ``order``-th derivative of every row of ``C``.

    Examples
    --------
    >>> derivative_coefficients(np.array([[1.0, 2.0, 3.0]]), 1)
    array([[2., 6.]])
    """
    C = np.asarray(C, dtype=float)
    d = C.shape[-1] - 1
    if order > d:
        return np.zeros(C.shape[:-1] + (1,))
    k = np.arange(order, d + 1)
    fall = np.ones(len(k))
    for j in range(order):
        fall *= k - j
    return C[..., order:] * fall


def polyval_rows(C: np.ndarray, u: np.ndarray) -> np.ndarray:
    """Evaluate row i of ``C`` at ``u[i, ...]`` (Horner, broadcast over trailing axes)."""
    u = np.asarray(u, dtype=float)
    out = np.zeros_like(u)
    shape = (C.shape[0],) + (1,) * (u.ndim - 1)
    for c in C[:, ::-1].T:
        out = out * u + c.reshape(shape)
    return out


def piece_extremes(C: np.ndarray, h: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Minimum and maximum of every polynomial row of ``C`` on [0, h].

    Returns ``(min, argmin_u, max, argmax_u)``, each of shape (pieces,).

    Examples
    --------
    >>> lo, ulo, hi, uhi = piece_extremes(np.array([[0.0, 1.0, -1.0]]), 1.0)  # u − u²
    >>> float(hi[0]), float(uhi[0]), float(lo[0])
    (0.25, 0.5, 0.0)
    """
    C = np.asarray(C, dtype=float)
    m, d1 = C.shape
    # Work in s = u/h ∈ [0, 1] so that coefficients are of comparable size.
    Cs = C * h ** np.arange(d1)
    cand = [np.zeros(m), np.ones(m)]
    D = derivative_coefficients(Cs, 1)
    deg = D.shape[1] - 1
    if deg >= 1:
        scale = np.abs(D).max(axis=1)
        scale[scale == 0] = 1.0
        lead = D[:, -1]
        tiny = np.abs(lead) < 1e-13 * scale
        # A vanishing leading coefficient: perturb it so its root flies off to
        # ~1e13, far outside [0, 1]; the other roots keep their accuracy.
        lead = np.where(tiny, 1e-13 * scale, lead)
        if deg == 1:
            roots = (-D[:, 0] / lead)[:, None].astype(complex)
        elif deg == 2:
            a, b, c = lead, D[:, 1], D[:, 0]
            disc = np.sqrt((b * b - 4 * a * c).astype(complex))
            q = -0.5 * (b + np.where(b.real >= 0, 1, -1) * disc)  # stable quadratic formula
            with np.errstate(divide="ignore", invalid="ignore"):
                roots = np.stack([q / a, np.where(q != 0, c / q, 0.0)], axis=1)
        else:
            comp = np.zeros((m, deg, deg))
            comp[:, 0, :] = -D[:, -2::-1] / lead[:, None]
            comp[:, np.arange(1, deg), np.arange(deg - 1)] = 1.0
            roots = np.linalg.eigvals(comp)
        real = np.abs(roots.imag) <= 1e-9 * np.maximum(1.0, np.abs(roots.real))
        r = np.where(real & (roots.real > 0) & (roots.real < 1), roots.real, 0.0)
        cand += list(r.T)
    S = np.stack(cand, axis=1)  # (m, candidates) in s
    vals = polyval_rows(Cs, S)
    i_lo = np.argmin(vals, axis=1)
    i_hi = np.argmax(vals, axis=1)
    rows = np.arange(m)
    return vals[rows, i_lo], S[rows, i_lo] * h, vals[rows, i_hi], S[rows, i_hi] * h
