"""One piece of a piecewise motion law: a polynomial plus one sinusoid.

Every textbook cam law is, piece by piece, of the form

    f(u) = P(u) + a·sin(ω·u) + b·cos(ω·u),     u = T − t0 ∈ [0, L]

where P is a polynomial.  Differentiation and integration keep that form, and
when a sinusoid is present P has degree ≤ 1, so the stationary points of every
derivative solve ``c + R·cos(ω·u + φ) = 0``: a closed form.  Without a
sinusoid they are polynomial roots.  Nothing here samples a grid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.polynomial import polynomial as P

__all__ = ["TrigPoly"]


def _trim(coef) -> tuple[float, ...]:
    """The coefficients as floats without trailing zeros (plain Python: a lift table makes 10⁵ pieces)."""
    if isinstance(coef, (tuple, list)):
        vals = [float(c) for c in coef]
    else:
        vals = [float(c) for c in np.atleast_1d(np.asarray(coef, dtype=float))]
    k = len(vals)
    while k > 0 and vals[k - 1] == 0.0:
        k -= 1
    return tuple(vals[:k]) if k else (0.0,)


@dataclass(frozen=True)
class TrigPoly:
    """``f(u) = Σ poly[k]·u^k + a·sin(omega·u) + b·cos(omega·u)``.

    Parameters
    ----------
    poly : tuple of float
        Polynomial coefficients, lowest degree first.
    a, b : float
        Sine and cosine amplitudes.
    omega : float
        Angular frequency of the sinusoid (must be > 0 when a or b is not 0).

    Examples
    --------
    >>> f = TrigPoly((0.0, 1.0), a=-1 / (2 * math.pi), omega=2 * math.pi)  # cycloidal
    >>> round(float(f(0.5)), 12), round(float(f.derivative()(0.5)), 12)
    (0.5, 2.0)
    """

    poly: tuple[float, ...] = (0.0,)
    a: float = 0.0
    b: float = 0.0
    omega: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "poly", _trim(self.poly))
        if self.has_trig:
            if not self.omega > 0:
                raise ValueError(f"omega must be > 0 with a sinusoid, got {self.omega!r}")
            if len(self.poly) > 2:
                raise ValueError(
                    "a piece with a sinusoid may carry a polynomial of degree <= 1 "
                    f"(closed-form extremes), got degree {len(self.poly) - 1}"
                )

    @property
    def has_trig(self) -> bool:
        return self.a != 0.0 or self.b != 0.0

    def __call__(self, u):
        u = np.asarray(u, dtype=float)
        out = P.polyval(u, self.poly)
        if self.has_trig:
            out = out + self.a * np.sin(self.omega * u) + self.b * np.cos(self.omega * u)
        return out

    def derivative(self, order: int = 1) -> TrigPoly:
        f = self
        for _ in range(order):
            c = f.poly  # d/du Σ c_j u^j = Σ j·c_j u^(j−1): the same products as numpy's polyder
            poly = tuple(j * c[j] for j in range(1, len(c))) if len(c) > 1 else (0.0,)
            f = TrigPoly(poly, -f.b * f.omega, f.a * f.omega, f.omega)
        return f

    def integral(self, constant: float = 0.0) -> TrigPoly:
        """Antiderivative with value ``constant`` at u = 0."""
        poly = np.asarray(P.polyint(self.poly), dtype=float)
        a = b = 0.0
        if self.has_trig:
            a, b = self.b / self.omega, -self.a / self.omega
        poly[0] = constant - b  # F(0) = poly[0] + b·cos(0)
        return TrigPoly(poly, a, b, self.omega)

    def scaled(self, k: float) -> TrigPoly:
        return TrigPoly(tuple(k * c for c in self.poly), k * self.a, k * self.b, self.omega)

    def stationary_points(self, length: float) -> np.ndarray:
        """Sorted u in the open interval (0, length) where f'(u) = 0 (exact)."""
        d = self.derivative()
        if not d.has_trig:
            if len(d.poly) == 1:
                return np.empty(0)
            roots = P.polyroots(d.poly)
            roots = roots[np.abs(roots.imag) <= 1e-12 * max(1.0, length)].real
        else:
            # c + a' sin(ωu) + b' cos(ωu) = c + R cos(ωu − φ), R = hypot(a', b'), φ = atan2(a', b')
            c = d.poly[0] if len(d.poly) == 1 else None
            if c is None:  # excluded by __post_init__; kept explicit for the reader
                raise ValueError("non-constant polynomial beside a sinusoid")
            R = math.hypot(d.a, d.b)
            phi = math.atan2(d.a, d.b)
            ratio = -c / R
            if abs(ratio) > 1.0:
                return np.empty(0)
            base = math.acos(max(-1.0, min(1.0, ratio)))
            w = d.omega
            kmax = int(math.ceil((w * length + abs(phi)) / (2 * math.pi))) + 1
            cands = []
            for k in range(-kmax, kmax + 1):
                for s in (base, -base):
                    cands.append((s + phi + 2 * math.pi * k) / w)
            roots = np.array(cands)
        eps = 1e-13 * max(1.0, length)
        roots = np.sort(roots[(roots > eps) & (roots < length - eps)])
        # equal roots once (np.unique's result; numpy ≥ 2.3's np.unique imports numpy.ma, 40 ms of
        # `camcam optimize`, for its masked-array check)
        return roots[np.r_[True, roots[1:] != roots[:-1]]] if roots.size else roots
