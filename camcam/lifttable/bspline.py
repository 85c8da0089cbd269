"""Seed 002's "NURBS" fit: a chord-length cubic B-spline with free ends.

The table points P_i = (angle_i, lift_i) are interpolated by a parametric
cubic B-spline r(u) = (x(u), y(u)) whose knots are the cumulative chord
lengths ∇_i = |P_{i+1} − P_i| (seed 002, eqs. 7–9, all weights 1, so the
"NURBS" is a non-rational B-spline) with the free (natural) end condition
r''(u) = 0 at both ends (eq. 8).  scipy's ``make_interp_spline`` solves the
same interpolation system as eq. 9.

The lift as a function of the angle, y(x), is then piecewise *rational* in
the parameter: with D = d/dx = (1/x')·d/du,

    dᵏy/dxᵏ = N_k(u) / x'(u)^(2k−1),   N_1 = y',  N_{k+1} = N_k'·x' − (2k−1)·N_k·x''

so every derivative is exact, and its stationary points on a piece are the
roots of the polynomial N_k'·x' − (2k−1)·N_k·x'' — no grid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.polynomial import Polynomial
from scipy.interpolate import PPoly, make_interp_spline

from camcam.errors import InputError

__all__ = ["ChordBSpline", "chord_bspline"]


def _pieces(spline) -> list[Polynomial]:
    pp = PPoly.from_spline(spline)
    out = []
    for i in range(len(pp.x) - 1):
        if pp.x[i + 1] > pp.x[i]:
            out.append(Polynomial(pp.c[::-1, i]))
    return out


@dataclass(frozen=True, eq=False, kw_only=True)
class ChordBSpline:
    """y(x) of a chord-length parametric cubic B-spline, exact derivatives up to order 4.

    Called as ``spline(x, nu)`` like a scipy spline.  ``x_knots`` are the
    table angles (the spline passes through every table point).
    """

    x_knots: np.ndarray
    lengths: np.ndarray
    xs: tuple[Polynomial, ...]
    ys: tuple[Polynomial, ...]
    numerators: tuple[tuple[Polynomial, ...], ...]  # [k-1][piece] = N_k, k = 1..4

    def locate(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(piece index, local parameter v) with x(v) = x, by safeguarded Newton."""
        x = np.asarray(x, dtype=float)
        idx = np.clip(np.searchsorted(self.x_knots, x, side="right") - 1, 0, len(self.xs) - 1)
        v = np.empty_like(x)
        for i in np.unique(idx):
            m = idx == i
            L = self.lengths[i]
            px, dx = self.xs[i], self.xs[i].deriv()
            x0, x1 = self.x_knots[i], self.x_knots[i + 1]
            target = x[m]
            lo, hi = np.zeros_like(target), np.full_like(target, L)
            t = L * np.clip((target - x0) / (x1 - x0), 0.0, 1.0)
            for _ in range(100):
                f = px(t) - target
                lo = np.where(f < 0, t, lo)
                hi = np.where(f > 0, t, hi)
                step = f / dx(t)
                t_new = t - step
                outside = (t_new <= lo) | (t_new >= hi)
                t_new = np.where(outside, 0.5 * (lo + hi), t_new)
                if np.all(np.abs(t_new - t) <= 1e-15 * max(L, 1.0)):
                    t = t_new
                    break
                t = t_new
            v[m] = t
        return idx, v

    def __call__(self, x, nu: int = 0) -> np.ndarray:
        if not 0 <= nu <= 4:
            raise ValueError(f"derivative order must be 0..4, got {nu!r}")
        x = np.asarray(x, dtype=float)
        idx, v = self.locate(x.ravel())
        out = np.empty_like(v)
        for i in np.unique(idx):
            m = idx == i
            if nu == 0:
                out[m] = self.ys[i](v[m])
            else:
                out[m] = self.numerators[nu - 1][i](v[m]) / self.xs[i].deriv()(v[m]) ** (2 * nu - 1)
        return out.reshape(x.shape)

    def piece_value(self, nu: int, i: int, v) -> np.ndarray:
        """Derivative ``nu`` on piece i at local parameters v (one-sided at the piece ends)."""
        v = np.asarray(v, dtype=float)
        if nu == 0:
            return self.ys[i](v)
        return self.numerators[nu - 1][i](v) / self.xs[i].deriv()(v) ** (2 * nu - 1)

    def stationary(self, nu: int, i: int) -> tuple[np.ndarray, np.ndarray]:
        """Angles inside piece i where derivative ``nu`` (0..3) is stationary, and its values there."""
        L = self.lengths[i]
        dx, ddx = self.xs[i].deriv(), self.xs[i].deriv(2)
        if nu == 0:
            top = self.ys[i].deriv()
        else:
            N = self.numerators[nu - 1][i]
            top = N.deriv() * dx - (2 * nu - 1) * N * ddx
        coef = top.trim().coef
        if len(coef) < 2 or not np.any(coef):
            return np.empty(0), np.empty(0)
        r = np.roots(coef[::-1])
        r = r[np.abs(r.imag) <= 1e-9 * max(1.0, L)].real
        r = r[(r > 1e-13 * L) & (r < L * (1 - 1e-13))]
        return self.xs[i](r), self.piece_value(nu, i, r)


def chord_bspline(x, y) -> ChordBSpline:
    """Fit seed 002's chord-length cubic B-spline with free ends through (x_i, y_i).

    Raises :class:`InputError` when the fitted curve folds back in x (x' ≤ 0
    on a span), which makes y(x) multivalued.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.linspace(0.0, 10.0, 11); s = chord_bspline(x, 2 * x + 1)
    >>> round(float(s(3.3)), 12), round(float(s(3.3, 1)), 12)
    (7.6, 2.0)
    """
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    chords = np.hypot(np.diff(x), np.diff(y))
    u = np.concatenate([[0.0], np.cumsum(chords)])
    sx = make_interp_spline(u, x, k=3, bc_type="natural")
    sy = make_interp_spline(u, y, k=3, bc_type="natural")
    xs, ys = _pieces(sx), _pieces(sy)
    for i, (px, L) in enumerate(zip(xs, chords)):
        d = px.deriv()
        cands = [0.0, L, *[r.real for r in d.deriv().roots() if abs(r.imag) < 1e-12 and 0 < r.real < L]]
        if min(d(c) for c in cands) <= 0:
            raise InputError(
                f"the chord-length B-spline folds back between {x[i]:g}° and {x[i + 1]:g}°; use a cubic spline fit"
            )
    nums = []
    N = [p.deriv() for p in ys]
    for k in range(1, 5):
        nums.append(tuple(N))
        m = 2 * k - 1
        N = [n.deriv() * px.deriv() - m * n * px.deriv(2) for n, px in zip(N, xs)]
    return ChordBSpline(x_knots=x, lengths=chords, xs=tuple(xs), ys=tuple(ys), numerators=tuple(nums))
