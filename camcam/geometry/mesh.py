"""Watertight triangle meshes of the cams (trimesh), built from exact curve points.

Every surface is a band of quads between two closed rings of equally many
points (the rings' points lie on the exact cam surfaces).  The bands of a
solid form one cycle of rings (r0→r1→…→r0), each ring once first and once
second in a band, so shared edges match and run opposite ways: the mesh is
closed and consistently wound by construction; it is turned inside out if its
volume comes out negative.

* disc cam: the profile ring, extruded to ``thickness``, with a bore (and its keyway: the bore's ring is
  the bore-and-keyway outline, star-shaped about the centre, sampled at the profile ring's polar angles with
  the sample nearest each of the keyway's four corners moved onto it; with a dowel hole through it the top
  and bottom faces are GEOS's constrained Delaunay triangulation of the face with its holes, which uses
  the rings' own points only, so every edge still has its twin in a wall band);
* face-groove cam: a disc of ``outer_radius`` with the groove (between the two
  flanks) cut ``groove_depth`` deep into the top face;
* cylindrical cam: a cylinder with the groove cut, walls sampled on the exact
  cylinders r = ρ between the groove bottom and the surface.

A disc profile must be star-shaped about the cam centre (its polar angle
monotone), which every practical disc cam is; otherwise :class:`GeometryError`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from camcam.advice import largest_below_mm
from camcam.errors import GeometryError

if TYPE_CHECKING:
    import trimesh

__all__ = ["MeshParts", "disc_parts", "groove_parts", "cylinder_parts", "disc_mesh", "groove_mesh", "cylinder_mesh",
           "ring_points", "bore_outline", "keyway_corners"]

#: Points per analytic piece of a curve in the mesh rings.
POINTS_PER_PIECE = 180


def ring_points(curve, per_piece: int = POINTS_PER_PIECE) -> tuple[np.ndarray, np.ndarray]:
    """(parameters, points) of a closed curve: ``per_piece`` per analytic piece, the end once."""
    br = curve.breaks
    t = np.concatenate([np.linspace(a, b, per_piece, endpoint=False) for a, b in zip(br, br[1:])])
    return t, curve.evaluate(t)


def _polar(points: np.ndarray, what: str) -> np.ndarray:
    phi = np.unwrap(np.arctan2(points[:, 1], points[:, 0]))
    steps = np.diff(np.append(phi, phi[0] + (2 * math.pi if phi[-1] > phi[0] else -2 * math.pi)))
    if not (np.all(steps > 0) or np.all(steps < 0)):
        i = int(np.argmin(np.abs(steps)))
        raise GeometryError(f"the {what} is not star-shaped about the cam centre near point {i}; cannot mesh it")
    return phi


def _band(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Triangles joining index-matched closed rings of vertex indices a and b."""
    a2, b2 = np.roll(a, -1), np.roll(b, -1)
    return np.concatenate([np.stack([a, a2, b2], 1), np.stack([a, b2, b], 1)])


def _fan(ring: np.ndarray, centre: int, first: bool = True) -> np.ndarray:
    """Triangles closing a ring to a centre vertex; ``first``: the ring's edges run as in ``_band(ring, ·)``."""
    tri = np.stack([ring, np.roll(ring, -1), np.full_like(ring, centre)], 1)
    return tri if first else tri[:, ::-1]


#: Decimals of mm to which two vertices are one (trimesh's merge of the same, ``trimesh.tol.merge``).
MERGE_DECIMALS = 8


@dataclass(frozen=True, eq=False)
class MeshParts:
    """A cam's triangles: ``vertices`` (n, 3) mm, ``faces`` (m, 3) indices.

    numpy only: :meth:`closed` checks that they close a solid and winds them outward (what `camcam run`
    uses for the STL and the mesh figures); :meth:`solid` makes the watertight trimesh (and imports
    trimesh), the tests' independent view of the same triangles.
    """

    vertices: np.ndarray
    faces: np.ndarray

    @property
    def triangles(self) -> np.ndarray:
        """(m, 3, 3) the faces' corners, mm."""
        return self.vertices[self.faces]

    def crosses(self) -> np.ndarray:
        """(m, 3) each face's edge cross product (v1 − v0) × (v2 − v1): twice its area along its normal."""
        t = self.triangles
        return np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 1])

    def volume_mm3(self) -> float:
        """The signed volume the faces enclose (divergence theorem: Σ (c_x · Σ x) / 6 over the faces; trimesh's
        sum), positive when they are wound outward."""
        t = self.triangles
        return float(np.sum(self.crosses()[:, 0] * (t[:, 0, 0] + t[:, 1, 0] + t[:, 2, 0])) / 6.0)

    def closed(self) -> "MeshParts":
        """These triangles wound outward, once checked to close a solid: vertices that agree to
        :data:`MERGE_DECIMALS` are one, and then every directed edge occurs once and its reverse once
        (every edge between two faces, wound the same way), and the volume is positive.

        Raises
        ------
        GeometryError
            The triangles do not close a solid (a groove or profile that intersects itself).
        """
        key = np.round(self.vertices * 10.0 ** MERGE_DECIMALS)
        _, one = np.unique(key, axis=0, return_inverse=True)
        f = one.reshape(-1)[self.faces]
        a, b = f.reshape(-1), np.roll(f, -1, axis=1).reshape(-1)
        n = np.int64(len(self.vertices))
        edges, back = np.sort(a * n + b), np.sort(b * n + a)
        paired = len(edges) > 0 and bool(np.all(edges[1:] != edges[:-1])) and bool(np.array_equal(edges, back))
        parts = self if self.volume_mm3() >= 0 else MeshParts(self.vertices, self.faces[:, ::-1].copy())
        if not (paired and parts.volume_mm3() > 0):
            raise GeometryError("the cam mesh is not a closed solid (the groove or profile intersects itself)")
        return parts

    def moved(self, offset) -> "MeshParts":
        """The same triangles moved by ``offset`` (3,) mm."""
        return MeshParts(self.vertices + np.asarray(offset, dtype=float), self.faces)

    def solid(self) -> "trimesh.Trimesh":
        """The watertight, consistently wound trimesh with positive volume.

        Raises
        ------
        GeometryError
            The triangles do not close a solid (a groove or profile that intersects itself).
        """
        import trimesh

        m = trimesh.Trimesh(self.vertices, self.faces, process=True)
        if m.volume < 0:
            m.invert()
        if not (m.is_watertight and m.is_winding_consistent and m.volume > 0):
            raise GeometryError("the cam mesh is not a closed solid (the groove or profile intersects itself)")
        return m


class _Builder:
    def __init__(self) -> None:
        self.vertices: list[np.ndarray] = []
        self.faces: list[np.ndarray] = []
        self.count = 0

    def add(self, pts: np.ndarray) -> np.ndarray:
        pts = np.atleast_2d(pts)
        idx = np.arange(self.count, self.count + len(pts))
        self.vertices.append(pts)
        self.count += len(pts)
        return idx

    def parts(self) -> MeshParts:
        return MeshParts(np.concatenate(self.vertices), np.concatenate(self.faces))


def _xy(points: np.ndarray, z: float) -> np.ndarray:
    return np.column_stack([points, np.full(len(points), z)])


def _circle(radius: float, phi: np.ndarray) -> np.ndarray:
    return radius * np.column_stack([np.cos(phi), np.sin(phi)])


def keyway_corners(bore_r: float, keyway) -> np.ndarray:
    """The keyway's four corners (mm, drawing frame) in order round the bore: where its wall leaves the bore,
    its bottom's two corners, where its other wall meets the bore."""
    a = math.radians(keyway.angle_deg)
    u, v = np.array([math.cos(a), math.sin(a)]), np.array([-math.sin(a), math.cos(a)])
    h = keyway.width / 2
    s = math.sqrt(bore_r * bore_r - h * h)
    far = bore_r + keyway.depth
    return np.array([s * u - h * v, far * u - h * v, far * u + h * v, s * u + h * v])


def bore_outline(bore_r: float, phi: np.ndarray, keyway=None) -> np.ndarray:
    """Points of the bore (with ``keyway``: bore and keyway) at the polar angles ``phi``; a keyway's corners
    replace the samples nearest them (one sample each: :class:`GeometryError` when two share one)."""
    if keyway is None:
        return _circle(bore_r, phi)
    a = math.radians(keyway.angle_deg)
    th = np.angle(np.exp(1j * (phi - a)))  # relative to the keyway's centre line, in (−π, π]
    h = keyway.width / 2
    r = np.full(len(phi), bore_r)
    c, s = np.cos(th), np.abs(np.sin(th))
    inside = (c > 0) & (s * bore_r <= h)
    with np.errstate(divide="ignore"):
        r[inside] = np.minimum((bore_r + keyway.depth) / c[inside], np.where(s[inside] > 0, h / s[inside], np.inf))
    pts = r[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])
    corners = keyway_corners(bore_r, keyway)
    idx = [int(np.argmin(np.abs(np.angle(np.exp(1j * (phi - math.atan2(p[1], p[0]))))))) for p in corners]
    if len(set(idx)) < 4:
        raise GeometryError(f"cam.keyway: {keyway.width:g} mm is too narrow for the mesh's {len(phi)} points round "
                            f"the bore")
    pts[idx] = corners
    return pts


def _annulus_prism(b: _Builder, outer: np.ndarray, inner_r: float, phi: np.ndarray, z0: float, z1: float,
                   keyway=None) -> None:
    o0, o1 = b.add(_xy(outer, z0)), b.add(_xy(outer, z1))
    b.faces.append(_band(o0, o1))
    if inner_r > 0:
        hole = bore_outline(inner_r, phi, keyway)
        i0, i1 = b.add(_xy(hole, z0)), b.add(_xy(hole, z1))
        b.faces += [_band(o1, i1), _band(i1, i0), _band(i0, o0)]
    else:
        c0, c1 = b.add([0.0, 0.0, z0]), b.add([0.0, 0.0, z1])
        b.faces += [_fan(o0, c0[0], first=False), _fan(o1, c1[0])]


def _reach(bore: float, keyway) -> float:
    """The farthest the bore (and its keyway) reaches from the centre."""
    return bore / 2 if keyway is None else float(np.hypot(*keyway_corners(bore / 2, keyway).T).max())


#: Points round a dowel hole in the mesh.
DOWEL_POINTS = 72


def _faces_with_holes(b: _Builder, outer: np.ndarray, holes: list[np.ndarray], like: np.ndarray) -> None:
    """Top and bottom faces of a prism whose rings ``outer`` and ``holes`` (index arrays of b's vertices, a pair
    per ring: bottom, top) have their walls already: each face's triangles wound as ``like`` (a top-face triangle
    of the band convention) and the bottom's the other way.

    Both faces are the same polygon in XY: it is triangulated once (its top's rings), each triangle's corners
    found by their position in the rings, and those positions taken at each level."""
    import shapely
    from shapely.geometry import Polygon

    verts = np.concatenate(b.vertices)
    top = [outer[1]] + [h[1] for h in holes]
    rings = [verts[ids][:, :2] for ids in top]
    position = {tuple(p): k for k, p in enumerate(np.concatenate(rings))}  # a point twice: its last position
    poly = Polygon(rings[0], rings[1:])
    corners = np.array([[position[c] for c in g.exterior.coords[:3]]
                        for g in shapely.constrained_delaunay_triangles(poly).geoms])
    for level, sign in ((1, 1.0), (0, -1.0)):
        tris = np.concatenate([outer[level]] + [h[level] for h in holes])[corners]
        p = verts[tris][:, :, :2]
        u, v = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
        area = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
        want = sign * np.sign(like)
        b.faces.append(np.where((np.sign(area) == want)[:, None], tris, tris[:, ::-1]))


def _signed_top(outer: np.ndarray, inner: np.ndarray) -> float:
    """The XY winding of the band convention's first top-face triangle (o[0], o[1], i[1])."""
    (ux, uy), (vx, vy) = outer[1] - outer[0], inner[1] - outer[0]
    return float(ux * vy - uy * vx)


def _bore_misfit(bore: float, ring: np.ndarray, what: str) -> str:
    """The error of a bore that does not fit inside ``ring`` (n, 2): where the ring comes nearest the axis, and
    the largest bore on the 0.01 mm grid that fits (the same points, the same check)."""
    r = np.hypot(ring[:, 0], ring[:, 1])
    k = int(np.argmin(r))
    return (f"cam.bore: {bore:g} mm does not fit inside {what}, which comes within {r[k]:.3f} mm of the axis; "
            f"expected at most {largest_below_mm(2 * r[k]):g} mm")


def disc_parts(cam, thickness: float, bore: float, per_piece: int = POINTS_PER_PIECE, keyway=None,
               dowel=None) -> MeshParts:
    """The disc cam extruded from z = 0 to ``thickness`` with a bore of diameter ``bore`` (and its ``keyway``, a
    ``dowel`` hole through it)."""
    _, pts = ring_points(cam.profile, per_piece)
    phi = _polar(pts, "profile")
    if bore / 2 >= np.hypot(pts[:, 0], pts[:, 1]).min():
        raise GeometryError(_bore_misfit(bore, pts, "the profile"))
    if _reach(bore, keyway) >= np.hypot(pts[:, 0], pts[:, 1]).min():
        raise GeometryError(f"cam.keyway: it reaches radius {_reach(bore, keyway):.3g} mm, outside the profile")
    b = _Builder()
    if dowel is None:
        _annulus_prism(b, pts, bore / 2, phi, 0.0, thickness, keyway)
        return b.parts()
    cx, cy = dowel.centre
    r_d = dowel.diameter / 2
    turn = 1.0 if phi[-1] > phi[0] else -1.0  # the hole's ring runs round its centre as the bore's round the axis
    ring = np.column_stack([cx, cy]) + _circle(r_d, turn * np.linspace(0, 2 * math.pi, DOWEL_POINTS, endpoint=False))
    from shapely.geometry import Point, Polygon

    if not Polygon(pts).contains(Point(cx, cy).buffer(r_d)) or Point(cx, cy).distance(
            Polygon(bore_outline(bore / 2, phi, keyway) if bore > 0 else [(0, 0), (0, 0), (0, 0)])) <= r_d:
        raise GeometryError(f"cam.dowel: the Ø{dowel.diameter:g} mm hole at radius {dowel.radius:g} mm does not fit "
                            f"between the bore and the profile")
    o0, o1 = b.add(_xy(pts, 0.0)), b.add(_xy(pts, thickness))
    b.faces.append(_band(o0, o1))
    holes = []
    if bore > 0:
        hole = bore_outline(bore / 2, phi, keyway)
        i0, i1 = b.add(_xy(hole, 0.0)), b.add(_xy(hole, thickness))
        b.faces.append(_band(i1, i0))
        holes.append((i0, i1))
        like = _signed_top(pts, hole)
    else:
        like = _signed_top(pts, 0.5 * pts)
    d0, d1 = b.add(_xy(ring, 0.0)), b.add(_xy(ring, thickness))
    b.faces.append(_band(d1, d0))
    holes.append((d0, d1))
    _faces_with_holes(b, (o0, o1), holes, like)
    return b.parts()


def groove_parts(cam, thickness: float, bore: float, outer_radius: float, per_piece: int = POINTS_PER_PIECE,
                 keyway=None) -> MeshParts:
    """A face-groove cam: disc of ``outer_radius``, groove ``cam.groove_depth`` deep in the top face."""
    h = cam.groove_depth
    if not h < thickness:
        raise GeometryError(f"cam.groove_depth {h:g} mm must be smaller than the thickness {thickness:g} mm")
    _, inner = ring_points(cam.flanks[0], per_piece)
    _, outer = ring_points(cam.flanks[1], per_piece)
    pi, po = _polar(inner, "inner flank"), _polar(outer, "outer flank")
    if np.hypot(outer[:, 0], outer[:, 1]).max() >= outer_radius:
        raise GeometryError(f"cam.outer_radius {outer_radius:g} mm does not contain the groove")
    if bore / 2 >= np.hypot(inner[:, 0], inner[:, 1]).min():
        raise GeometryError(_bore_misfit(bore, inner, "the groove's inner flank"))
    if _reach(bore, keyway) >= np.hypot(inner[:, 0], inner[:, 1]).min():
        raise GeometryError(f"cam.keyway: it reaches radius {_reach(bore, keyway):.3g} mm, outside the groove's "
                            f"inner flank")
    zg = thickness - h
    b = _Builder()
    rim = _circle(outer_radius, po)
    c0, c1 = b.add(_xy(rim, 0.0)), b.add(_xy(rim, thickness))
    o_g, o_t = b.add(_xy(outer, zg)), b.add(_xy(outer, thickness))
    i_g, i_t = b.add(_xy(inner, zg)), b.add(_xy(inner, thickness))
    b.faces += [_band(c0, c1), _band(c1, o_t), _band(o_t, o_g), _band(o_g, i_g), _band(i_g, i_t)]
    if bore > 0:
        core = bore_outline(bore / 2, pi, keyway)
        h0, h1 = b.add(_xy(core, 0.0)), b.add(_xy(core, thickness))
        b.faces += [_band(i_t, h1), _band(h1, h0), _band(h0, c0)]
    else:
        top, bot = b.add([0.0, 0.0, thickness]), b.add([0.0, 0.0, 0.0])
        b.faces += [_fan(i_t, top[0]), _fan(c0, bot[0], first=False)]
    return b.parts()


def cylinder_parts(cam, per_piece: int = POINTS_PER_PIECE, levels: int = 6) -> MeshParts:
    """A :class:`~camcam.geometry.cylindrical.CylindricalCam` as a solid with its groove cut."""
    br = cam.breaks
    t = np.concatenate([np.linspace(a, b, per_piece, endpoint=False) for a, b in zip(br, br[1:])])
    radii = np.linspace(cam.bottom_radius, cam.base_radius, levels + 1)
    b = _Builder()
    walls = []
    for side in (0, 1):
        rings = [b.add(cam.flank_on_surface(t, side, r)) for r in radii]
        walls.append(rings)
        pairs = zip(rings, rings[1:]) if side == 0 else zip(rings[1:], rings)
        b.faces += [_band(r0, r1) for r0, r1 in pairs]
    b.faces.append(_band(walls[1][0], walls[0][0]))  # groove bottom
    R, L = cam.base_radius, cam.length
    ends = []
    for side, x in ((0, 0.0), (1, L)):
        top = np.concatenate(b.vertices)[walls[side][-1]]
        phi = np.unwrap(np.arctan2(top[:, 2], top[:, 1]))
        _check_monotone(phi, side)
        rim = b.add(np.column_stack([np.full(len(t), x), R * np.cos(phi), R * np.sin(phi)]))
        b.faces.append(_band(walls[side][-1], rim) if side == 0 else _band(rim, walls[side][-1]))
        if cam.bore > 0:
            hole = b.add(np.column_stack([np.full(len(t), x), cam.bore / 2 * np.cos(phi), cam.bore / 2 * np.sin(phi)]))
            b.faces.append(_band(rim, hole) if side == 0 else _band(hole, rim))
            ends.append(hole)
        else:
            c = b.add([x, 0.0, 0.0])
            b.faces.append(_fan(rim, c[0], first=side == 0))
    if cam.bore > 0:
        b.faces.append(_band(ends[0], ends[1]))
    return b.parts()


def disc_mesh(cam, thickness: float, bore: float, per_piece: int = POINTS_PER_PIECE) -> "trimesh.Trimesh":
    """:func:`disc_parts` as a solid."""
    return disc_parts(cam, thickness, bore, per_piece).solid()


def groove_mesh(cam, thickness: float, bore: float, outer_radius: float,
                per_piece: int = POINTS_PER_PIECE) -> "trimesh.Trimesh":
    """:func:`groove_parts` as a solid."""
    return groove_parts(cam, thickness, bore, outer_radius, per_piece).solid()


def cylinder_mesh(cam, per_piece: int = POINTS_PER_PIECE, levels: int = 6) -> "trimesh.Trimesh":
    """:func:`cylinder_parts` as a solid."""
    return cylinder_parts(cam, per_piece, levels).solid()


def _check_monotone(phi: np.ndarray, side: int) -> None:
    steps = np.diff(phi)
    if not (np.all(steps > 0) or np.all(steps < 0)):
        raise GeometryError(f"groove flank {side} folds over itself (pressure angle too large for the roller); cannot mesh it")
