"""Optimised laws as JSON: what ``camcam optimize`` writes and ``law = "file:…"`` reads.

```json
{"format": "camcam-bspline-law", "version": 1,
 "degree": 5, "segments": 7, "symmetric": true,
 "control_points": [...], "knots": [...],
 "Vm": 1.99923, "Am": 4.86097, "Jm": 61.4, "Jmax": 61.4, "Jmin": -61.4,
 "problem": {...}, "solver": {...}}
```

Control points and knots are those of the half curve on [0, 0.5] when
``symmetric`` (the rest is the point mirror), else of the curve on [0, 1].
Floats are written with ``repr`` precision, so a law read back is the same law.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from camcam.errors import InputError
from camcam.inputs import read_text
from camcam.optimize.bspline_law import BSplineLaw
from camcam.optimize.space import MAX_DEGREE, MAX_SEGMENTS

__all__ = ["FORMAT", "law_document", "law_from_document", "read_law_file", "BOUNDARY_ATOL"]

FORMAT = "camcam-bspline-law"
#: A law file's boundary conditions must hold to this (dimensionless S, V, A):
#: written laws hold them to ~1e-14; a hand-edited control point breaks them by ≥ 1e-6.
BOUNDARY_ATOL = 1e-9


def law_document(law: BSplineLaw, problem: dict | None = None, solver: dict | None = None) -> dict:
    """The JSON object for ``law`` (with its exact characteristic values)."""
    c = law.characteristics()
    doc = {
        "format": FORMAT,
        "version": 1,
        "degree": law.degree,
        "segments": law.segments,
        "symmetric": law.symmetric,
        "control_points": [float(p) for p in law.control_points],
        "knots": [float(k) for k in law.knots],
        "Vm": c.Vm,
        "Am": c.Am,
        "Jm": c.Jm,
        "Jmax": c.Jmax.value,
        "Jmin": c.Jmin.value,
    }
    if problem is not None:
        doc["problem"] = problem
    if solver is not None:
        doc["solver"] = solver
    return doc


def law_from_document(doc, name: str = "bspline") -> BSplineLaw:
    """The law of a parsed law file; :class:`InputError` naming the bad key otherwise.

    Examples
    --------
    >>> from camcam.optimize.space import BSplineSpace
    >>> sp = BSplineSpace(5, 4, True)
    >>> law = BSplineLaw.from_free(sp, sp.initial_free())
    >>> law_from_document(law_document(law)).control_points == law.control_points
    True
    >>> law_from_document({"format": FORMAT, "degree": 4})
    Traceback (most recent call last):
    ...
    camcam.errors.InputError: degree: expected an odd integer from 3 to 9, got 4
    """
    if not isinstance(doc, dict):
        raise InputError("expected a JSON object")
    if doc.get("format") != FORMAT:
        raise InputError(f'format: expected "{FORMAT}", got {json.dumps(doc.get("format"))}')
    deg = doc.get("degree")
    if not (type(deg) is int and 3 <= deg <= MAX_DEGREE and deg % 2 == 1):
        raise InputError(f"degree: expected an odd integer from 3 to {MAX_DEGREE}, got {json.dumps(deg)}")
    seg = doc.get("segments")
    if not (type(seg) is int and 1 <= seg <= MAX_SEGMENTS):
        raise InputError(f"segments: expected an integer from 1 to {MAX_SEGMENTS}, got {json.dumps(seg)}")
    sym = doc.get("symmetric")
    if not isinstance(sym, bool):
        raise InputError(f"symmetric: expected true or false, got {json.dumps(sym)}")
    pts = doc.get("control_points")
    if not isinstance(pts, list) or not all(type(p) in (int, float) and math.isfinite(p) for p in pts):
        raise InputError("control_points: expected an array of finite numbers")
    if len(pts) != seg + deg:
        raise InputError(f"control_points: a degree-{deg} B-spline over {seg} segments has {seg + deg} control points, got {len(pts)}")
    try:
        law = BSplineLaw(deg, seg, sym, tuple(float(p) for p in pts), name=name)
    except ValueError as err:
        raise InputError(f"segments: {err}") from None
    for T, k, v in law.space.conditions + ((1.0, 0, 1.0), (1.0, 1, 0.0), (1.0, 2, 0.0)):
        got = float(law.evaluate(T, k))
        if abs(got - v) > BOUNDARY_ATOL:
            what = "SVA"[k]
            raise InputError(f"control_points: {what}({T:g}) = {got:.12g}, expected {v:g} (the law must rise from rest to rest, 0 to 1)")
    return law


def read_law_file(path: str | Path, name: str | None = None) -> BSplineLaw:
    """Read a law file; :class:`InputError` (one line, naming the file) on any problem."""
    path = Path(path)
    text = read_text(path)
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as err:
        raise InputError(f"{path}: not valid JSON: {err}") from None
    try:
        return law_from_document(doc, name or f"file:{path.name}")
    except InputError as err:
        raise InputError(f"{path}: {err}") from None
