"""The setup sheet's first picture: the part on the machine, as inline SVG.

Drawn from the same geometry the program, the DXF and the STL come from, in
the program's frame, so that the machinist sees where the work zero is before
reading a number:

* a disc cam (or a grooved disc): the top view (the blank, the finished part,
  the bore with its keyway, the dowel hole, the cam-angle-0 line and X0 Y0)
  beside the side view seen from the front of the machine (−Y): the blank, the
  part below Z0, Z0 on the top face, and the tool at the deepest pass with its
  holder where the spec gives one;
* a barrel cam: the side view on the rotary axis (the cylinder from X0 on its
  left end face, the groove's visible half, the A axis and the chuck) beside the
  end view seen from +X (the bore and the A0 mark: cam angle 0 at the top).

It is SVG written here, not a matplotlib plot: a few hundred lines of text,
no rendering process and no raster (it prints sharp on the A4 sheet).  The
scale is the same for both views of a picture (stated in its caption), and
every length drawn is a length of the part.

Examples
--------
>>> svg = Canvas(200.0, 100.0)
>>> svg.line([(0.0, 0.0), (10.0, 0.0)], "part")
>>> svg.text(5.0, 5.0, "X0 <Y0>")
>>> out = svg.svg()
>>> out.startswith('<svg xmlns="http://www.w3.org/2000/svg"'), "X0 &lt;Y0&gt;" in out
(True, True)
"""

from __future__ import annotations

import html
import math
from dataclasses import dataclass

import numpy as np

__all__ = ["SetupPicture", "setup_picture", "Canvas"]

#: The picture's size in CSS pixels (96 per inch): 170 × 53 mm printed, the width of the A4 sheet's text.
WIDTH_PX, HEIGHT_PX = 640.0, 200.0
#: Room round each view for its labels (px).
MARGIN_PX = 22.0
#: Room right of the last view for a label such as "T1 Ø16" (px at 11 px type).
LABEL_ROOM_PX = 40.0
#: Stroke and fill of each kind of line drawn (class name → SVG style).
STYLE = ("text{font:11px sans-serif;fill:#1b1b1b}.blank{fill:#e9e4d8;stroke:#8a7f66;stroke-width:1}"
         ".part{fill:#b9cde3;stroke:#1f4e79;stroke-width:1.4}.cut{fill:#ffffff;stroke:#1f4e79;stroke-width:1.2}"
         ".groove{fill:none;stroke:#1f4e79;stroke-width:1}.datum{fill:none;stroke:#c0392b;stroke-width:1.2}"
         ".zero{fill:none;stroke:#c0392b;stroke-width:1.2;stroke-dasharray:5 3}"
         ".axis{fill:none;stroke:#555;stroke-width:.8;stroke-dasharray:8 2 2 2}"
         ".tool{fill:#d0d0d0;stroke:#333;stroke-width:1}.holder{fill:#9a9a9a;stroke:#333;stroke-width:1}"
         ".chuck{fill:#cfcfcf;stroke:#333;stroke-width:1}")


@dataclass(frozen=True)
class SetupPicture:
    """The picture as SVG text and its caption."""

    svg: str
    caption: str


class Canvas:
    """SVG in picture pixels; shapes are given in pixels (y down), :class:`View` maps millimetres to them."""

    def __init__(self, width_px: float, height_px: float) -> None:
        self.width_px, self.height_px = width_px, height_px
        self._items: list[str] = []
        self.px_per_mm: float | None = None  # set by the views: written on the svg element (data-px-per-mm)

    def line(self, points, kind: str, closed: bool = False) -> None:
        """A polyline (or polygon with ``closed``) through ``points`` (px), drawn as ``kind`` (a STYLE class)."""
        pts = " ".join(f"{x:.2f},{y:.2f}" for x, y in points)
        tag = "polygon" if closed else "polyline"
        self._items.append(f'<{tag} class="{kind}" points="{pts}"/>')

    def path(self, rings, kind: str) -> None:
        """A filled outline with holes: ``rings`` a list of closed point lists (px), even-odd filled."""
        d = " ".join("M" + " L".join(f"{x:.2f},{y:.2f}" for x, y in ring) + " Z" for ring in rings)
        self._items.append(f'<path class="{kind}" fill-rule="evenodd" d="{d}"/>')

    def text(self, x: float, y: float, text: str, anchor: str = "start") -> None:
        self._items.append(f'<text x="{x:.1f}" y="{y:.1f}" text-anchor="{anchor}">{html.escape(text)}</text>')

    def svg(self) -> str:
        return (f'<svg xmlns="http://www.w3.org/2000/svg" width="{self.width_px:g}" height="{self.height_px:g}" '
                f'viewBox="0 0 {self.width_px:g} {self.height_px:g}" role="img"'
                + (f' data-px-per-mm="{self.px_per_mm!r}"' if self.px_per_mm is not None else "") + ">"
                f"<style>{STYLE}</style>" + "".join(self._items) + "</svg>")


@dataclass(frozen=True, kw_only=True)
class View:
    """Millimetres (a view's horizontal and vertical axes, vertical up) to picture pixels at ``scale`` px/mm."""

    left_px: float
    top_px: float
    u_min: float
    v_max: float
    scale: float

    def px(self, points) -> np.ndarray:
        p = np.asarray(points, dtype=float).reshape(-1, 2)
        return np.column_stack([self.left_px + (p[:, 0] - self.u_min) * self.scale,
                                self.top_px + (self.v_max - p[:, 1]) * self.scale])


def _views(canvas: Canvas, boxes) -> tuple[list[View], float]:
    """Side-by-side views of the model boxes ``(u0, u1, v0, v1)`` (mm) at one scale that fits them all."""
    gap = MARGIN_PX
    room_w = canvas.width_px - gap * (len(boxes) + 1)
    room_h = canvas.height_px - 2 * gap
    width = sum(u1 - u0 for u0, u1, _, _ in boxes)
    scale = min(room_w / width, min(room_h / (v1 - v0) for _, _, v0, v1 in boxes))
    views, left = [], gap
    for u0, u1, v0, v1 in boxes:
        top = gap + (room_h - (v1 - v0) * scale) / 2
        views.append(View(left_px=left, top_px=top, u_min=u0, v_max=v1, scale=scale))
        left += (u1 - u0) * scale + gap
    canvas.px_per_mm = float(scale)
    # no empty room on the right when the height sets the scale, but room for the last view's labels (the tool's)
    canvas.width_px = round(left + LABEL_ROOM_PX, 1)
    return views, scale


def _rings(polygon) -> list[np.ndarray]:
    """Every ring (exterior and holes) of a shapely Polygon or MultiPolygon, as (n, 2) arrays (mm)."""
    geoms = getattr(polygon, "geoms", [polygon])
    return [np.asarray(r.coords)[:, :2] for g in geoms for r in (g.exterior, *g.interiors)]


def _scale_text(scale: float) -> str:
    return f"scale 1 : {96 / 25.4 / scale:.3g} on screen at 96 px per inch"


def _disc(built, r, machining) -> SetupPicture:
    from camcam.geometry.mesh import bore_outline

    spec, cam = built.spec, built.cam
    profile = cam.profile.polyline()
    blank = r.blank
    region = _rings(blank.region) if blank is not None else [profile]
    lo = np.min([ring.min(axis=0) for ring in region], axis=0)
    hi = np.max([ring.max(axis=0) for ring in region], axis=0)
    top_z = blank.top_z_mm if blank is not None else 0.0
    deepest = min((p.z for p in r.toolpath.passes), default=-spec.thickness)
    d = r.tool_diameter_mm
    tool_x0 = hi[0] + 0.3 * d
    holder = machining.holder_diameter_mm if machining.stick_out_mm is not None else 0.0
    stick = machining.stick_out_mm if machining.stick_out_mm is not None else max(2.5 * d, spec.thickness + 5.0)
    tool_top = deepest + stick
    side_hi = max(top_z, tool_top) + (0.25 * stick if holder else 0.0)
    canvas = Canvas(WIDTH_PX, HEIGHT_PX)
    (top, side), scale = _views(canvas, [(lo[0], hi[0], lo[1], hi[1]),
                                         (lo[0], tool_x0 + max(d, holder or 0.0), -spec.thickness,
                                          side_hi)])
    # top view: the blank, the part (or the groove it leaves), the bore, keyway and dowel
    canvas.path([top.px(ring) for ring in region], "blank")
    if blank is not None and blank.groove:
        canvas.path([top.px(ring) for ring in _rings(blank.part)], "cut")
    else:
        canvas.path([top.px(profile)], "part")
    if spec.bore:
        phi = np.linspace(0.0, 2 * math.pi, 361)[:-1]
        canvas.line(top.px(bore_outline(spec.bore / 2, phi, spec.keyway)), "cut", closed=True)
    if spec.dowel is not None:
        a = math.radians(spec.dowel.angle_deg)
        c = spec.dowel.radius * np.array([math.cos(a), math.sin(a)])
        phi = np.linspace(0.0, 2 * math.pi, 73)[:-1]
        canvas.line(top.px(c + spec.dowel.diameter / 2 * np.column_stack([np.cos(phi), np.sin(phi)])), "cut",
                    closed=True)
    p0 = cam.profile.evaluate(np.array([cam.profile.t_start]))[0]
    canvas.line(top.px([(0.0, 0.0), p0]), "datum")
    q = top.px(p0)[0]
    canvas.text(q[0] + 3, q[1] - 3, "cam angle 0")
    _origin(canvas, top, "X", "Y", "X0 Y0")
    # side view from the front (−Y): blank, part below Z0, the tool at the deepest pass
    canvas.line(side.px([(lo[0], -spec.thickness), (hi[0], -spec.thickness), (hi[0], top_z), (lo[0], top_z)]),
                "blank", closed=True)
    pl, ph = profile[:, 0].min(), profile[:, 0].max()
    if blank is not None and blank.groove:
        pl, ph = lo[0], hi[0]
    canvas.line(side.px([(pl, -spec.thickness), (ph, -spec.thickness), (ph, 0.0), (pl, 0.0)]), "part", closed=True)
    canvas.line(side.px([(tool_x0, deepest), (tool_x0 + d, deepest), (tool_x0 + d, tool_top), (tool_x0, tool_top)]),
                "tool", closed=True)
    if holder:
        hd = holder
        cx = tool_x0 + d / 2
        canvas.line(side.px([(cx - hd / 2, tool_top), (cx + hd / 2, tool_top), (cx + hd / 2, side_hi),
                             (cx - hd / 2, side_hi)]), "holder", closed=True)
    t = side.px([(tool_x0 + d, (deepest + tool_top) / 2)])[0]
    canvas.text(t[0] + 3, t[1], f"T{r.toolpath.tool_number} Ø{d:g}")
    z0 = side.px([(lo[0] - 2.0 / scale * 8, 0.0), (hi[0], 0.0)])
    canvas.line(z0, "zero")
    canvas.text(z0[0][0], z0[0][1] - 3, "Z0")
    _origin(canvas, side, "X", "Z", "")
    what = "grooved disc" if blank is not None and blank.groove else "cam"
    caption = (f"The part on the machine: top view (left) and side view from the front (right) of the blank, the "
               f"{what}, its bore and datum; X0 Y0 on the cam axis, Z0 on the top face, the cam-angle-0 line in "
               f"red, the tool at the deepest pass (Z{deepest:g}); {_scale_text(scale)}.")
    return SetupPicture(canvas.svg(), caption)


def _barrel(built, r) -> SetupPicture:
    spec, cam = built.spec, built.cam
    R, L = cam.base_radius, cam.length
    chuck = 0.25 * L
    canvas = Canvas(WIDTH_PX, HEIGHT_PX)
    (side, end), scale = _views(canvas, [(-chuck, L + 0.1 * L, -1.15 * R, 1.15 * R), (-1.15 * R, 1.15 * R,
                                                                                       -1.15 * R, 1.15 * R)])
    # side view from the front (−Y): chuck, cylinder, the groove's front half, the A axis
    canvas.line(side.px([(-chuck, -1.1 * R), (0.0, -1.1 * R), (0.0, 1.1 * R), (-chuck, 1.1 * R)]), "chuck",
                closed=True)
    canvas.line(side.px([(0.0, -R), (L, -R), (L, R), (0.0, R)]), "part", closed=True)
    for index in (0, 1):
        p = cam.flank(index, R).polyline()
        front = p[:, 1] < 0.0  # the half the viewer at −Y sees
        for run in np.split(np.arange(len(p)), np.nonzero(np.diff(front.astype(int)))[0] + 1):
            if front[run[0]] and len(run) > 1:
                canvas.line(side.px(p[run][:, [0, 2]]), "groove")
    canvas.line(side.px([(-chuck, 0.0), (L + 0.1 * L, 0.0)]), "axis")
    a = side.px([(L + 0.1 * L, 0.0)])[0]
    canvas.text(a[0], a[1] - 4, "A axis", anchor="end")
    _origin(canvas, side, "X", "Z", "X0 (left end face)")
    # end view from +X: the cylinder, the bore, A0 (cam angle 0: the groove centre at the top, +Z)
    phi = np.linspace(0.0, 2 * math.pi, 181)[:-1]
    ring = np.column_stack([np.cos(phi), np.sin(phi)])
    canvas.path([end.px(R * ring)] + ([end.px(spec.bore / 2 * ring)] if spec.bore else []), "part")
    # seen from +X, +Y points left and +Z up
    canvas.line(end.px([(0.0, 0.0), (0.0, R)]), "datum")
    m = end.px([(0.0, R)])[0]
    canvas.text(m[0] + 4, m[1] - 4, "A0: cam angle 0")
    _origin(canvas, end, "−Y", "Z", "Y0 Z0")
    caption = (f"The part on the machine: side view from the front (left) with the chuck, the groove's front half "
               f"and the A axis, and end view from +X (right) with the bore and A0 (cam angle 0 at the top, +Z); X0 "
               f"on the left end face, Y0 Z0 on the cam axis; {_scale_text(scale)}.")
    return SetupPicture(canvas.svg(), caption)


def _origin(canvas: Canvas, view: View, u_name: str, v_name: str, label: str) -> None:
    """Two short red arrows at the view's origin, named."""
    o = view.px([(0.0, 0.0)])[0]
    canvas.line([(o[0], o[1]), (o[0] + 24, o[1])], "datum")
    canvas.line([(o[0], o[1]), (o[0], o[1] - 24)], "datum")
    canvas.text(o[0] + 26, o[1] + 4, u_name)
    canvas.text(o[0] - 3, o[1] - 27, v_name)
    if label:
        canvas.text(o[0] + 4, o[1] + 14, label)


def setup_picture(built, r, machining) -> SetupPicture:
    """The part on the machine for the job ``r`` (a :class:`~camcam.nc.result.MachiningResult`) of ``built``
    (``machining``: the spec's table, for the tool holder); the report's setup sheet opens with it.
    ``tests/report/test_setup_picture.py`` reads the lengths drawn back at the stated scale.
    """
    return _barrel(built, r) if r.rotary else _disc(built, r, machining)
