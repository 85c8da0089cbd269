"""The part as measured against the design: alignment, deviation, outliers, verdict and the motion it makes.

:func:`inspect_part` takes the built cam, its spec tables and a
:class:`~camcam.inspect.measured.MeasuredPart` and returns a frozen
:class:`Inspection`:

1. the measured kind is matched to the cam (CMM points and dial readings on a
   disc cam, wall points on a barrel cam); bore points, when given, move the
   CMM points to the bore's centre first;
2. the alignment (:mod:`camcam.inspect.alignment`) is fitted robustly with the
   loss scale at the tolerance; the deviations along the cam angle then go
   through seed 004's bad-point test (:func:`camcam.lifttable.badpoints.find_bad_points`,
   the deviation as the "lift" of a periodic table, per wall on a barrel);
   the points it flags are outliers, left out of the fit and the verdict and
   listed; the fit is repeated without them with the loss scale at 3 × the
   test's noise estimate, until the outliers no longer change (at most
   :data:`MAX_ROUNDS` rounds);
3. a fitted rotation above ``max_rotation_deg`` is refused (an
   :class:`~camcam.errors.InputError` naming it), and so is a part the best fit
   leaves more than :data:`ANOTHER_CAM_FACTOR` × the tolerance from the design
   (median |deviation|: points from another cam, or the wrong spec);
4. verdict: PASS when every kept point is within ±tolerance, else FAIL naming
   the worst point;
5. the aligned points (for a dial, the profile points the probe touched) go
   through seed 002's reverse design (:func:`camcam.reverse.reverse_design`),
   and the recovered lift, velocity and acceleration are compared with the
   design (:func:`camcam.reverse.compare.motion_errors`).  When the reverse fit
   cannot run on the points, the reason is kept (``motion_note``), never hidden.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from camcam.errors import CamcamError, InputError
from camcam.geometry.cylindrical import CylindricalCam
from camcam.geometry.disc import DiscCam
from camcam.inspect.alignment import MODES, Alignment, fit_alignment
from camcam.inspect.measured import MeasuredPart, bore_centre
from camcam.inspect.nominal import BarrelWalls, DialProfile, DiscProfile
from camcam.lifttable.badpoints import DEFAULT_THRESHOLD, find_bad_points
from camcam.lifttable.table import LiftTable
from camcam.reverse.compare import motion_errors
from camcam.reverse.design import ReverseOptions, reverse_design
from camcam.reverse.points import MIN_POINTS as REVERSE_MIN_POINTS
from camcam.reverse.points import MeasuredPoints

__all__ = ["InspectOptions", "Outlier", "MotionCheck", "Inspection", "inspect_part", "ANOTHER_CAM_FACTOR",
           "MAX_ROUNDS", "WORST_COUNT"]

#: A part whose median |deviation| after the best fit exceeds this many tolerances is not this cam.
ANOTHER_CAM_FACTOR = 10.0
#: Most rounds of fit → outliers → fit.
MAX_ROUNDS = 4
#: Points listed as the worst.
WORST_COUNT = 10
#: The loss scale never goes below this (mm): a tenth of a micrometre, below any CMM's noise.
MIN_LOSS_SCALE = 1e-4
#: Output angles of the recovered motion (every 0.5°).
MOTION_STEPS = 720
#: √(1 + Σw²) of the cubic through two neighbours each side on even spacing (seed 004's g: √(70/36)).
EVEN_GAIN = math.sqrt(70.0 / 36.0)
#: Largest cam-angle gap in the points for the outlier test to treat them as a whole revolution, degrees.
PERIODIC_GAP_DEG = 30.0


@dataclass(frozen=True, kw_only=True)
class InspectOptions:
    """``align``: none, rotation (default) or rigid; ``max_rotation_deg``: a larger fitted rotation is refused;
    ``tolerance_mm``: the ± band of the verdict; ``probe_radius_mm``: a dial's tip radius; ``bore``: bore
    points that locate a CMM part's centre; ``threshold``: the bad-point test's k (seed 004); ``motion``:
    whether to recover the motion the part makes."""

    tolerance_mm: float
    align: str = "rotation"
    max_rotation_deg: float = 2.0
    probe_radius_mm: float | None = None
    bore: MeasuredPart | None = None
    threshold: float = DEFAULT_THRESHOLD
    motion: bool = True  # False: no reverse fit (the deviation alone; a few seconds less)


@dataclass(frozen=True, kw_only=True)
class Outlier:
    """A point the bad-point test flagged: its file row, cam angle, deviation and score (r/(g·σ̂), seed 004)."""

    row: int
    angle_deg: float
    deviation_mm: float
    score: float


@dataclass(frozen=True, kw_only=True)
class MotionCheck:
    """The motion the measured cam produces against the design (``camcam reverse``'s figures), with the
    recovered and design columns (lift, velocity/deg, acceleration/deg²) at ``angles_deg``; per wall on a
    barrel (``wall`` 0 or 1, None on a disc)."""

    wall: int | None
    angles_deg: np.ndarray
    recovered: np.ndarray
    design: np.ndarray
    errors: dict
    unit: str


@dataclass(frozen=True, kw_only=True)
class Inspection:
    """Everything about the measured part, per point in file order (``angle_deg``, ``deviation_mm``, ``wall``,
    ``outlier`` mask) and as figures."""

    kind: str
    source: str
    rows: tuple[int, ...]
    tolerance_mm: float
    alignment: Alignment
    angle_deg: np.ndarray
    deviation_mm: np.ndarray
    wall: np.ndarray | None
    outlier: np.ndarray
    outliers: tuple[Outlier, ...]
    noise_sigma_mm: float
    bore: dict | None
    motion: tuple[MotionCheck, ...]
    motion_note: str | None
    notes: tuple[str, ...] = field(default=())

    @property
    def kept(self) -> np.ndarray:
        return ~self.outlier

    @property
    def worst_index(self) -> int:
        """File-order index of the kept point of largest |deviation|."""
        idx = np.flatnonzero(self.kept)
        return int(idx[np.argmax(np.abs(self.deviation_mm[idx]))])

    @property
    def max_deviation_mm(self) -> float:
        return float(self.deviation_mm[self.kept].max())

    @property
    def min_deviation_mm(self) -> float:
        return float(self.deviation_mm[self.kept].min())

    @property
    def passed(self) -> bool:
        return bool(np.all(np.abs(self.deviation_mm[self.kept]) <= self.tolerance_mm))

    @property
    def verdict(self) -> str:
        return "PASS" if self.passed else "FAIL"

    def worst(self, count: int = WORST_COUNT) -> list[int]:
        """File-order indices of the ``count`` kept points of largest |deviation|, worst first."""
        idx = np.flatnonzero(self.kept)
        return [int(i) for i in idx[np.argsort(-np.abs(self.deviation_mm[idx]), kind="stable")[:count]]]

    def worst_line(self) -> str:
        """One line naming the worst point: its row, angle, deviation and the tolerance."""
        i = self.worst_index
        wall = f", wall {int(self.wall[i])}" if self.wall is not None else ""
        return (f"{self.verdict}: worst point {self.source} row {self.rows[i]} at cam angle {self.angle_deg[i]:.2f}°{wall}: "
                f"deviation {self.deviation_mm[i]:+.4f} mm, tolerance ±{self.tolerance_mm:g} mm")

    @property
    def max_acceleration_error(self) -> float | None:
        if not self.motion:
            return None
        return max(m.errors["max_acceleration_error"] for m in self.motion)


def _model(built, part: MeasuredPart, options: InspectOptions):
    cam = built.cam
    if part.kind == "barrel":
        if not isinstance(cam, CylindricalCam):
            raise InputError(f"{part.source}: groove wall points (x, y, z) need a cylindrical cam; the spec's cam is "
                             f"{built.spec.kind}")
        return BarrelWalls(cam)
    if not isinstance(cam, DiscCam):
        raise InputError(f"{part.source}: {part.kind} measurements need a disc cam (cam.kind = \"disc\"); the spec's "
                         f"cam is {built.spec.kind}" + ("; measure a barrel's groove walls as x, y, z points"
                                                         if isinstance(cam, CylindricalCam) else ""))
    if part.kind == "dial":
        if options.probe_radius_mm is None or not options.probe_radius_mm >= 0:
            raise InputError("--probe-radius: a dial-indicator table needs the probe's tip radius in mm (>= 0)")
        return DialProfile(cam, options.probe_radius_mm)
    return DiscProfile(cam)


def _outliers(angle_deg: np.ndarray, dev: np.ndarray, index: np.ndarray, threshold: float):
    """Seed 004's bad-point test on (cam angle, deviation) of the points ``index``: (flagged indices, scores, σ̂)."""
    order = np.argsort(angle_deg[index], kind="stable")
    idx = index[order]
    a, d = angle_deg[idx].copy(), dev[idx]
    keep = np.concatenate([[True], np.diff(a) > 1e-9])  # two points at one cam angle: the test takes the first
    idx, a, d = idx[keep], a[keep], d[keep]
    if len(a) < 6:
        return [], [], 0.0
    gaps = np.diff(np.concatenate([a, [a[0] + 360.0]]))
    periodic = gaps.max() <= PERIODIC_GAP_DEG
    if periodic:
        a, d = np.append(a, a[0] + 360.0), np.append(d, d[0])
    rows = tuple(int(i) + 1 for i in idx) + ((int(idx[0]) + 1,) if periodic else ())
    rep = find_bad_points(LiftTable(tuple(a), tuple(d), "deviation", rows=rows), threshold=threshold)
    # the test removes points one at a time and never takes one back: beside two neighbouring outliers a good
    # point can score higher than the second outlier and go first.  A point whose deviation agrees with the
    # cubic through its kept neighbours (the test's own re-interpolation, rep.table) is taken back.
    at = {r: k for k, r in enumerate(rows[:len(idx)])}
    bad = [p for p in rep.points
           if abs(d[at[p.row]] - rep.table.y[at[p.row]]) > max(threshold * EVEN_GAIN * rep.noise_sigma, rep.min_size)]
    return [p.row - 1 for p in bad], [p.score for p in bad], rep.noise_sigma


def _data(part: MeasuredPart, options: InspectOptions, model) -> tuple[np.ndarray, dict | None]:
    if part.kind != "cmm" or options.bore is None:
        return part.values.copy(), None
    bc = bore_centre(options.bore)
    bore = {"centre_mm": [float(v) for v in bc.centre], "centre_sigma_mm": [float(v) for v in bc.centre_sigma],
            "radius_mm": bc.radius, "rms_mm": bc.rms_mm, "points": len(options.bore)}
    return part.values - bc.centre, bore


def inspect_part(built, cam_spec, follower_spec, program, part: MeasuredPart, options: InspectOptions) -> Inspection:
    """Inspect ``part`` against ``built`` (module docstring); ``cam_spec``/``follower_spec``/``program`` are
    the spec's tables the reverse fit and the design motion need."""
    if options.align not in MODES:
        raise InputError(f"--align: unknown alignment {options.align!r}; known: {', '.join(MODES)}")
    if not options.tolerance_mm > 0:
        raise InputError(f"inspection.tolerance: expected mm > 0, got {options.tolerance_mm:g}")
    model = _model(built, part, options)
    data, bore = _data(part, options, model)
    n = len(part)
    u = np.zeros(4 if part.kind != "cmm" else 3)
    if part.kind == "barrel":
        data = np.concatenate([data, model.assign(data)[:, None]], axis=1)
    if part.kind == "dial":
        e0 = model.evaluate(u, data)
        u[3] = -float(np.median(e0.deviation / e0.jacobian[:, 3]))
    outlier = np.zeros(n, dtype=bool)
    scale = options.tolerance_mm
    found: dict[int, float] = {}
    sigma_noise = 0.0
    for _ in range(MAX_ROUNDS):
        al = fit_alignment(model, data, options.align, ~outlier, scale, u)
        u = al.u
        ev = model.evaluate(u, data)
        ang = np.degrees(ev.angle)
        groups = [np.arange(n)] if part.kind != "barrel" else [np.flatnonzero(data[:, 3] == w) for w in (0, 1)]
        new = np.zeros(n, dtype=bool)
        found, sig = {}, []
        for g in groups:
            bad, scores, s = _outliers(ang, ev.deviation, g, options.threshold)
            new[bad] = True
            found.update(zip(bad, scores))
            if len(g) >= 6:
                sig.append(s)
        sigma_noise = float(max(sig)) if sig else 0.0
        scale = max(3.0 * sigma_noise, MIN_LOSS_SCALE)
        if np.array_equal(new, outlier):
            break
        outlier = new
    if n - int(outlier.sum()) < 6:
        raise InputError(f"{part.source}: only {n - int(outlier.sum())} points are left after the outliers")
    kept = ~outlier
    dev = ev.deviation
    med = float(np.median(np.abs(dev[kept])))
    if med > ANOTHER_CAM_FACTOR * options.tolerance_mm:
        raise InputError(f"{part.source}: the best fit leaves the points {med:.4f} mm (median) from the design, more than "
                         f"{ANOTHER_CAM_FACTOR:g} × the tolerance {options.tolerance_mm:g} mm: these points are not from "
                         "this cam (check the spec, the file and the frame)")
    if abs(al.rotation_deg) > options.max_rotation_deg:
        raise InputError(f"--max-rotation: the fitted rotation is {al.rotation_deg:+.3f}° (more than "
                         f"{options.max_rotation_deg:g}°): check the part's angular datum, or allow it with --max-rotation")
    outs = tuple(Outlier(row=part.rows[i], angle_deg=float(ang[i]), deviation_mm=float(dev[i]), score=float(found[i]))
                 for i in sorted(found, key=lambda j: ang[j]))
    motion, note = _motion(model, part, data, ev, kept, cam_spec, follower_spec, program) if options.motion else ((), None)
    return Inspection(kind=part.kind, source=part.source, rows=part.rows, tolerance_mm=options.tolerance_mm,
                      alignment=al, angle_deg=ang, deviation_mm=dev,
                      wall=data[:, 3].astype(int) if part.kind == "barrel" else None, outlier=outlier,
                      outliers=outs, noise_sigma_mm=sigma_noise, bore=bore, motion=motion, motion_note=note)


def _motion(model, part, data, ev, kept, cam_spec, follower_spec, program):
    """Seed 002's reverse fit of the aligned points, per wall on a barrel, against the design.

    Barrel points are measured at any depth; seed 002's slopes come from neighbouring points, so each is
    carried to the wall's reference cross-section (:attr:`CylindricalCam.reference_radius`, where the
    roller's middle runs) at its cam angle, with its deviation."""
    walls = [None] if part.kind != "barrel" else [0, 1]
    out, notes = [], []
    for w in walls:
        sel = kept if w is None else kept & (data[:, 3] == w)
        rows = tuple(part.rows[i] for i in np.flatnonzero(sel))
        if len(rows) < REVERSE_MIN_POINTS:
            notes.append(f"wall {w}: {len(rows)} points, the reverse fit needs {REVERSE_MIN_POINTS}")
            continue
        xyz = ev.aligned[sel]
        if w is not None:
            k = int(sel.sum())
            S, n_in = model.surface(ev.angle[sel], np.full(k, model.cam.reference_radius), np.full(k, w))
            xyz = S - ev.deviation[sel][:, None] * n_in
        pts = MeasuredPoints(xyz, rows, part.source)
        try:
            res = reverse_design(pts, cam_spec, follower_spec, ReverseOptions(smoothing=True, flank=w or 0))
        except CamcamError as err:
            notes.append(("" if w is None else f"wall {w}: ") + str(err))
            continue
        ang = np.arange(MOTION_STEPS) * (360.0 / MOTION_STEPS)
        rec = np.stack([res.motion(ang, k) for k in range(3)], axis=-1)
        design, errors = motion_errors(ang, rec, program, cam_spec.kind)
        out.append(MotionCheck(wall=w, angles_deg=ang, recovered=rec, design=design, errors=errors, unit=res.unit))
    note = "; ".join(notes) if notes else None
    if note is not None:
        note = "the motion of the measured cam could not be recovered: " + note
    return tuple(out), note
