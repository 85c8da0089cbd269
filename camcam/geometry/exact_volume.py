"""A cam's volume from its exact curves, independent of any mesh or CAD kernel.

* disc cam: the area the exact profile encloses (Green's theorem, ½∮(x y′ − y x′) dθ, by
  adaptive quadrature per analytic piece) times the thickness, less the bore, its keyway
  (the rectangle outside the bore's circle) and the dowel hole;
* face-groove cam: the disc of the outside radius less the groove (the area between the
  exact flanks times the groove depth), the bore and its keyway;
* barrel cam: the cylinder less the bore and the groove; the groove's volume is
  ∫ r·|∮x₁ dφ − ∮x₀ dφ| dr over the groove's radii r (Gauss–Legendre), the band between the
  two walls on the cylinder of radius r, whose edges are the exact wall points on that
  cylinder (:meth:`~camcam.geometry.cylindrical.CylindricalCam.flank_on_surface`).

Examples
--------
>>> from camcam.geometry.params import Keyway
>>> round(keyway_area(12.0, Keyway(width=4.0, depth=1.8)), 3)  # DIN 6885 for a 12 mm shaft
7.652
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["enclosed_area", "keyway_area", "cam_volume", "disc_volume", "groove_volume", "barrel_volume"]


def enclosed_area(curve) -> float:
    """The area (mm², unsigned) a closed exact planar curve encloses."""
    from scipy.integrate import quad

    def integrand(t: float) -> float:
        (x, y), (dx, dy) = curve.evaluate([t], 0)[0], curve.evaluate([t], 1)[0]
        return 0.5 * (x * dy - y * dx)

    br = curve.breaks
    return abs(sum(quad(integrand, a, b, epsabs=1e-10, epsrel=1e-13, limit=400)[0] for a, b in zip(br, br[1:])))


def keyway_area(bore: float, keyway) -> float:
    """The keyway's area outside the bore's circle (mm²): its rectangle from the centre out, less the part of
    the bore's disc between its walls."""
    if keyway is None or bore <= 0:
        return 0.0
    r, h = bore / 2, keyway.width / 2
    far = r + keyway.depth  # the keyway's bottom, from the centre along its centre line
    in_bore = h * math.sqrt(r * r - h * h) + r * r * math.asin(h / r)
    return 2 * h * far - in_bore


def _holes_area(bore: float, keyway, dowel=None) -> float:
    area = math.pi * (bore / 2) ** 2 + keyway_area(bore, keyway)
    return area + (math.pi * (dowel.diameter / 2) ** 2 if dowel is not None else 0.0)


def disc_volume(cam, thickness: float, bore: float, keyway=None, dowel=None) -> float:
    """A disc cam's volume, mm³."""
    return (enclosed_area(cam.profile) - _holes_area(bore, keyway, dowel)) * thickness


def groove_volume(cam, thickness: float, bore: float, outer_radius: float, keyway=None) -> float:
    """A face-groove cam's volume, mm³."""
    groove = enclosed_area(cam.flanks[1]) - enclosed_area(cam.flanks[0])
    return (math.pi * outer_radius ** 2 - _holes_area(bore, keyway)) * thickness - groove * cam.groove_depth


#: Cam angles per analytic piece and Gauss–Legendre radii of the barrel groove's volume.
BARREL_POINTS_PER_PIECE, BARREL_RADII = 4000, 8


def _band_width_integral(cam, rho: float) -> float:
    """|∮x₁ dφ − ∮x₀ dφ| on the cylinder of radius ``rho``: the band between the walls' area over ``rho`` (mm)."""
    br = cam.breaks
    t = np.concatenate([np.linspace(a, b, BARREL_POINTS_PER_PIECE, endpoint=False) for a, b in zip(br, br[1:])])
    t = np.append(t, br[-1])
    total = []
    for side in (0, 1):
        p = cam.flank_on_surface(t, side, rho)
        phi = np.unwrap(np.arctan2(p[:, 2], p[:, 1]))
        total.append(np.trapezoid(p[:, 0], phi) if hasattr(np, "trapezoid") else np.trapz(p[:, 0], phi))
    return abs(total[1] - total[0])


def barrel_volume(cam) -> float:
    """A barrel cam's volume, mm³ (the groove's by the trapezoid rule in φ on each cylinder: its error falls
    with the square of :data:`BARREL_POINTS_PER_PIECE`)."""
    R, r_b, L = cam.base_radius, cam.bore / 2, cam.length
    x, w = np.polynomial.legendre.leggauss(BARREL_RADII)
    lo, hi = cam.bottom_radius, R
    rho = 0.5 * (hi - lo) * x + 0.5 * (hi + lo)
    groove = 0.5 * (hi - lo) * sum(wi * r * _band_width_integral(cam, r) for wi, r in zip(w, rho))
    return math.pi * (R * R - r_b * r_b) * L - groove


def cam_volume(built) -> float:
    """The volume of a :class:`~camcam.geometry.build.BuiltCam` (mm³)."""
    from camcam.geometry.build import groove_outer_radius

    c = built.spec
    if c.kind == "disc":
        return disc_volume(built.cam, c.thickness, c.bore, c.keyway, c.dowel)
    if c.kind == "disc-groove":
        return groove_volume(built.cam, c.thickness, c.bore, groove_outer_radius(built.cam, c), c.keyway)
    return barrel_volume(built.cam)
