"""The design space of seed 000: uniform odd-degree B-splines with end conditions.

A cam curve is a uniform B-spline of odd degree ``n`` over ``N`` equal knot
intervals of ``[0, L]`` (seed 000, eq. 3), with ``N + n`` control points.
Boundary conditions fix ``n0`` of them, leaving ``N + n − n0`` independent
("free") control points, the optimisation variables:

* symmetric (``L = 0.5``): S(0) = 0, V(0) = 0, A(0) = 0, S(0.5) = 0.5,
  A(0.5) = 0 (n0 = 5); the curve on [0.5, 1] is the point mirror
  S(T) = 1 − S(1 − T), so V and J are even and A odd about T = 0.5;
* asymmetric (``L = 1``): S, V, A fixed at both ends (n0 = 6).

The first control points are solved from the start conditions and the last
ones from the end conditions; the others are free.  Every quantity the
optimisers need is affine in the free points: the power-basis coefficients of
each polynomial piece of S are ``C0 + K @ x``.

The knots are uniform, so every basis function is the cardinal B-spline
M_n(x) = (1/n!) Σ_l (−1)^l C(n+1, l) (x − l)_+^n, shifted and scaled; its
power coefficients on each knot interval are integers over n! (computed
exactly, :func:`cardinal_pieces`).  scipy's ``BSpline``/``PPoly.from_spline``
give the same numbers (the tests compare them) but need ``scipy.interpolate``,
whose import alone (0.4–0.8 s) is longer than ``camcam optimize``'s whole
exact solve; :meth:`BSplineSpace.spline` still returns a scipy ``BSpline``
for checks.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
from numpy.polynomial import polynomial as P

__all__ = ["BSplineSpace", "MAX_DEGREE", "MAX_SEGMENTS"]

#: Largest degree accepted (odd degrees 3 … 9 cover every practical cam curve).
MAX_DEGREE = 9
#: Largest number of knot intervals accepted (keeps the LP and JSON small).
MAX_SEGMENTS = 400


@dataclass(frozen=True)
class BSplineSpace:
    """Uniform B-splines of odd ``degree`` over ``segments`` intervals with the paper's end conditions.

    Parameters
    ----------
    degree : int
        Odd degree n (3 … 9).
    segments : int
        Number N of equal knot intervals of [0, 0.5] (symmetric) or [0, 1].
    symmetric : bool
        Point-symmetric about (0.5, 0.5) (optimised on [0, 0.5]) or not.

    Examples
    --------
    >>> sp = BSplineSpace(5, 7, True)
    >>> sp.n_control, sp.n_conditions, sp.n_free
    (12, 5, 7)
    >>> x = sp.initial_free()
    >>> S0, V0, A0 = (float(sp.spline(x)(0.0, k)) for k in range(3))
    >>> max(abs(S0), abs(V0), abs(A0)) < 1e-12
    True
    """

    degree: int = 5
    segments: int = 7
    symmetric: bool = True
    _p0: np.ndarray = field(init=False, repr=False, compare=False)
    _E: np.ndarray = field(init=False, repr=False, compare=False)
    _Q: np.ndarray = field(init=False, repr=False, compare=False)
    _free: tuple = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        n, N = self.degree, self.segments
        if not (isinstance(n, int) and 3 <= n <= MAX_DEGREE and n % 2 == 1):
            raise ValueError(f"degree must be an odd integer from 3 to {MAX_DEGREE}, got {n!r}")
        if not (isinstance(N, int) and 1 <= N <= MAX_SEGMENTS):
            raise ValueError(f"segments must be an integer from 1 to {MAX_SEGMENTS}, got {N!r}")
        if self.n_free < 1:
            raise ValueError(f"{N} segment(s) of degree {n} leave no free control point")
        # Power-basis coefficients (lowest first, local variable u = T − T_i) of S on
        # each knot interval, per control point: Q[i, k, j].  Control point j's basis
        # function is M_n((T − t_j)/h), t_j = (j − n)·h: on interval i it is M_n's
        # piece m = i + n − j (0 ≤ m ≤ n), whose coefficient of s^k becomes one of u^k / h^k.
        M = cardinal_pieces(n)
        Q = np.zeros((N, n + 1, self.n_control))
        scale = self.h ** -np.arange(n + 1.0)
        for i in range(N):
            for m in range(n + 1):
                Q[i, :, i + n - m] = M[m] * scale
        object.__setattr__(self, "_Q", Q)
        # Boundary-condition rows B @ P = b, P the N + n control points.
        conds = self.conditions
        B = np.concatenate([self.basis_matrix(np.array([T]), k) for T, k, _ in conds])
        b = np.array([v for _, _, v in conds])
        n_start = sum(1 for T, _, _ in conds if T == 0.0)
        n_end = len(conds) - n_start
        det = list(range(n_start)) + list(range(self.n_control - n_end, self.n_control))
        free = [j for j in range(self.n_control) if j not in det]
        Bd = B[:, det]
        if len(set(det)) != len(det) or np.linalg.cond(Bd) > 1e10:
            raise ValueError(f"{N} segment(s) are too few for the end conditions of degree {n}")
        p0 = np.zeros(self.n_control)
        E = np.zeros((self.n_control, len(free)))
        p0[det] = np.linalg.solve(Bd, b)
        E[det] = -np.linalg.solve(Bd, B[:, free])
        E[free, np.arange(len(free))] = 1.0
        object.__setattr__(self, "_p0", p0)
        object.__setattr__(self, "_E", E)
        object.__setattr__(self, "_free", tuple(free))

    # -- layout -----------------------------------------------------------------
    @property
    def span(self) -> float:
        """Length L of the optimised range: 0.5 (symmetric) or 1."""
        return 0.5 if self.symmetric else 1.0

    @property
    def h(self) -> float:
        """Knot spacing ΔT."""
        return self.span / self.segments

    @property
    def knots(self) -> np.ndarray:
        """The N + 2n + 1 uniform knots, n of them outside [0, L] at each end."""
        return self.span * np.arange(-self.degree, self.segments + self.degree + 1) / self.segments

    @property
    def n_control(self) -> int:
        return self.segments + self.degree

    @property
    def conditions(self) -> tuple[tuple[float, int, float], ...]:
        """(T, derivative order, value) of every boundary condition."""
        start = ((0.0, 0, 0.0), (0.0, 1, 0.0), (0.0, 2, 0.0))
        if self.symmetric:
            return start + ((0.5, 0, 0.5), (0.5, 2, 0.0))
        return start + ((1.0, 0, 1.0), (1.0, 1, 0.0), (1.0, 2, 0.0))

    @property
    def n_conditions(self) -> int:
        return 5 if self.symmetric else 6

    @property
    def n_free(self) -> int:
        """N + n − n0 independent control points."""
        return self.segments + self.degree - self.n_conditions

    @property
    def n_pieces(self) -> int:
        """Polynomial pieces of the whole law on [0, 1] (2N when mirrored)."""
        return 2 * self.segments if self.symmetric else self.segments

    @property
    def breaks(self) -> np.ndarray:
        """Piece boundaries of the whole law, 0 … 1."""
        return np.arange(self.n_pieces + 1) / self.n_pieces

    # -- maps from the free points ----------------------------------------------
    def control_points(self, x) -> np.ndarray:
        """All N + n control points for the free points ``x``."""
        return self._p0 + self._E @ np.asarray(x, dtype=float)

    def free_points(self, control) -> np.ndarray:
        """The free points inside a full control vector (inverse of :meth:`control_points`)."""
        return np.asarray(control, dtype=float)[list(self._free)]

    def spline(self, x):
        """The scipy ``BSpline`` over [0, L] for the free points ``x`` (for checks: it imports scipy.interpolate)."""
        from scipy.interpolate import BSpline

        return BSpline(self.knots, self.control_points(x), self.degree)

    def basis_matrix(self, T, nu: int = 0) -> np.ndarray:
        """Values (or ``nu``-th derivatives) of the N + n basis functions at ``T`` in [0, L]: shape (len(T), N + n).

        Each T is evaluated on its knot interval (the last interval for T = L), from the
        exact power coefficients.  The basis is C^(n−1): for ``nu`` < n a T on a knot gives
        the same value from either side (up to rounding), while the n-th derivative jumps there.

        Examples
        --------
        >>> sp = BSplineSpace(3, 4, False)
        >>> B = sp.basis_matrix(np.array([0.0, 0.3, 1.0]))
        >>> B.sum(axis=1).round(15).tolist()  # a partition of unity
        [1.0, 1.0, 1.0]
        """
        T = np.asarray(T, dtype=float)
        n, N, h = self.degree, self.segments, self.h
        i = np.clip(np.floor(T / h).astype(int), 0, N - 1)
        u = T - i * h
        k = np.arange(n + 1)
        falling = np.array([math.perm(int(p), nu) for p in k], dtype=float)  # d^ν u^p = p!/(p−ν)! u^(p−ν)
        powers = np.where(k >= nu, u[:, None] ** np.maximum(k - nu, 0), 0.0) * falling
        return np.einsum("sk,skj->sj", powers, self._Q[i])

    def affine_pieces(self) -> tuple[np.ndarray, np.ndarray]:
        """``(C0, K)`` with piece coefficients ``C0 + K @ x`` for the whole law on [0, 1].

        ``C0`` has shape (pieces, n + 1), ``K`` (pieces, n + 1, free); the
        coefficients are lowest first in u = T − breaks[i], u ∈ [0, h].
        """
        Q = self._Q
        C0 = Q @ self._p0
        K = Q @ self._E
        if not self.symmetric:
            return C0, K
        # Mirror: S(0.5 + k·h + u) = 1 − S_i(h − u) with i = N − 1 − k.
        F = _reflection_matrix(self.degree, self.h)
        C0m = 1.0 * np.eye(1, self.degree + 1)[0] - C0[::-1] @ F.T
        Km = -np.einsum("jk,ikf->ijf", F, K[::-1])
        return np.concatenate([C0, C0m]), np.concatenate([K, Km])

    def pieces(self, control) -> np.ndarray:
        """Piece coefficients (pieces, n + 1) of the whole law for a full control vector."""
        C = self._Q @ np.asarray(control, dtype=float)
        if not self.symmetric:
            return C
        F = _reflection_matrix(self.degree, self.h)
        Cm = np.eye(1, self.degree + 1)[0] - C[::-1] @ F.T
        return np.concatenate([C, Cm])

    def initial_free(self) -> np.ndarray:
        """A feasible-looking start: the free points closest (least squares) to the cycloidal law."""
        T = np.linspace(0.0, self.span, 20 * self.segments + 1)
        target = T - np.sin(2 * math.pi * T) / (2 * math.pi)
        basis = self.basis_matrix(T)
        x, *_ = np.linalg.lstsq(basis @ self._E, target - basis @ self._p0, rcond=None)
        return x


@functools.lru_cache(maxsize=None)
def cardinal_pieces(n: int) -> np.ndarray:
    """Power coefficients of the cardinal B-spline M_n on its n + 1 unit intervals: ``C[m, k]``, s^k on [m, m + 1].

    M_n(m + s) = (1/n!) Σ_{l ≤ m} (−1)^l C(n+1, l) (m − l + s)^n, so the
    coefficient of s^k is the integer Σ_l (−1)^l C(n+1, l) C(n, k) (m − l)^(n−k)
    over n!, rounded once to the nearest float.  (Read-only: cached per degree.)

    Examples
    --------
    >>> (cardinal_pieces(1) * 1).tolist()  # the hat: s on [0, 1], 1 − s on [1, 2]
    [[0.0, 1.0], [1.0, -1.0]]
    >>> (cardinal_pieces(3) * 6).tolist()[1]  # M_3 on [1, 2] is (1 + 3s + 3s² − 3s³)/6
    [1.0, 3.0, 3.0, -3.0]
    """
    out = np.empty((n + 1, n + 1))
    for m in range(n + 1):
        for k in range(n + 1):
            num = sum((-1) ** l * math.comb(n + 1, l) * math.comb(n, k) * (m - l) ** (n - k) for l in range(m + 1))
            out[m, k] = num / math.factorial(n)
    out.flags.writeable = False
    return out


def _reflection_matrix(degree: int, h: float) -> np.ndarray:
    """F with coef(p(h − u)) = F @ coef(p(u)), coefficients lowest first."""
    F = np.zeros((degree + 1, degree + 1))
    for k in range(degree + 1):
        e = np.zeros(k + 1)
        e[k] = 1.0
        comp = _compose(e, h)
        F[: len(comp), k] = comp
    return F


def _compose(coef: np.ndarray, h: float) -> np.ndarray:
    """Coefficients of p(h − u) for p with coefficients ``coef``."""
    out = np.zeros(1)
    for c in coef[::-1]:  # Horner: out = out·(h − u) + c
        out = P.polyadd(P.polymul(out, [h, -1.0]), [c])
    return out
