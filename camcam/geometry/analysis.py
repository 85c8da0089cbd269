"""What a designer checks before cutting a disc cam, each with the cam angle where it occurs.

* pressure angle: its largest |value|;
* radius of curvature of the pitch curve and of the profile: the smallest on
  the convex part, and the concave parts as cam-angle ranges;
* undercut / cusp: :func:`check_undercut` raises :class:`GeometryError` naming
  the angle and the smallest base radius that avoids it;
* face width of a flat-faced follower.

Curvature is taken *convex-positive*: κc = −σ·κ, κ the signed curvature of
:mod:`camcam.geometry.curve` (a "ccw" cam's curves run clockwise).  Angles are
program cam angles in degrees.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from camcam.advice import smallest_above_mm
from camcam.errors import GeometryError
from camcam.geometry.extrema import extreme, negative_ranges
from camcam.geometry.jet import hypot

__all__ = ["AngleValue", "CurvatureSummary", "FaceWidth", "DiscAnalysis", "analyse", "max_pressure_angle", "undercut_margin", "convex_curvature", "flat_radius", "check_undercut",
           "smallest_base_radius_without_undercut", "analyse_cylindrical", "radius_text"]


@dataclass(frozen=True)
class AngleValue:
    value: float
    angle_deg: float


def radius_text(radius_mm: float | None, at_deg: float | None, decimals: int = 3) -> str:
    """A smallest radius of curvature as printed: with its cam angle, or "infinite" for a straight profile.

    A profile with no curvature (a dwell-only barrel's developed flanks) has no smallest finite
    radius and no place where it occurs; ``None`` stands for that in the report's dicts.

    Examples
    --------
    >>> radius_text(12.3456, 37.5)
    '12.346 mm at 37.50°'
    >>> radius_text(math.inf, 0.0)
    'infinite (straight: no curvature)'
    """
    if radius_mm is None or not math.isfinite(radius_mm):
        return "infinite (straight: no curvature)"
    return f"{radius_mm:.{decimals}f} mm" + (f" at {at_deg:.2f}°" if at_deg is not None else "")


@dataclass(frozen=True)
class CurvatureSummary:
    """Smallest radius of curvature on the convex part, and the concave ranges (degrees).

    ``min_radius_mm`` is ``math.inf`` where the curve is straight throughout; ``angle_deg`` then
    names no particular place (:attr:`at_deg` is None).
    """

    min_radius_mm: float
    angle_deg: float
    concave_deg: tuple[tuple[float, float], ...]
    min_concave_radius: AngleValue | None

    @property
    def at_deg(self) -> float | None:
        """Where the smallest radius occurs, None on a straight curve (no smallest finite radius)."""
        return self.angle_deg if math.isfinite(self.min_radius_mm) else None

    def describe(self, decimals: int = 3) -> str:
        """``"12.346 mm at 37.50°"``, or ``"infinite (straight: no curvature)"``."""
        return radius_text(self.min_radius_mm, self.at_deg, decimals)


@dataclass(frozen=True)
class FaceWidth:
    """Contact positions along a flat face (mm from the stem axis or the pivot) and their span."""

    min_mm: AngleValue
    max_mm: AngleValue

    @property
    def width_mm(self) -> float:
        return self.max_mm.value - self.min_mm.value


@dataclass(frozen=True)
class DiscAnalysis:
    max_pressure_angle_deg: AngleValue  # value is |φ|max in degrees
    pitch: CurvatureSummary | None
    profile: CurvatureSummary
    face: FaceWidth | None


def convex_curvature(curve, sigma: int, t, piece: int | None = None):
    """(κc, dκc/dθ) of a cam curve at program angles t (convex-positive, 1/mm)."""
    x, y = curve.jets(t, 3, piece)
    x1, y1 = x.derivative(), y.derivative()
    x2, y2 = x1.derivative(), y1.derivative()
    v = hypot(x1, y1).truncate(1)
    k = (x1.truncate(1) * y2 - y1.truncate(1) * x2) / (v * v * v) * (-sigma)
    return k.d[0], k.d[1]


def flat_radius(cam, t, piece: int | None = None):
    """(ρ, dρ/dθ): signed radius of curvature of a flat-faced profile, convex-positive, mm.

    A flat face's profile is the envelope of its lines; where ρ < 0 the envelope
    folds into a swallowtail with cusps, which the signed curvature of the
    traced curve cannot show (it stays positive).  So ρ is taken against the
    face normal n: c′ = ρ·ψ′·Jn with ψ′ = n × n′ the normal's turning rate.
    For a translating flat face ρ = R_b + s + s″.
    """
    x, y = cam.profile.jets(t, 2, piece)
    nx, ny = cam._normal_jets(np.atleast_1d(np.asarray(t, float)), 2, piece)
    x1, y1 = x.derivative(), y.derivative()
    n1x, n1y = nx.derivative(), ny.derivative()
    nx1, ny1 = nx.truncate(1), ny.truncate(1)
    rho = (y1 * nx1 - x1 * ny1) / (nx1 * n1y - ny1 * n1x)
    return rho.d[0], rho.d[1]


def flat_summary(cam) -> CurvatureSummary:
    br = cam.breaks
    f = lambda t, i: flat_radius(cam, t, i)  # noqa: E731
    low = extreme(f, br, "min", cam.inner_breaks)
    concave = negative_ranges(lambda t, i: f(t, i)[0], br)
    spans = tuple((_deg(a) if a >= 0 else math.degrees(a), math.degrees(b)) for a, b in concave)
    worst = AngleValue(abs(low.value), _deg(low.t)) if concave else None
    return CurvatureSummary(low.value if low.value > 0 else 0.0, _deg(low.t), spans, worst)


def _deg(t: float) -> float:
    return math.degrees(t) % 360.0


def curvature_summary(curve, sigma: int, breaks, inner=None) -> CurvatureSummary:
    f = lambda t, i: convex_curvature(curve, sigma, t, i)  # noqa: E731
    top = extreme(f, breaks, "max", inner)
    concave = negative_ranges(lambda t, i: f(t, i)[0], breaks)
    low = None
    if concave:
        c = extreme(f, breaks, "min", inner)
        low = AngleValue(1.0 / abs(c.value), _deg(c.t))
    rad = 1.0 / top.value if top.value > 0 else math.inf
    spans = tuple((_deg(a) if a >= 0 else math.degrees(a), math.degrees(b)) for a, b in concave)
    return CurvatureSummary(rad, _deg(top.t), spans, low)


def max_pressure_angle(cam) -> AngleValue:
    """Largest |pressure angle| in degrees and the program angle where it occurs."""

    def pa(t, i):
        j = cam.pressure_angle(t, 1, i)
        return j.d[0], j.d[1]

    p = extreme(pa, cam.breaks, "absmax", cam.inner_breaks)
    return AngleValue(abs(math.degrees(p.value)), _deg(p.t))


def analyse(cam) -> DiscAnalysis:
    """All analyses of a :class:`DiscCam` or :class:`GrooveCam`."""
    br = cam.breaks
    pressure = max_pressure_angle(cam)
    inner = cam.inner_breaks
    pitch = curvature_summary(cam.pitch, cam.sigma, br, inner) if cam.pitch is not None else None
    profile = curvature_summary(cam.profile, cam.sigma, br, inner) if cam.pitch is not None else flat_summary(cam)
    face = None
    if getattr(cam, "is_roller", True) is False:

        def fp(t, i):
            j = cam.face_position(t, 1, i)
            return j.d[0], j.d[1]

        lo, hi = extreme(fp, br, "min", inner), extreme(fp, br, "max", inner)
        face = FaceWidth(AngleValue(lo.value, _deg(lo.t)), AngleValue(hi.value, _deg(hi.t)))
    return DiscAnalysis(pressure, pitch, profile, face)


# -- undercut -----------------------------------------------------------------
def undercut_margin(cam) -> tuple[float, float]:
    """(margin, angle): margin ≤ 0 means undercut or cusp at that program angle (rad)."""
    br = cam.breaks
    sg = cam.sigma
    if cam.pitch is not None:
        curve = cam.pitch
        f = lambda t, i: convex_curvature(curve, sg, t, i)  # noqa: E731
        grooved = hasattr(cam, "flanks")
        c = extreme(f, br, "absmax" if grooved else "max", cam.inner_breaks)
        return 1.0 - cam.roller_radius * abs(c.value) if grooved else 1.0 - cam.roller_radius * c.value, c.t
    c = extreme(lambda t, i: flat_radius(cam, t, i), br, "min", cam.inner_breaks)
    return c.value, c.t


def _with_base(cam, base_radius: float):
    if hasattr(cam, "flanks"):
        return replace(cam, cam=replace(cam.cam, base_radius=base_radius))
    return replace(cam, base_radius=base_radius)


def smallest_base_radius_without_undercut(cam) -> float:
    """The smallest base radius (mm, rounded up to 0.01) at which ``cam`` has no undercut or cusp."""

    def m(r):
        try:
            return undercut_margin(_with_base(cam, r))[0]
        except GeometryError:
            return -1.0

    lo, hi = cam.base_radius, cam.base_radius
    while m(hi) <= 0:
        lo, hi = hi, hi * 2.0
        if hi > 1e5:
            raise GeometryError("no base radius up to 100 m avoids the undercut; the motion is too steep for this follower")
    from scipy.optimize import brentq  # only sizing asks this: a run need not import scipy.optimize

    r = brentq(m, lo, hi, xtol=1e-6) if m(lo) < 0 else lo
    return smallest_above_mm(r)


def _too_steep(cam, angle_deg: float, what: str) -> str:
    """The error of an undercut or cusp no base radius avoids: the segment of the motion it is in, named as the
    spec names it, and what would avoid it (campaign seed 50: five oscillating flat-faced followers, whose cusp
    a larger base radius moves but never removes, and a larger pivot distance deepens, were told only "the
    motion is too steep for this follower")."""
    field, g = cam.program.spec_field(math.radians(angle_deg))
    kind = getattr(cam.follower, "kind", "this")
    if field == "motion.lift_table":
        return (f"{field}: {what} at cam angle {angle_deg:.2f}°, and no base radius up to 100 m avoids "
                f"it: the lift is too steep there for this {kind} follower; expected a gentler lift about that angle")
    unit = "°" if cam.program.unit == "deg" else " mm"
    return (f"{field}: {what} at cam angle {angle_deg:.2f}° in its {g.law.name} from {g.start_deg:g}° "
            f"to {g.end_deg:g}° (rise {g.scale:g}{unit}), and no base radius up to 100 m avoids it: the motion is too "
            f"steep there for this {kind} follower; expected a longer segment or a smaller rise")


def check_undercut(cam) -> None:
    """Raise :class:`GeometryError` if the profile (or a groove flank) has an undercut or a cusp."""
    margin, t = undercut_margin(cam)
    if margin > 0:
        return
    ang = _deg(t)
    try:
        fix = smallest_base_radius_without_undercut(cam)
    except GeometryError:
        raise GeometryError(_too_steep(cam, ang, "cusp" if cam.pitch is None else "undercut")) from None
    if cam.pitch is not None:
        k = convex_curvature(cam.pitch, cam.sigma, np.array([t]))[0][0]
        where = "the pitch curve's radius of curvature" + (" (concave)" if k < 0 else "")
        raise GeometryError(
            f"undercut at cam angle {ang:.2f}°: {where} there is {1 / abs(k):.3f} mm, not larger than the roller "
            f"radius {cam.roller_radius:g} mm; cam.base_radius >= {fix:.2f} mm avoids it"
        )
    raise GeometryError(
        f"cusp at cam angle {ang:.2f}°: the flat-faced profile's radius of curvature there is "
        f"{margin:.3f} mm (it must stay positive); cam.base_radius >= {fix:.2f} mm avoids it"
    )


# -- cylindrical cams ----------------------------------------------------------
def _groove_bend(cam) -> tuple[float, float]:
    """(radius, program angle rad) of the sharpest bend of the developed groove centre line at the groove
    bottom (infinite for a straight one)."""
    centre = cam.developed_centre(cam.bottom_radius)
    c = extreme(lambda t, i: convex_curvature(centre, 1, t, i), cam.breaks, "absmax", cam.inner_breaks)
    return (1.0 / abs(c.value) if c.value else math.inf), c.t


def analyse_cylindrical(cam) -> DiscAnalysis:
    """Pressure angle at the groove bottom (its largest) and the developed groove's curvature there.

    ``profile.min_radius_mm`` is the smallest radius of curvature of the developed
    flanks at the groove bottom on their convex side: that of the developed centre
    line minus the roller radius.  Raises :class:`GeometryError` if the roller
    does not fit the groove's bends (centre-line radius ≤ roller radius).
    """
    pressure = max_pressure_angle(cam)
    rho, t = _groove_bend(cam)
    if rho <= cam.roller_radius:
        from camcam.geometry.resize import base_radius_advice, base_radius_meeting

        # measured on the cam rebuilt at that radius (an oscillating roller's pivot moved out with it)
        fix = base_radius_meeting(cam, lambda c: _groove_bend(c)[0] - c.roller_radius - 1e-9)
        way = f"{base_radius_advice(cam, fix)} avoids it" if fix is not None else \
            "no cam.base_radius up to 10 m avoids it; the motion is too steep for this follower"
        raise GeometryError(
            f"undercut at cam angle {_deg(t):.2f}°: the developed groove centre line bends with radius {rho:.3f} mm "
            f"at the groove bottom, not larger than the roller radius {cam.roller_radius:g} mm; {way}"
        )
    summary = CurvatureSummary(rho - cam.roller_radius, _deg(t), (), None)
    return DiscAnalysis(pressure, CurvatureSummary(rho, _deg(t), (), None), summary, None)
