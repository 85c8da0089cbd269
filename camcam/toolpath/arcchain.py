"""The fewest-arcs chain: a closed G1 arc chain of a given count, its joints and curvatures optimised by LP.

The beam march (:mod:`camcam.toolpath.beam`) places one joint after another;
its count is a step function of where it starts (±1–2 arcs over the starts of
one contour).  This module answers the question the count depends on
directly: how close to the curve can ``n`` arcs, placed anywhere, stay?  It
fits a closed G1 arc chain of ``n`` arcs to the curve in the largest error
(minimax) by sequential linear programming (SLP) on the chain's joints; the
breakpoints are free, on the curve or off it across the band, as in Maier's
smooth minimum arc paths ("Smooth minimum arc paths", 2014), and G1 is a
constraint rather than a march's inheritance.

The chain (:class:`Joints`).  Arc i leaves joint Jᵢ along θᵢ and ends at
Jᵢ₊₁; it is G1 at its end when θᵢ₊₁ = 2φᵢ − θᵢ (φᵢ the chord's direction),
one equation per arc, and its curvature is kᵢ = 2 sin(φᵢ − θᵢ)/|chord|.  Each
sample of the curve depends on one arc's two joints only, so the problem is
local and well conditioned (a turtle path of curvatures and lengths, tried
first, moved the whole rest of the chain with each arc and converged poorly).

The coordinates (:class:`OnCurve`).  A joint is its curve parameter t, its
offset v along the normal and its turn ψ off the tangent: J = P(t) + v N(t),
θ = arg P′(t) + ψ.  A joint sliding along the curve keeps its offset and its
turn against the curve, so a step's effect is nearly linear (a slide along a
fixed tangent would leave the curve by κu²/2 and turn against it by κu, far
more than δ).

The error (:func:`chain_errors`).  A sample P of the curve (every few rows of a
table, fixed along the curve) is measured against the arc whose span holds
it by the exact signed distance to the arc's circle,
e = (2a − k|d|²)/(1 + √(1 − 2ak + k²|d|²)), d = P − Jᵢ and a its normal
component (finite for k → 0: the line).  Its derivatives are exact: a joint's
move translates the circle, a turn of θᵢ rotates it about Jᵢ, and a change
of kᵢ moves the foot by ∂/∂k of the point at length σ along the arc.

The step (:func:`minimax_chain`).  One LP (HiGHS) per step,

    minimise t + μs  subject to  |eⱼ + ∇eⱼ·δ| ≤ t,  |cᵢ(gᵢ + ∇gᵢ·δ)| ≤ s,
                                 |βᵢ + ∇βᵢ·δ| ≤ max sweep / 2,  δ in a trust region,

with g the G1 residuals, β the arcs' half turns and μ = 10 (an exact
penalty: the gap goes to zero); the chain is then evaluated exactly, the step
kept if t + μs fell, and the trust region set by the ratio of the achieved
to the predicted fall.  The LP takes its sample rows as they bind (cutting
planes, :func:`_solve_step`).
"""

from __future__ import annotations

import math

import numpy as np

from camcam.geometry.curve import derivatives
from camcam.toolpath.elements import element_tangent

__all__ = ["Joints", "OnCurve", "CurveTable", "on_curve", "joints_of", "joint_rows", "sample_spacing",
           "chain_samples", "chain_errors", "step_jacobians", "minimax_chain"]


class Joints:
    """A closed G1 arc chain by its joints: points J (n, 2) and directions θ (n,), turning 2πw once round.

    Arc i leaves J[i] along θ[i] and ends at J[i + 1] (J[0] after the last);
    it is G1 at its end when θ[i + 1] = 2φᵢ − θ[i] (φᵢ the chord's direction),
    and its curvature is kᵢ = 2 sin(φᵢ − θᵢ)/|chord|.
    """

    __slots__ = ("J", "theta", "w")

    def __init__(self, J, theta, w: int):
        self.J = np.asarray(J, float)
        self.theta = np.asarray(theta, float)
        self.w = int(w)

    def arcs(self):
        """Per arc: chord vector (n, 2), chord length, half turn β = φ − θ (wrapped), curvature, G1 residual."""
        J, th = self.J, self.theta
        v = np.roll(J, -1, axis=0) - J
        c = np.hypot(v[:, 0], v[:, 1])
        beta = np.mod(np.arctan2(v[:, 1], v[:, 0]) - th + np.pi, 2 * np.pi) - np.pi
        k = 2.0 * np.sin(beta) / c
        th_next = np.roll(th, -1)
        th_next[-1] += 2 * np.pi * self.w
        g = th_next - th - 2.0 * beta
        g = np.mod(g + np.pi, 2 * np.pi) - np.pi
        return v, c, beta, k, g


def _dpoint_dk(theta, k, sigma):
    """∂/∂k of the point at length σ along an arc leaving at direction θ with curvature k, (…, 2)."""
    x = 0.5 * k * sigma
    small = np.abs(x) < 1e-4
    xs = np.where(small, 1.0, x)
    s = np.where(small, 1.0 - x * x / 6.0, np.sin(xs) / xs)  # sinc
    ds = np.where(small, -x / 3.0 + x ** 3 / 30.0, (xs * np.cos(xs) - np.sin(xs)) / (xs * xs))
    psi = theta + x
    f = 0.5 * sigma * sigma
    return np.stack([f * (ds * np.cos(psi) - s * np.sin(psi)), f * (ds * np.sin(psi) + s * np.cos(psi))], -1)


class CurveTable:
    """The closed curve on [a, b] at ``rows`` + 1 even parameters from ``a`` (the last row is the first again)."""

    def __init__(self, curve, a, b, rows):
        self.n = rows
        self.t = a + np.mod(np.arange(rows + 1) * ((b - a) / rows), b - a)
        self.P = curve.evaluate(self.t, 0)

    def nearest(self, E, stride: int = 32):
        """Table row nearest each point E (n, 2): the nearest of every ``stride``-th row, then ±``stride`` rows
        about it (the same row as a search of the whole table for points near a curve that does not come
        back near itself within ``stride`` rows, as a cam's does not)."""
        coarse = np.arange(0, self.n, stride)
        d = self.P[coarse][None, :, :] - E[:, None, :]
        guess = coarse[np.argmin(np.einsum("ijk,ijk->ij", d, d), axis=1)]
        return self.project(E, guess, stride)

    def project(self, E, guess, window):
        """Table row nearest each point E (n, 2), searched within ``window`` rows of ``guess`` (n,), cyclic."""
        off = np.arange(-window, window + 1)
        rows = np.mod(guess[:, None] + off[None, :], self.n)
        d = self.P[rows] - E[:, None, :]
        return rows[np.arange(len(E)), np.argmin(np.einsum("ijk,ijk->ij", d, d), axis=1)]


def joint_rows(oc: "OnCurve", tab: "CurveTable") -> np.ndarray:
    """The joints' fractional table rows once round from the first, and the first's again + ``tab.n``: (k + 1,)."""
    rf = (oc.t - oc.a) / (oc.b - oc.a) * tab.n
    rf = rf[0] + np.mod(rf - rf[0], tab.n)
    return np.concatenate([rf, [rf[0] + tab.n]])


def sample_spacing(oc: "OnCurve", tab: "CurveTable", per_arc: int) -> int:
    """Table rows between samples: ``per_arc`` samples on an arc of the median span, every row at most."""
    a, b = oc.a, oc.b
    spans = np.mod(np.diff(np.concatenate([oc.t, oc.t[:1] + (b - a)])), b - a) / (b - a) * tab.n
    return max(1, int(float(np.median(spans)) / per_arc))


def chain_samples(oc: "OnCurve", tab: "CurveTable", spacing: int):
    """Every ``spacing``-th table row and the arc whose span holds it (the joints' parameters cut the turn).

    The rows are fixed along the curve: a joint that moves hands only the
    samples it passes over to its other arc, where (G1) their error is nearly
    the same, so the largest error changes smoothly with the joints.
    """
    rows = np.arange(0, tab.n, spacing)
    rf = (oc.t - oc.a) / (oc.b - oc.a) * tab.n
    r0 = rf[0]
    rel_j = np.mod(rf - r0, tab.n)
    rel_s = np.mod(rows - r0, tab.n)
    arc = np.searchsorted(rel_j, rel_s, side="right") - 1
    return rows, np.clip(arc, 0, len(rf) - 1)


def chain_errors(ch: Joints, tab: CurveTable, rows, arc):
    """The samples (table ``rows``) against their arcs (``arc``, one per row).

    Returns the errors e (m,), each sample's arc (m,), its length σ along the arc to its foot, the foot Q
    (m, 2), the arc's normal there n (m, 2), and the arcs' data (:meth:`Joints.arcs`).
    """
    arcs = ch.arcs()
    k_all = arcs[3]
    P = tab.P[rows]
    d = P - ch.J[arc]
    th = ch.theta[arc]
    T = np.stack([np.cos(th), np.sin(th)], -1)
    a = d[:, 1] * T[:, 0] - d[:, 0] * T[:, 1]  # d·N, N = (−T_y, T_x)
    b = np.einsum("ij,ij->i", d, T)
    k = k_all[arc]
    dd = np.einsum("ij,ij->i", d, d)
    e = (2 * a - k * dd) / (1.0 + np.sqrt(np.maximum(1.0 - 2 * a * k + k * k * dd, 0.0)))
    ang = np.arctan2(k * b, 1.0 - k * a)
    big = np.abs(k) > 1e-12
    sigma = np.where(big, ang / np.where(big, k, 1.0), b)
    phi = th + k * sigma
    nrm = np.stack([-np.sin(phi), np.cos(phi)], -1)
    Q = P - e[:, None] * nrm
    return e, arc, sigma, Q, nrm, arcs


def _jacobian(ch: Joints, e, arc, sigma, Q, nrm, arcs, frames):
    """Rows of the samples' errors and of the G1 residuals against (δu, δv, δθ) per joint: (m, 3n), (n, 3n).

    δu, δv move a joint along ``frames`` (T, N) (n, 2, 2): the curve's tangent and normal at its row.
    """
    n = len(ch.theta)
    v, c, beta, k, g = arcs
    perp = np.stack([-v[:, 1], v[:, 0]], -1) / (c * c)[:, None]  # ∂φ/∂J_{i+1}
    cb, sb = np.cos(beta), np.sin(beta)
    dk_dnext = (2 * cb / c)[:, None] * perp - (2 * sb / c ** 2)[:, None] * (v / c[:, None])
    dk_dth = -2 * cb / c
    m = len(e)
    rows = np.arange(m)
    nxt = (arc + 1) % n
    de_dk = -np.einsum("ij,ij->i", nrm, _dpoint_dk(ch.theta[arc], k[arc], sigma))
    rel = Q - ch.J[arc]
    de_dth = -(rel[:, 0] * nrm[:, 1] - rel[:, 1] * nrm[:, 0]) + de_dk * dk_dth[arc]
    de_dJ = -nrm - de_dk[:, None] * dk_dnext[arc]  # the start joint (directly, and through k)
    de_dJn = de_dk[:, None] * dk_dnext[arc]  # the end joint, through k
    T, N = frames[:, 0], frames[:, 1]
    Je = np.zeros((m, 3 * n))
    Je[rows, arc] = np.einsum("ij,ij->i", de_dJ, T[arc])
    Je[rows, n + arc] = np.einsum("ij,ij->i", de_dJ, N[arc])
    np.add.at(Je, (rows, nxt), np.einsum("ij,ij->i", de_dJn, T[nxt]))
    np.add.at(Je, (rows, n + nxt), np.einsum("ij,ij->i", de_dJn, N[nxt]))
    Je[rows, 2 * n + arc] = de_dth
    # G1: g = θ_{i+1} − θ_i − 2β, β = φ − θ_i
    Jg = np.zeros((n, 3 * n))
    i = np.arange(n)
    i1 = (i + 1) % n
    Jg[i, 2 * n + i1] += 1.0
    Jg[i, 2 * n + i] += 1.0
    dg_dnext = -2 * perp
    Jg[i, i1] += np.einsum("ij,ij->i", dg_dnext, T[i1])
    Jg[i, n + i1] += np.einsum("ij,ij->i", dg_dnext, N[i1])
    Jg[i, i] += np.einsum("ij,ij->i", -dg_dnext, T[i])
    Jg[i, n + i] += np.einsum("ij,ij->i", -dg_dnext, N[i])
    return Je, Jg


class OnCurve:
    """Joints in the curve's own coordinates: parameter t, offset v along the normal, turn ψ off the tangent.

    A joint sliding along the curve keeps its offset and its turn against
    the curve (J = P(t) + v N(t), θ = arg P′(t) + ψ): in these coordinates a
    step's effect is nearly linear (a slide along a fixed tangent would leave
    the curve by κ·u²/2 and turn against it by κu, both far more than δ).
    """

    def __init__(self, curve, a, b, *, t, v, psi, w):
        self.curve, self.a, self.b = curve, a, b
        self.t = a + np.mod(np.asarray(t, float) - a, b - a)
        self.v, self.psi, self.w = np.asarray(v, float), np.asarray(psi, float), int(w)
        d0, d1, d2 = derivatives(curve, self.t, 2, first=0)
        sp = np.hypot(d1[:, 0], d1[:, 1])
        self.speed = sp
        self.T = d1 / sp[:, None]
        self.N = np.stack([-self.T[:, 1], self.T[:, 0]], -1)
        self.kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / sp ** 3
        phi = np.unwrap(np.arctan2(self.T[:, 1], self.T[:, 0]))
        self.joints = Joints(d0 + self.v[:, None] * self.N, phi + self.psi, w)

    def moved(self, du, dv, dpsi):
        return OnCurve(self.curve, self.a, self.b, t=self.t + du / self.speed, v=self.v + dv, psi=self.psi + dpsi,
                       w=self.w)


def on_curve(curve, a, b, joints: Joints, t_guess) -> OnCurve:
    """The curve coordinates of joints (t by Newton on (P(t) − J)·P′(t) = 0 from ``t_guess``)."""
    t = np.asarray(t_guess, float).copy()
    J = joints.J
    for _ in range(6):
        d0, d1, d2 = derivatives(curve, t, 2, first=0)
        r = d0 - J
        g = np.einsum("ij,ij->i", r, d1)
        dg = np.einsum("ij,ij->i", d1, d1) + np.einsum("ij,ij->i", r, d2)
        t = t - g / dg
    d0, d1 = curve.evaluate(t, 0), curve.evaluate(t, 1)
    T = d1 / np.hypot(d1[:, 0], d1[:, 1])[:, None]
    v = (J[:, 1] - d0[:, 1]) * T[:, 0] - (J[:, 0] - d0[:, 0]) * T[:, 1]
    phi = np.arctan2(T[:, 1], T[:, 0])
    psi = np.mod(joints.theta - phi + np.pi, 2 * np.pi) - np.pi
    return OnCurve(curve, a, b, t=t, v=v, psi=psi, w=joints.w)


def step_jacobians(oc: OnCurve, res):
    """∂ of the samples' errors, G1 gaps and half turns by every joint's (δu, δv, δψ): (m, 3n), (n, 3n), (n, 3n).

    ``res`` is :func:`chain_errors` of ``oc.joints``.  Columns: the joints'
    slides along the curve (mm), offsets along its normal (mm), turns off its
    tangent (rad), as :meth:`OnCurve.moved` applies them: a slide moves the
    joint along the tangent and turns its direction with the curve's (κ per mm).
    """
    n = len(oc.t)
    # J = P(t) + v N(t): a slide du (t by du / speed) moves J by T (1 − κv) du (the offset curve's speed)
    fr = np.stack([oc.T * (1.0 - oc.kappa * oc.v)[:, None], oc.N], 1)
    Je, Jg = _jacobian(oc.joints, *res, fr)
    v, c, beta, k, g = res[5]
    # β = φ − θ: ∂β/∂θ_i = −1, ∂β/∂J_{i+1} = perp, ∂β/∂J_i = −perp
    i = np.arange(n)
    i1 = (i + 1) % n
    perp = np.stack([-v[:, 1], v[:, 0]], -1) / (c * c)[:, None]
    Jb = np.zeros((n, 3 * n))
    Jb[i, 2 * n + i] = -1.0
    Jb[i, i1] += np.einsum("ij,ij->i", perp, fr[i1, 0])
    Jb[i, n + i1] += np.einsum("ij,ij->i", perp, fr[i1, 1])
    Jb[i, i] -= np.einsum("ij,ij->i", perp, fr[i, 0])
    Jb[i, n + i] -= np.einsum("ij,ij->i", perp, fr[i, 1])
    # a slide along the curve turns the joint's direction with the curve's: column u += κ · column ψ
    for Jx in (Je, Jg, Jb):
        Jx[:, :n] += Jx[:, 2 * n:] * oc.kappa[None, :]
    return Je, Jg, Jb


def _solve_step(cost, lo, hi, Je, e, err, Jgc, gc, Jb, half, beta):
    """One SLP step's LP, its sample rows added as they bind (cutting planes).

    Rows: |e + Je·δ| ≤ t per sample, |gc + Jgc·δ| ≤ s per arc (the G1 gap
    × chord), |β + Jb·δ| ≤ half per arc (the sweep).  The samples start with
    those whose error is within 80 % of the largest; any other whose
    linearised error exceeds t at the solution is added and the LP solved
    again from its last basis (:class:`~camcam.optimize.lp.IncrementalLp`),
    until none does: the same optimum as with every sample, from a third of
    the rows or less.
    """
    from camcam.optimize.lp import IncrementalLp

    nv = len(cost)
    k = Je.shape[1]

    def rows(J, rhs, col):
        """J·δ − v_col ≤ rhs and −J·δ − v_col ≤ −rhs … as dense rows (two per row of J)."""
        A = np.zeros((2 * len(J), nv))
        A[0::2, :k], A[1::2, :k] = J, -J
        if col is not None:
            A[:, col] = -1.0
        return A, np.ravel(np.stack([rhs[0], rhs[1]], -1))

    # without presolve (the rows are already a small dense model: nothing for it to remove) and with Devex
    # pricing: on the 40 contours of benchmarks/run_nc.py --arcs (2026-12-07, issue 49) the contour fits took
    # 25.0 s against 27.9 s with HiGHS's defaults and printed 1002 blocks against 1004, each contour within
    # its bound either way; on the 55 LPs of the default disc at 0.001 mm replayed, 0.22 against 0.33 CPU s
    lp = IncrementalLp(cost, lo, hi, presolve=False, devex=True)
    A, b = rows(Jgc, (-gc, gc), nv - 1)
    lp.add_rows(A, b)
    A, b = rows(Jb, (half - beta, half + beta), None)
    lp.add_rows(A, b)
    taken = np.abs(e) >= 0.8 * err
    todo = np.flatnonzero(taken)
    while True:
        A, b = rows(Je[todo], (-e[todo], e[todo]), nv - 2)
        lp.add_rows(A, b)
        sol = lp.solve()
        if sol.status != "optimal":
            return sol
        lin = e.copy()
        for col in np.flatnonzero(sol.x[:k]).tolist():  # column by column: the same sums on every CPU
            lin += Je[:, col] * sol.x[col]
        lin = np.abs(lin)
        todo = np.flatnonzero(~taken & (lin > sol.x[-2] * (1.0 + 1e-9)))
        if not len(todo):
            return sol
        taken[todo] = True


def minimax_chain(start: OnCurve, tab: CurveTable, *, max_sweep: float, per_arc: int = 24,
                  iterations: int = 30, hopeless: float = math.inf, early: tuple[int, float] | None = None,
                  enough: float = 0.0) -> tuple[OnCurve, float, float]:
    """The G1 chain of ``len(start.t)`` arcs nearest the curve in the largest error, by SLP from ``start``.

    Parameters
    ----------
    start : OnCurve
        The first chain (G1 or not: the gap is driven to zero).
    tab : CurveTable
        The curve's table (from the section's start ``a``); samples are every
        few of its rows, ``per_arc`` on an arc of the median span.
    max_sweep : float
        Largest sweep of an arc (rad); an arc already wider is not widened.
    iterations : int
        LP steps at most; the loop ends sooner when a step gains less than
        1e-4 of the score or the trust region falls below 1e-9 mm.
    enough : float
        A step that leaves the chain within this error (mm), and G1 to 1e-3 of it, ends the loop: a caller
        that needs only that much spares the steps that would lower it further.
    hopeless : float
        After half the ``iterations`` a chain still over this error (mm) is
        given up (:func:`camcam.toolpath.arcpolish.fewer_arcs` passes 1.05 ×
        its target: on the 12 cases it was measured on, 45 optimisations, the
        error at half time was within 2 % of the final one).
    early : (int, float), optional
        (step, error in mm): a chain still over that error at that step, before half the ``iterations``,
        is given up too (:func:`camcam.toolpath.arcseed.seeded_chain` judges its seeds at step 8 as well).

    Returns
    -------
    (OnCurve, float, float)
        The chain, its largest sampled error (mm) and its largest G1 gap × chord (mm).

    Examples
    --------
    A circle of radius 10 mm: four arcs of its own radius fit it exactly.

    >>> from camcam.geometry.curve import FunctionCurve
    >>> def circle(t, k):
    ...     c, s = np.cos(t), np.sin(t)
    ...     return 10 * np.stack([[c, s], [-s, c], [-c, -s], [s, -c]][k], -1)
    >>> C = FunctionCurve(circle, 0.0, 2 * np.pi, closed=True)
    >>> tab = CurveTable(C, 0.0, 2 * np.pi, 4096)
    >>> t = np.array([0.1, 1.7, 3.3, 4.6])
    >>> start = OnCurve(C, 0.0, 2 * np.pi, t=t, v=np.full(4, 0.01), psi=np.array([0.002, -0.001, 0.0, 0.001]), w=1)
    >>> chain, err, gap = minimax_chain(start, tab, max_sweep=np.radians(120))
    >>> bool(err < 1e-6 and gap < 1e-9)
    True
    """
    n = len(start.t)
    oc = start
    spacing = sample_spacing(start, tab, per_arc)

    def merit(o):
        # a step that collapses an arc (two joints met: k = 2 sin β / |chord|) scores inf and is refused
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
            res = chain_errors(o.joints, tab, *chain_samples(o, tab, spacing))
        v, c, beta, k, g = res[5]
        err, gap = float(np.abs(res[0]).max()), float(np.abs(g * c).max())
        ok = math.isfinite(err + gap) and float(c.min()) > 1e-9
        return (err, gap, res) if ok else (math.inf, math.inf, res)

    mu = 10.0  # weight of the G1 gap against the error: an exact penalty (the gap goes to 0 first)
    err, gap, res = merit(oc)
    score = err + mu * gap
    if not math.isfinite(score):  # two joints on one point: no chain to step from
        return oc, err, gap
    R_v = max(err, 1e-6)
    R_u = 0.25
    nv = 3 * n + 2  # δu, δv, δψ per joint; t (largest error), s (largest G1 gap × chord)
    cost = np.zeros(nv)
    cost[-2], cost[-1] = 1.0, mu
    for step in range(iterations):
        if step == iterations // 2 and err > hopeless or early is not None and step == early[0] and err > early[1]:
            break
        e = res[0]
        Je, Jg, Jb = step_jacobians(oc, res)
        v, c, beta, k, g = res[5]
        Jgc = Jg * c[:, None]
        half = np.maximum(0.5 * max_sweep, np.abs(beta))  # never wider than now
        reach = R_u * np.minimum(c, np.roll(c, 1))
        lo = np.concatenate([-reach, np.full(n, -R_v), -4 * R_v / c, [0.0, 0.0]])
        hi = np.concatenate([reach, np.full(n, R_v), 4 * R_v / c, [np.inf, np.inf]])
        sol = _solve_step(cost, lo, hi, Je, e, err, Jgc, g * c, Jb, half, beta)
        if sol.status == "optimal":
            dx = sol.x
            trial = oc.moved(dx[:n], dx[n:2 * n], dx[2 * n:3 * n])
            t_err, t_gap, t_res = merit(trial)
            t_score = t_err + mu * t_gap
            predicted = float(dx[-2] + mu * dx[-1])
            # the ratio of the achieved to the predicted fall sets the next trust region
            rho = (score - t_score) / max(score - predicted, 1e-300)
            if t_score < score:
                done = score - t_score < 1e-4 * score or (t_err <= enough and t_gap <= 1e-3 * enough)
                oc, err, gap, res, score = trial, t_err, t_gap, t_res, t_score
                if rho > 0.75:
                    R_v, R_u = min(2 * R_v, max(err, 1e-6) * 4), min(2 * R_u, 0.5)
                elif rho < 0.25:
                    R_v, R_u = 0.5 * R_v, 0.5 * R_u
                if done:
                    break
                continue
        R_v *= 0.5
        R_u *= 0.5
        if R_v < 1e-9:
            break
    return oc, err, gap


def joints_of(elements) -> Joints:
    """The joints of a printed closed spline: each element's start and start direction."""
    J = np.array([e.start for e in elements], float)
    th = []
    for e in elements:
        t = element_tangent(e, False)
        th.append(math.atan2(t[1], t[0]))
    th = np.unwrap(np.array(th))
    # turning once round: the last element's end direction against the first's start
    t_end = element_tangent(elements[-1], True)
    total = th[-1] - th[0] + float(np.mod(math.atan2(t_end[1], t_end[0]) - th[-1] + np.pi, 2 * np.pi) - np.pi)
    return Joints(J, th, int(round(total / (2 * math.pi))))
