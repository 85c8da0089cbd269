"""Truncated Taylor jets: exact derivatives through composition.

A :class:`Jet` holds a quantity and its first ``K`` derivatives with respect to
one parameter (the cam angle), each an array over the sample points.  Sums,
products, quotients and the elementary functions below propagate every
derivative exactly (Leibniz and Faà di Bruno rules), so a cam profile built
from the motion program's ``lift(θ, k)`` carries exact derivatives without a
hand-written formula per follower.  ``K`` is at most 4, the highest order the
motion program provides.

Examples
--------
>>> import numpy as np
>>> t = Jet.variable(np.array([0.5]), 3)
>>> y = (t * t).sin()          # y = sin(t²)
>>> float(y.d[1][0]) == float(2 * 0.5 * np.cos(0.25))
True
"""

from __future__ import annotations

from dataclasses import dataclass
from math import comb

import numpy as np

__all__ = ["Jet", "MAX_ORDER", "hypot"]

#: Highest derivative order a jet carries (the motion program gives lift up to order 4).
MAX_ORDER = 4

#: Binomial coefficients C(k, j) for k, j ≤ 8 (Leibniz's rule in :meth:`Jet.__mul__`).
_BINOMIAL = np.array([[comb(k, j) for j in range(9)] for k in range(9)], dtype=float)


@dataclass(frozen=True)
class Jet:
    """Value and derivatives 1…K of a scalar field over sample points.

    ``d`` has shape (K+1, n): ``d[k]`` is the k-th derivative.
    """

    d: np.ndarray

    # -- construction -------------------------------------------------------
    @staticmethod
    def variable(t, K: int) -> "Jet":
        t = np.atleast_1d(np.asarray(t, dtype=float))
        d = np.zeros((K + 1, t.size))
        d[0] = t
        if K >= 1:
            d[1] = 1.0
        return Jet(d)

    @staticmethod
    def constant(c, n: int, K: int) -> "Jet":
        d = np.zeros((K + 1, n))
        d[0] = c
        return Jet(d)

    @staticmethod
    def from_derivatives(rows) -> "Jet":
        """A jet from the list ``[f, f′, f″, …]`` (arrays of one length)."""
        return Jet(np.array([np.asarray(r, dtype=float) for r in rows]))

    @property
    def K(self) -> int:
        return self.d.shape[0] - 1

    @property
    def value(self) -> np.ndarray:
        return self.d[0]

    def truncate(self, K: int) -> "Jet":
        return Jet(self.d[: K + 1])

    def derivative(self) -> "Jet":
        """The jet of f′ (one order less)."""
        return Jet(self.d[1:])

    # -- arithmetic ---------------------------------------------------------
    def _coerce(self, other) -> "Jet":
        if isinstance(other, Jet):
            return other
        return Jet.constant(other, self.d.shape[1], self.K)

    def __add__(self, other) -> "Jet":
        o = self._coerce(other)
        k = min(self.K, o.K)
        return Jet(self.d[: k + 1] + o.d[: k + 1])

    __radd__ = __add__

    def __neg__(self) -> "Jet":
        return Jet(-self.d)

    def __sub__(self, other) -> "Jet":
        return self + (-self._coerce(other))

    def __rsub__(self, other) -> "Jet":
        return self._coerce(other) - self

    def __mul__(self, other) -> "Jet":
        if not isinstance(other, Jet):
            return Jet(self.d * np.asarray(other, dtype=float))
        K = min(self.K, other.K)
        out = np.empty((K + 1, self.d.shape[1]))
        for k in range(K + 1):
            # Leibniz's rule, the k + 1 terms as rows summed in order (the sums a row at a time, as before)
            out[k] = (_BINOMIAL[k, : k + 1, None] * self.d[: k + 1] * other.d[k::-1]).sum(axis=0)
        return Jet(out)

    __rmul__ = __mul__

    def __truediv__(self, other) -> "Jet":
        if not isinstance(other, Jet):
            return Jet(self.d / np.asarray(other, dtype=float))
        return self * other.reciprocal()

    def __rtruediv__(self, other) -> "Jet":
        return self._coerce(other) * self.reciprocal()

    # -- composition --------------------------------------------------------
    def compose(self, f) -> "Jet":
        """f∘self, where ``f`` = [f(u), f′(u), …, f⁽ᴷ⁾(u)] at u = self.value (Faà di Bruno)."""
        u = self.d
        K = self.K
        if K > MAX_ORDER:
            raise ValueError(f"jets carry at most order {MAX_ORDER}, got {K}")
        out = [f[0]]
        if K >= 1:
            out.append(f[1] * u[1])
        if K >= 2:
            out.append(f[2] * u[1] ** 2 + f[1] * u[2])
        if K >= 3:
            out.append(f[3] * u[1] ** 3 + 3 * f[2] * u[1] * u[2] + f[1] * u[3])
        if K >= 4:
            out.append(
                f[4] * u[1] ** 4 + 6 * f[3] * u[1] ** 2 * u[2] + f[2] * (3 * u[2] ** 2 + 4 * u[1] * u[3]) + f[1] * u[4]
            )
        return Jet(np.array(out))

    def reciprocal(self) -> "Jet":
        u = self.value
        return self.compose([(-1) ** j * _fact(j) / u ** (j + 1) for j in range(self.K + 1)])

    def sin(self) -> "Jet":
        s, c = np.sin(self.value), np.cos(self.value)
        return self.compose([s, c, -s, -c, s][: self.K + 1])

    def cos(self) -> "Jet":
        s, c = np.sin(self.value), np.cos(self.value)
        return self.compose([c, -s, -c, s, c][: self.K + 1])

    def sqrt(self) -> "Jet":
        u = self.value
        r = np.sqrt(u)
        f = [r, 0.5 / r, -0.25 / (u * r), 0.375 / (u * u * r), -0.9375 / (u**3 * r)]
        return self.compose(f[: self.K + 1])

    def atan(self) -> "Jet":
        u = self.value
        q = 1.0 / (1.0 + u * u)
        f = [
            np.arctan(u),
            q,
            -2 * u * q**2,
            (6 * u * u - 2) * q**3,
            24 * u * (1 - u * u) * q**4,
        ]
        return self.compose(f[: self.K + 1])

    @staticmethod
    def atan2(y: "Jet", x: "Jet") -> "Jet":
        """The angle of (x, y): value from ``np.arctan2``, derivatives from (x y′ − y x′)/(x² + y²)."""
        K = min(x.K, y.K)
        val = np.arctan2(y.value, x.value)
        if K == 0:
            return Jet(val[None, :])
        xs, ys = x.truncate(K - 1), y.truncate(K - 1)
        rate = (xs * y.derivative().truncate(K - 1) - ys * x.derivative().truncate(K - 1)) / (xs * xs + ys * ys)
        return Jet(np.vstack([val[None, :], rate.d]))


def _fact(j: int) -> float:
    out = 1.0
    for i in range(2, j + 1):
        out *= i
    return out


def hypot(x: Jet, y: Jet) -> Jet:
    """√(x² + y²) as a jet."""
    return (x * x + y * y).sqrt()
