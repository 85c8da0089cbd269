"""STEP (ISO 10303-21, AP214) export of a cam's exact solid, and reading one back.

The solid is :func:`camcam.export.step_solids.cam_solid`'s (OpenCascade, through OCP:
``pip install 'camcam[cad]'``).  The file's bytes depend on the cam alone: the header's
time stamp, which OpenCascade sets to the clock, is :data:`TIME_STAMP`, and the header
names the part, not a path, so the sample outputs are recorded like every other file.

OCP is imported only when a STEP is written or read, never by ``import camcam``;
:func:`cad_available` says whether it can be.  The extra is ``cadquery-ocp-novtk``, OCP
without VTK (a 67 MB wheel, about 1 s to import): it has all this needs (the STEP writer
and reader, B-spline curves and surfaces, booleans, ``BRepCheck_Analyzer``, volumes);
build123d would pull in the VTK-carrying ``cadquery-ocp`` and a modelling layer camcam
does not use.
"""

from __future__ import annotations

import re
import tempfile
from pathlib import Path

__all__ = ["step_bytes", "step_files", "cam_step", "read_step", "cad_available", "load_cad", "CAD_HINT", "TIME_STAMP", "STEP_SCHEMA"]

#: The one line `camcam run` prints when it cannot write the STEP.
CAD_HINT = "STEP not written: pip install 'camcam[cad]' (OpenCascade) to get the cam as an exact solid"
#: The header's time stamp (ISO 8601): fixed, so that the same cam gives the same bytes.
TIME_STAMP = "2000-01-01T00:00:00"
#: The application protocol written.
STEP_SCHEMA = "AP214IS"


def cad_available() -> bool:
    """Whether OpenCascade (OCP) can be imported (this imports it: about a second)."""
    import importlib

    try:
        importlib.import_module("OCP.STEPControl")
    except ImportError:
        return False
    return True


#: What a STEP's solid needs beside OCP: the solids' builders; and a barrel's groove walls scipy's splines too
#: (:func:`camcam.geometry.bspline_fit.fit_surface`; a disc's curves are OpenCascade's).
_CAD_MODULES, _BARREL_MODULES = ("camcam.export.step_solids",), ("camcam.export.barrel_solid", "scipy.interpolate")


def load_cad(kind: str) -> bool:
    """:func:`cad_available`, and the modules a ``kind`` cam's solid needs loaded, with the cyclic collector
    paused: the imports make many objects and no garbage (a barrel's STEP child spent 0.16 CPU s collecting
    during them, cylindrical-translating; 0.05 s after).  It runs again afterwards if it ran before."""
    import gc
    import importlib

    running = gc.isenabled()
    gc.disable()
    try:
        if not cad_available():
            return False
        for module in _CAD_MODULES + (() if kind in ("disc", "disc-groove") else _BARREL_MODULES):
            importlib.import_module(module)
        return True
    finally:
        if running:
            gc.enable()


def step_bytes(shape, name: str) -> bytes:
    """The AP214 STEP file of the OCP ``shape`` (mm), its product named ``name``, with a fixed time stamp.

    Raises
    ------
    RuntimeError
        OpenCascade did not translate or write the shape.
    """
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.Interface import Interface_Static
    from OCP.STEPControl import STEPControl_StepModelType, STEPControl_Writer

    _quiet()
    Interface_Static.SetCVal_s("write.step.schema", STEP_SCHEMA)
    Interface_Static.SetCVal_s("write.step.unit", "MM")
    writer = STEPControl_Writer()
    if writer.Transfer(shape, STEPControl_StepModelType.STEPControl_AsIs) != IFSelect_ReturnStatus.IFSelect_RetDone:
        raise RuntimeError(f"OpenCascade could not translate {name}'s solid to STEP")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / f"{name}.step"
        if writer.Write(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:
            raise RuntimeError(f"OpenCascade could not write {name}'s STEP file")
        text = path.read_bytes()
    return _fixed_header(text, name)


def _quiet() -> None:
    """Keep OpenCascade's transfer statistics off stdout (the run's stdout is its summary): failures only."""
    from OCP.Message import Message, Message_Gravity

    for printer in Message.DefaultMessenger_s().Printers():
        printer.SetTraceLevel(Message_Gravity.Message_Fail)


def _fixed_header(text: bytes, name: str) -> bytes:
    """``text`` with FILE_NAME's name and time stamp and the PRODUCT's name fixed (OpenCascade writes the path,
    the clock, and a translator name with a count of the files written so far in the process)."""
    quoted = name.encode("ascii", "replace").replace(b"'", b"''")
    fixes = ((rb"FILE_NAME\('(?:[^']|'')*',\s*'[^']*'", b"FILE_NAME('%s','%s'" % (quoted, TIME_STAMP.encode())),
             (rb"PRODUCT\('(?:[^']|'')*',\s*'(?:[^']|'')*'", b"PRODUCT('%s','%s'" % (quoted, quoted)))
    for pattern, fixed in fixes:
        text, n = re.subn(pattern, lambda _: fixed, text, count=1)
        if n != 1:
            raise RuntimeError(f"OpenCascade's STEP file has no {pattern[:9].decode()}")
    return text


def step_files(built, name: str) -> tuple[dict[str, bytes], str | None]:
    """``({"<name>.step": bytes}, None)`` of the cam's exact solid, or ``({}, why)``: one line saying why not
    (:data:`CAD_HINT` where OCP is not installed; OpenCascade's failure on this cam otherwise, which leaves
    the rest of the run as it is)."""
    if not load_cad(built.spec.kind):
        return {}, CAD_HINT
    from OCP.Standard import Standard_Failure

    from camcam.errors import GeometryError

    try:
        return {f"{name}.step": cam_step(built, name)}, None
    except (GeometryError, RuntimeError, Standard_Failure) as err:
        return {}, f"STEP not written: {err}"


def cam_step(built, name: str) -> bytes:
    """The STEP file of a :class:`~camcam.geometry.build.BuiltCam`'s exact solid."""
    from camcam.export.step_solids import cam_solid

    return step_bytes(cam_solid(built), name)


def read_step(data: bytes):
    """The one shape of a STEP file's bytes (an OCP ``TopoDS_Shape``).

    Raises
    ------
    ValueError
        OpenCascade could not read the file, or it holds no shape.
    """
    from OCP.IFSelect import IFSelect_ReturnStatus
    from OCP.STEPControl import STEPControl_Reader

    _quiet()
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "read.step"
        path.write_bytes(data)
        reader = STEPControl_Reader()
        if reader.ReadFile(str(path)) != IFSelect_ReturnStatus.IFSelect_RetDone:
            raise ValueError("OpenCascade could not read the STEP file")
        reader.TransferRoots()
        if reader.NbShapes() < 1:
            raise ValueError("the STEP file holds no shape")
        return reader.OneShape()
