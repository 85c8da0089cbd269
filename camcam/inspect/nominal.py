"""The exact nominal surface a measured point is compared with: nearest points by root finding.

Each model takes the full alignment vector ``u`` and returns, per measured point,
the signed normal deviation from the built cam's exact curve (+ material left,
− overcut), its derivative by each alignment parameter (the Jacobian the least
squares fit and its uncertainty use), the cam angle of the nearest nominal point
and that point with its normal.  Nothing is sampled into a polyline: a grid of
the exact curve only starts the root finding.

``DiscProfile`` (CMM points on a disc cam, ``u = (ψ, tx, ty)``)
    the aligned point q = R(ψ)·p + t; its foot θ solves (q − P(θ))·P′(θ) = 0
    by safeguarded Newton on the profile's exact jets; the deviation is
    (q − P)·N, N the unit normal away from the material.
``DialProfile`` (dial-indicator readings, ``u = (ψ, cx, cy, z0)``)
    a probe of tip radius r_p on a line through the dividing head's axis c
    (part frame) at cam angle θ + ψ: its centre lies on the profile offset by r_p,
    Q(t), where the line crosses it, cross(u, Q(t) − c) = 0 (Newton in t).  The
    nominal reading is h = (Q − c)·u; a reading off by e (after the fitted zero
    z0) is a normal deviation e·(N·u).
``BarrelWalls`` (points on the groove walls, ``u = (ψ, tx, ty, tz)``)
    q = Rx(ψ)·p + t; the wall is the exact surface S(θ, ρ) of program angle and
    roller cross-section (:meth:`~camcam.geometry.cylindrical.CylindricalCam.wall_point`);
    the foot (θ, ρ) minimises |q − S| (Gauss–Newton, derivatives of S by central
    differences); the deviation is −(q − S)·N, N the wall normal into the groove
    (a point inside the groove has had material cut away).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from camcam.errors import GeometryError

__all__ = ["Evaluation", "DiscProfile", "DialProfile", "BarrelWalls", "PARAMETERS"]

TWO_PI = 2.0 * math.pi
#: Grid of the exact curve that starts each nearest-point search (per revolution).
START_GRID = 1024
#: Newton stops when the nearest-point condition holds to this (mm).
FOOT_TOL = 1e-11
#: The same on a barrel's wall, whose derivatives are central differences (their rounding floor is ~1e-11 mm).
WALL_FOOT_TOL = 1e-9
MAX_STEPS = 50

#: Names of the full alignment vector of each model (the fit frees some of them, :mod:`camcam.inspect.alignment`).
PARAMETERS = {
    "cmm": ("rotation", "tx", "ty"),
    "dial": ("rotation", "cx", "cy", "zero"),
    "barrel": ("rotation", "tx", "ty", "tz"),
}


@dataclass(frozen=True, kw_only=True)
class Evaluation:
    """Per point: ``deviation`` (mm), ``jacobian`` (n, len(u)) of the deviation, ``angle`` (rad, [0, 2π)),
    ``foot`` (n, 2 or 3) the nearest nominal point, ``normal`` the unit direction a positive deviation
    points in (away from the material of a disc profile, into the wall of a groove), ``aligned`` the
    measured point in the design frame (for a dial, the profile point the probe touched)."""

    deviation: np.ndarray
    jacobian: np.ndarray
    angle: np.ndarray
    foot: np.ndarray
    normal: np.ndarray
    aligned: np.ndarray


def _rot(psi: float) -> np.ndarray:
    c, s = math.cos(psi), math.sin(psi)
    return np.array([[c, -s], [s, c]])


def _jets(curve, t, K: int) -> list[np.ndarray]:
    """[C(t), C′(t), …, C^(K)(t)] of a planar jet curve, each (n, 2)."""
    jx, jy = curve.jets(t, K)
    return [np.stack([jx.d[k], jy.d[k]], axis=-1) for k in range(K + 1)]


def _grid_start(grid_t: np.ndarray, grid_pts: np.ndarray, q: np.ndarray) -> np.ndarray:
    """The grid parameter nearest each point of ``q`` (in blocks: n × grid distances at most 4 M at a time)."""
    out = np.empty(len(q))
    block = max(1, 4_000_000 // len(grid_t))
    for a in range(0, len(q), block):
        d2 = ((q[a:a + block, None, :] - grid_pts[None, :, :]) ** 2).sum(axis=-1)
        out[a:a + block] = grid_t[np.argmin(d2, axis=1)]
    return out


class DiscProfile:
    """A disc cam's exact profile (module docstring)."""

    kind = "cmm"

    def __init__(self, cam) -> None:
        self.cam = cam
        self.curve = cam.profile
        self.grid_t = np.linspace(0.0, TWO_PI, START_GRID, endpoint=False)
        self.grid_pts = self.curve.evaluate(self.grid_t)
        self.step = TWO_PI / START_GRID

    def foot(self, q: np.ndarray) -> np.ndarray:
        """Program angle θ (rad) of the profile point nearest each q (n, 2)."""
        t = _grid_start(self.grid_t, self.grid_pts, q)
        lo, hi = t - self.step, t + self.step
        act = np.arange(len(q))  # the points still moving (a converged one stays where it is)
        for _ in range(MAX_STEPS):
            ta = t[act]
            P, d1, d2 = _jets(self.curve, ta, 2)
            r = q[act] - P
            f = np.einsum("ij,ij->i", r, d1)
            sp2 = np.einsum("ij,ij->i", d1, d1)
            fp = -sp2 + np.einsum("ij,ij->i", r, d2)
            moving = np.abs(f) > FOOT_TOL * np.sqrt(sp2)
            act, ta, f, sp2, fp = act[moving], ta[moving], f[moving], sp2[moving], fp[moving]
            if not act.size:
                break
            # f > 0: the nearest point lies ahead; keep the bracket [lo, hi] and fall back to its middle
            lo[act] = np.where(f > 0, ta, lo[act])
            hi[act] = np.where(f < 0, ta, hi[act])
            step = np.where(fp < 0, -f / np.where(fp < 0, fp, 1.0), f / sp2)
            new = ta + step
            t[act] = np.where((new >= lo[act]) & (new <= hi[act]), new, 0.5 * (lo[act] + hi[act]))
        return np.mod(t, TWO_PI)

    def evaluate(self, u, points: np.ndarray) -> Evaluation:
        psi, tx, ty = u
        q = points @ _rot(psi).T + np.array([tx, ty])
        t = self.foot(q)
        S = self.curve.evaluate(t)
        N = self.cam.normal(t)
        dev = np.einsum("ij,ij->i", q - S, N)
        qr = q - np.array([tx, ty])
        jac = np.stack([N[:, 1] * qr[:, 0] - N[:, 0] * qr[:, 1], N[:, 0], N[:, 1]], axis=-1)  # N·(J qr), N·I
        return Evaluation(deviation=dev, jacobian=jac, angle=t, foot=S, normal=N, aligned=q)


class DialProfile:
    """Dial-indicator readings on a disc cam (module docstring).  ``values`` (n, 2): angle (deg), reading (mm)."""

    kind = "dial"

    def __init__(self, cam, probe_radius: float) -> None:
        self.cam = cam
        self.probe_radius = float(probe_radius)
        self.curve = cam.offset_profile(self.probe_radius)
        self.sigma = cam.sigma
        self.grid_t = np.linspace(0.0, TWO_PI, START_GRID, endpoint=False)
        self.grid_pts = self.curve.evaluate(self.grid_t)

    def _direction(self, theta: np.ndarray) -> np.ndarray:
        """The probe's line in the part frame at cam angle θ: R(−σθ)·(0, 1)."""
        a = -self.sigma * theta
        return np.stack([-np.sin(a), np.cos(a)], axis=-1)

    def contact(self, theta: np.ndarray, c: np.ndarray) -> np.ndarray:
        """Parameter t of the offset curve where the probe line at cam angle θ through c meets it."""
        u = self._direction(theta)
        rel = self.grid_pts[None, :, :] - c[None, None, :]
        cosang = (rel[..., 0] * u[:, None, 0] + rel[..., 1] * u[:, None, 1]) / np.hypot(rel[..., 0], rel[..., 1])
        t = self.grid_t[np.argmax(cosang, axis=1)]
        for _ in range(MAX_STEPS):
            Q, d1 = _jets(self.curve, t, 1)
            g = u[:, 0] * (Q[:, 1] - c[1]) - u[:, 1] * (Q[:, 0] - c[0])
            gp = u[:, 0] * d1[:, 1] - u[:, 1] * d1[:, 0]
            if np.all(np.abs(g) <= FOOT_TOL):
                break
            t = t - np.clip(g / np.where(gp == 0, 1e-300, gp), -0.05, 0.05)
        return np.mod(t, TWO_PI)

    def evaluate(self, u, values: np.ndarray) -> Evaluation:
        psi, cx, cy, z0 = u
        c = np.array([cx, cy])
        theta = np.radians(values[:, 0]) + psi
        t = self.contact(theta, c)
        Q = self.curve.evaluate(t)
        N = self.cam.normal(t)
        ud = self._direction(theta)
        h = np.einsum("ij,ij->i", Q - c, ud)
        cos = np.einsum("ij,ij->i", N, ud)
        if np.any(cos <= 0.05):
            i = int(np.argmin(cos))
            raise GeometryError(f"reading {i + 1}: the probe meets the profile at {math.degrees(math.acos(max(-1.0, min(1.0, cos[i])))):.1f}° "
                                "from its normal; a radial probe cannot read this cam there")
        dev = (values[:, 1] + z0 - h) * cos
        du = -self.sigma * np.stack([-ud[:, 1], ud[:, 0]], axis=-1)  # d u / dψ = −σ J u
        jac = np.stack([h * np.einsum("ij,ij->i", du, N), N[:, 0], N[:, 1], cos], axis=-1)
        P = Q - self.probe_radius * N  # the profile point the probe touches
        return Evaluation(deviation=dev, jacobian=jac, angle=t, foot=P, normal=N, aligned=P + dev[:, None] * N)


class BarrelWalls:
    """The two walls of a barrel cam's groove (module docstring).  The points are (n, 4): x, y, z and the
    wall (0 or 1), chosen by :meth:`assign` once and kept while the alignment moves the points."""

    kind = "barrel"
    H_THETA = 1e-6
    H_RHO = 1e-5

    def __init__(self, cam) -> None:
        self.cam = cam
        self.grid_t = np.linspace(0.0, TWO_PI, START_GRID // 4, endpoint=False)
        rho = 0.5 * (cam.base_radius + cam.bottom_radius)
        self.grid = [cam.wall_point(self.grid_t, rho, w) for w in (0, 1)]

    def _surface(self, t, rho, walls):
        out = np.empty((len(t), 3))
        for w in (0, 1):
            m = walls == w
            if m.any():
                out[m] = self.cam.wall_point(t[m], rho[m], w)
        return out

    def _derivatives(self, t, rho, walls):
        ht, hr = self.H_THETA, self.H_RHO
        St = (self._surface(t + ht, rho, walls) - self._surface(t - ht, rho, walls)) / (2 * ht)
        Sr = (self._surface(t, rho + hr, walls) - self._surface(t, rho - hr, walls)) / (2 * hr)
        return St, Sr

    def foot(self, q: np.ndarray, walls: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(θ, ρ) of the wall point nearest each q on its wall (Gauss–Newton from the grid)."""
        t = np.empty(len(q))
        for w in (0, 1):
            m = walls == w
            if m.any():
                t[m] = _grid_start(self.grid_t, self.grid[w], q[m])
        rho = np.hypot(q[:, 1], q[:, 2])
        act = np.arange(len(q))  # the points still moving
        for _ in range(MAX_STEPS):
            ta, ra, wa = t[act], rho[act], walls[act]
            S = self._surface(ta, ra, wa)
            St, Sr = self._derivatives(ta, ra, wa)
            r = q[act] - S
            a11, a12, a22 = (np.einsum("ij,ij->i", St, St), np.einsum("ij,ij->i", St, Sr), np.einsum("ij,ij->i", Sr, Sr))
            b1, b2 = np.einsum("ij,ij->i", St, r), np.einsum("ij,ij->i", Sr, r)
            moving = (np.abs(b1) > WALL_FOOT_TOL * np.sqrt(a11)) | (np.abs(b2) > WALL_FOOT_TOL * np.sqrt(a22))
            if not moving.any():
                break
            act, a11, a12, a22, b1, b2 = act[moving], a11[moving], a12[moving], a22[moving], b1[moving], b2[moving]
            det = a11 * a22 - a12 * a12
            t[act] += np.clip((a22 * b1 - a12 * b2) / det, -0.05, 0.05)
            rho[act] += np.clip((a11 * b2 - a12 * b1) / det, -1.0, 1.0)
        return np.mod(t, TWO_PI), rho

    def surface(self, t, rho, walls) -> tuple[np.ndarray, np.ndarray]:
        """Wall points S(θ, ρ) (n, 3) on ``walls`` and the unit normal into the groove there."""
        t, rho, walls = (np.asarray(v, dtype=float) for v in (t, rho, walls))
        S = self._surface(t, rho, walls)
        St, Sr = self._derivatives(t, rho, walls)
        N = np.cross(St, Sr)
        N /= np.linalg.norm(N, axis=1)[:, None]
        into = np.where(walls == 0, 1.0, -1.0)  # wall 0 is the −X side: the groove lies towards +X
        return S, N * np.where(N[:, 0] * into < 0, -1.0, 1.0)[:, None]

    def _evaluate(self, q: np.ndarray, walls: np.ndarray):
        t, rho = self.foot(q, walls)
        S, N = self.surface(t, rho, walls)
        return t, S, N, -np.einsum("ij,ij->i", q - S, N)

    def assign(self, points: np.ndarray) -> np.ndarray:
        """The wall each point lies nearer to (0: −X side, 1: +X side), from the points as given."""
        n = len(points)
        d = [np.abs(self._evaluate(points, np.full(n, w))[3]) for w in (0, 1)]
        return np.where(d[0] <= d[1], 0, 1)

    def evaluate(self, u, points: np.ndarray) -> Evaluation:
        psi, tx, ty, tz = u
        c, s = math.cos(psi), math.sin(psi)
        R = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
        t3 = np.array([tx, ty, tz])
        q = points[:, :3] @ R.T + t3
        walls = points[:, 3].astype(int)
        t, S, N, dev = self._evaluate(q, walls)
        qr = q - t3
        ex_q = np.stack([np.zeros(len(q)), -qr[:, 2], qr[:, 1]], axis=-1)  # e_x × q
        jac = -np.concatenate([np.einsum("ij,ij->i", N, ex_q)[:, None], N], axis=1)
        return Evaluation(deviation=dev, jacobian=jac, angle=t, foot=S, normal=-N, aligned=q)
