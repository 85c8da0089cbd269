"""DXF drawing of a fitted contour with ezdxf.

Layers: ``CONTOUR`` (or the caller's ``contour_layer``) holds the fitted
lines and arcs exactly as machined (the printed numbers), ``EXACT`` the exact
curve as cubic SPLINEs (one per analytic piece, the cubic Hermite interpolant of the
curve's points and exact tangents; their measured deviation is returned and written as a text), plus any extra layers
the caller supplies (part outline, pitch curve, base circle, bore, roller
circles, angle-zero mark, title block).  Every layer gets its own colour
(:data:`LAYER_COLOURS`, in the order the layers are made) and the header's
``$EXTMIN``/``$EXTMAX`` hold the drawing's extents.
"""

from __future__ import annotations

import io
from collections import OrderedDict
from dataclasses import dataclass

import ezdxf
import numpy as np
from ezdxf import bbox, units

from camcam.toolpath.elements import Arc, Line, circular

__all__ = ["Polyline", "Circle", "Text", "ExactCurve", "DxfDrawing", "contour_dxf", "HermiteSpline", "spline_of_curve", "LAYER_COLOURS"]

#: AutoCAD colour indices given to the layers in the order they are made (red, green, blue, magenta,
#: cyan, yellow, then darker shades); all distinct and visible on a white or a black background.
LAYER_COLOURS = (1, 3, 5, 6, 4, 2, 30, 8, 150, 210, 90, 40, 130, 230, 70, 180, 20, 110)


@dataclass(frozen=True)
class Polyline:
    points: tuple[tuple[float, float], ...]
    closed: bool = False


@dataclass(frozen=True)
class Circle:
    centre: tuple[float, float]
    radius: float


@dataclass(frozen=True)
class Text:
    text: str
    insert: tuple[float, float]
    height: float = 2.5


@dataclass(frozen=True)
class ExactCurve:
    """An exact curve drawn as cubic SPLINEs (one per analytic piece) within the drawing's spline deviation."""

    curve: object


@dataclass(frozen=True)
class DxfDrawing:
    """The DXF text and the stated deviation of the exact-curve splines (mm)."""

    data: bytes
    spline_deviation_mm: float
    entities: int


@dataclass(frozen=True, eq=False)
class HermiteSpline:
    """The cubic spline through ``points_at_nodes`` (m + 1, 2) with the tangents ``tangents`` (m + 1, 2) there, at
    the increasing parameters ``nodes`` (m + 1,): each interval's cubic is the Hermite one, and the spline is C1.

    As a B-spline (what a DXF SPLINE holds): ``knots`` (2m + 6,) are the ends four times and each interior node
    twice; ``control_points`` (2m + 2, 2) are each interval's inner Bézier points P + h/3·P′ and P − h/3·P′ (h its
    length), between the first and the last point.  An interior node's point is where the B-spline's two
    control points either side of it meet in the ratio of the intervals, so it is not stored.

    Examples
    --------
    The parabola (t, t²) is a cubic: two intervals reproduce it exactly.

    >>> t = np.array([0.0, 0.5, 1.0])
    >>> s = HermiteSpline(t, np.stack([t, t * t], -1), np.stack([np.ones(3), 2 * t], -1))
    >>> s.knots.tolist()
    [0.0, 0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0, 1.0]
    >>> s.control_points.round(6).tolist()
    [[0.0, 0.0], [0.166667, 0.0], [0.333333, 0.083333], [0.666667, 0.416667], [0.833333, 0.666667], [1.0, 1.0]]
    >>> s.points(np.array([0.25, 0.8])).round(12).tolist()
    [[0.25, 0.0625], [0.8, 0.64]]
    """

    nodes: np.ndarray
    points_at_nodes: np.ndarray
    tangents: np.ndarray

    @property
    def knots(self) -> np.ndarray:
        t = self.nodes
        return np.concatenate([np.full(4, t[0]), np.repeat(t[1:-1], 2), np.full(4, t[-1])])

    def inner_points(self) -> np.ndarray:
        """Each interval's inner Bézier points P + h/3·P′ at its start and P − h/3·P′ at its end, (m, 2, 2)."""
        P, D = self.points_at_nodes, self.tangents
        h = np.diff(self.nodes)[:, None]
        return np.stack([P[:-1] + h / 3 * D[:-1], P[1:] - h / 3 * D[1:]], 1)

    @property
    def control_points(self) -> np.ndarray:
        P = self.points_at_nodes
        return np.concatenate([P[:1], self.inner_points().reshape(-1, 2), P[-1:]])

    def points(self, t) -> np.ndarray:
        """The spline at the parameters ``t`` (k,) within the nodes, (k, 2): each interval's Bézier form."""
        t = np.asarray(t, float)
        nodes = self.nodes
        i = np.clip(np.searchsorted(nodes, t, side="right") - 1, 0, len(nodes) - 2)
        u = (t - nodes[i])[:, None] / (nodes[i + 1] - nodes[i])[:, None]
        P0, P3 = self.points_at_nodes[i], self.points_at_nodes[i + 1]
        inner = self.inner_points()
        P1, P2 = inner[i, 0], inner[i, 1]
        v = 1.0 - u
        return v ** 3 * P0 + 3 * u * v * v * P1 + 3 * u * u * v * P2 + u ** 3 * P3


def spline_of_curve(curve, lo: float, hi: float, deviation_mm: float = 1e-4) -> tuple[HermiteSpline, float]:
    """The cubic Hermite spline of ``curve`` on [lo, hi] at even nodes; more nodes until max |S(t) − P(t)| ≤
    ``deviation_mm``.

    The curve's own points and exact tangents (``curve.evaluate(t, 1)``) fix each interval's cubic, so no
    system is solved and numpy alone makes it: the drawing's child imports no scipy.interpolate (with
    :mod:`camcam.verify.kdtree`, 0.27 CPU s a run, issue 49).  Its error bound, h⁴/384 · max |P⁗| an interval h,
    is a fifth of the C2 not-a-knot interpolant's through as many points (5h⁴/384 · max |P⁗|, de Boor), which it
    replaces.  The check samples 8 points per interval; |S(t) − P(t)| bounds the distance both ways between
    the spline and the curve.  Memory is O(nodes): ezdxf's ``global_bspline_interpolation``, tried for issue
    49, built a dense n × n matrix, and a curve that needs 20 000 points (design-space case 43:57's profile)
    took 23 GB and the run with it.

    Returns
    -------
    (HermiteSpline, float)
        The spline and its largest sampled deviation (mm).
    """
    n = 17
    while True:
        t = np.linspace(lo, hi, n)
        spl = HermiteSpline(t, curve.evaluate(t, 0), curve.evaluate(t, 1))
        tt = np.linspace(lo, hi, 8 * n)
        dev = float(np.hypot(*(spl.points(tt) - curve.evaluate(tt, 0)).T).max())
        if dev <= deviation_mm or n > 20000:
            return spl, dev
        n = int(n * 1.8)


def _deg(v) -> float:
    return float(np.degrees(np.arctan2(v[1], v[0])))


_FIXED_HEADER = {"$TDINDWG": 0.0, "$TDUSRTIMER": 0.0}


def contour_dxf(elements, curve=None, extras: dict | None = None, spline_deviation_mm: float = 1e-4,
                title: str | None = None, contour_layer: str = "CONTOUR") -> DxfDrawing:
    """Build the drawing in memory (no file I/O); the same input gives the same bytes.

    ``extras`` maps a layer name to a list of :class:`Polyline`, :class:`Circle`,
    :class:`Text`, :class:`ExactCurve`, :class:`~camcam.toolpath.elements.Line`
    and :class:`~camcam.toolpath.elements.Arc` items.  ezdxf's time stamps and GUIDs
    (``$TDCREATE``, ``$TDUPDATE``, ``$FINGERPRINTGUID``, ``$VERSIONGUID``, the
    ezdxf marker) are written as its fixed test values; ``$TDINDWG`` and
    ``$TDUSRTIMER`` are 0.
    """
    saved = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        return _build(elements, curve, extras, spline_deviation_mm, title, contour_layer)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = saved


def _add_splines(msp, curve, layer, deviation_mm) -> tuple[float, int]:
    worst, count = 0.0, 0
    br = list(curve.breaks)
    for lo, hi in zip(br, br[1:]):
        spl, dev = spline_of_curve(curve, lo, hi, deviation_mm)
        worst = max(worst, dev)
        msp.add_open_spline([tuple(p) for p in spl.control_points.tolist()], degree=3, knots=spl.knots.tolist(),
                            dxfattribs={"layer": layer})
        count += 1
    return worst, count


def _add_element(msp, e, layer) -> None:
    """A LINE or an ARC; a printed spiral arc as the circular arc through its ends (:func:`circular`)."""
    if isinstance(e, Line):
        msp.add_line(e.start, e.end, dxfattribs={"layer": layer})
    else:
        e = circular(e)
        a0, a1 = _deg(np.subtract(e.start, e.centre)), _deg(np.subtract(e.end, e.centre))
        if not e.ccw:
            a0, a1 = a1, a0
        msp.add_arc(e.centre, e.radius, a0, a1, dxfattribs={"layer": layer})


class _Layers:
    """Layers made on first use, each with the next colour of :data:`LAYER_COLOURS`."""

    def __init__(self, doc):
        self.doc = doc

    def __call__(self, name: str) -> str:
        if name not in self.doc.layers:
            k = sum(1 for layer in self.doc.layers if layer.dxf.name not in ("0", "Defpoints"))
            self.doc.layers.add(name, color=LAYER_COLOURS[k % len(LAYER_COLOURS)])
        return name


def _pin_classes(doc) -> None:
    """Fix the CLASSES section's order.  ``doc.write`` adds a CLASS for each entity type in use by
    iterating a set, whose order follows ``PYTHONHASHSEED``; adding them here first, sorted by name,
    leaves ``write`` nothing to add, so the bytes no longer depend on the seed."""
    doc.classes.add_required_classes(doc.dxfversion)
    doc.classes.classes = OrderedDict(sorted(doc.classes.classes.items()))


def _build(elements, curve, extras, spline_deviation_mm, title, contour_layer="CONTOUR") -> DxfDrawing:
    doc = ezdxf.new("R2010", setup=False)
    for key, value in _FIXED_HEADER.items():
        doc.header[key] = value
    doc.units = units.MM
    doc.header["$INSUNITS"] = units.MM
    doc.header["$MEASUREMENT"] = 1
    msp = doc.modelspace()
    layer_of = _Layers(doc)
    layer_of(contour_layer)
    count = 0
    for e in elements:
        _add_element(msp, e, contour_layer)
        count += 1
    worst = 0.0
    if curve is not None:
        worst, n = _add_splines(msp, curve, layer_of("EXACT"), spline_deviation_mm)
        count += n
    splines = curve is not None
    for layer, items in (extras or {}).items():
        layer_of(layer)
        for it in items:
            if isinstance(it, (Line, Arc)):
                _add_element(msp, it, layer)
            elif isinstance(it, Polyline):
                msp.add_lwpolyline(it.points, close=it.closed, dxfattribs={"layer": layer})
            elif isinstance(it, Circle):
                msp.add_circle(it.centre, it.radius, dxfattribs={"layer": layer})
            elif isinstance(it, ExactCurve):
                dev, n = _add_splines(msp, it.curve, layer, spline_deviation_mm)
                worst, splines = max(worst, dev), True
                count += n - 1
            elif isinstance(it, Text):
                msp.add_text(it.text, height=it.height, dxfattribs={"layer": layer}).set_placement(it.insert)
            else:
                raise TypeError(f"layer {layer}: cannot draw {type(it).__name__}")
            count += 1
    if splines:
        where = curve if curve is not None else next(it.curve for items in (extras or {}).values()
                                                       for it in items if isinstance(it, ExactCurve))
        msp.add_text(f"EXACT: cubic splines within {worst:.2g} mm of the exact curve", height=1.0,
                     dxfattribs={"layer": layer_of("EXACT")}).set_placement(tuple(where.evaluate([where.t_start], 0)[0]))
        count += 1
    if title:
        msp.add_text(title, height=3.5, dxfattribs={"layer": layer_of("TITLE")}).set_placement((0.0, -10.0))
        count += 1
    box = bbox.extents(msp, fast=True)
    if box.has_data:  # ezdxf copies the model space's extents to $EXTMIN/$EXTMAX when it writes
        msp.dxf.extmin = tuple(float(v) for v in box.extmin)
        msp.dxf.extmax = tuple(float(v) for v in box.extmax)
    _pin_classes(doc)
    buf = io.StringIO()
    doc.write(buf)
    return DxfDrawing(buf.getvalue().encode("utf-8"), worst, count)
