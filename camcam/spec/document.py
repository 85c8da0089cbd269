"""A whole spec file: reading the TOML and validating each table.

The spec is the only place that reads files named by the user besides the
exporters; the stages receive the frozen values built here.  Each table's
reader is imported when the file has that table: the readers bring in their
stage's settings (``[machining]`` the NC stage, ``[motion]`` the lift-table
fitting), which a spec with only ``[optimize]`` does not need.
"""

from __future__ import annotations

import importlib
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from camcam.errors import SpecError
from camcam.inputs import os_reason, read_limited
from camcam.spec.reader import Table, fmt
from camcam.spec.report import DEFAULT_REPORT, ReportSpec, read_report
from camcam.spec.size import SizeSpec, check_size_dynamics, read_size
from camcam.spec.stock import DEFAULT_STOCK, StockSpec, read_stock

if TYPE_CHECKING:
    from camcam.dynamics.train import DynamicsSpec
    from camcam.spec.cam import CamSpec
    from camcam.spec.follower import FollowerSpec
    from camcam.spec.inspection import InspectionSpec
    from camcam.spec.machining import MachiningSpec
    from camcam.spec.motion import MotionSpec
    from camcam.spec.optimize import OptimizeSpec

__all__ = ["Spec", "load_spec", "parse_spec", "MAX_SPEC_BYTES"]

_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,63}")  # whole name (fullmatch: "x\n" is refused)

#: Largest spec file read (the samples are 1-2 KiB).
MAX_SPEC_BYTES = 1 << 20


@dataclass(frozen=True, kw_only=True)
class Spec:
    """A validated spec.  Tables a file leaves out are ``None``; commands say which they need."""

    name: str
    source: Path
    motion: MotionSpec | None
    cam: CamSpec | None = None
    follower: FollowerSpec | None = None
    optimize: OptimizeSpec | None = None
    machining: MachiningSpec | None = None
    report: ReportSpec = DEFAULT_REPORT
    stock: StockSpec = DEFAULT_STOCK
    size: SizeSpec | None = None  # `camcam size` sweeps it; `camcam run` runs the design as written
    dynamics: DynamicsSpec | None = None  # forces, torque, contact stress, jump speed (camcam.dynamics)
    inspection: InspectionSpec | None = None  # `camcam inspect`: the measured part's tolerance band

    @property
    def unit(self) -> str:
        """Motion unit: degrees for an oscillating follower, else mm."""
        return self.follower.unit if self.follower is not None else "mm"

    def need(self, table: str, command: str):
        """The table ``table``, or a :class:`SpecError` saying ``command`` needs it."""
        value = getattr(self, table)
        if value is None:
            raise SpecError(table, f"missing; `camcam {command}` needs a [{table}] table")
        return value


def _reader(table: str, function: str):
    """``camcam.spec.<table>.<function>``, imported now (module docstring)."""
    return getattr(importlib.import_module(f"camcam.spec.{table}"), function)


def parse_spec(data: dict, source: Path) -> Spec:
    """Validate a parsed TOML document (``source`` names it and anchors relative paths)."""
    root = Table(data, "")
    name = root.string("name", source.stem)
    root.check("name", isinstance(name, str) and bool(_NAME.fullmatch(name)), f'{fmt(name)} must be 1–64 letters, digits, "_", "-" or "." (it names the output files)')
    base = source.parent
    cam_t = root.table("cam", None)
    cam = _reader("cam", "read_cam")(cam_t) if cam_t is not None else None
    fol_t = root.table("follower", None)
    follower = _reader("follower", "read_follower")(fol_t, cam.kind if cam else None) if fol_t is not None else None
    if cam is not None and follower is None:
        raise SpecError("follower", "missing; a [cam] needs a [follower] table")
    if follower is not None and cam is not None:
        if cam.kind != "disc" and not follower.is_roller:
            raise SpecError("follower.kind", f'"{follower.kind}": a {cam.kind} cam needs a roller follower')
    unit = follower.unit if follower is not None else "mm"
    motion = root.table("motion", None)
    motion_spec = _reader("motion", "read_motion")(motion, base, unit) if motion is not None else None
    if motion is not None:
        motion.done()
    optimize = root.table("optimize", None)
    optimize_spec = _reader("optimize", "read_optimize")(optimize) if optimize is not None else None
    if optimize is not None:
        optimize.done()
    machining = root.table("machining", None)
    # the cam's size (its base circle's or cylinder's diameter) bounds the tolerance: a likely unit mistake over it
    machining_spec = (_reader("machining", "read_machining")(machining, base, cam.kind if cam else None,
                                                             follower.kind if follower else None, source.name,
                                                             2.0 * cam.base_radius if cam else None,
                                                             cam.material if cam else None)
                      if machining is not None else None)
    if machining_spec is not None and cam is not None:
        _check_depth(machining_spec, cam)
    if machining_spec is not None:
        _reader("machining", "check_passes")(machining_spec)
    report_t = root.table("report", None)
    report_spec = read_report(report_t) if report_t is not None else DEFAULT_REPORT
    stock_t = root.table("stock", None)
    stock = read_stock(stock_t, cam) if stock_t is not None else DEFAULT_STOCK
    size_t = root.table("size", None)
    size_spec = read_size(size_t, cam, follower, motion_spec, machining_spec) if size_t is not None else None
    dynamics_t = root.table("dynamics", None)
    dynamics = _reader("dynamics", "read_dynamics")(dynamics_t, cam, follower) if dynamics_t is not None else None
    if size_spec is not None:
        check_size_dynamics(size_spec, dynamics)
    inspection_t = root.table("inspection", None)
    inspection = _reader("inspection", "read_inspection")(inspection_t) if inspection_t is not None else None
    root.done()
    return Spec(name=name, source=source, motion=motion_spec, cam=cam, follower=follower, optimize=optimize_spec,
                machining=machining_spec, report=report_spec, stock=stock, size=size_spec,
                dynamics=dynamics, inspection=inspection)


def _check_depth(m: MachiningSpec, cam: CamSpec) -> None:
    """A disc is cut at most ``BREAK_THROUGH_MM`` (:mod:`camcam.spec.machining`) below its thickness;
    a groove no deeper than ``groove_depth``."""
    if cam.kind == "disc":
        through = _reader("machining", "BREAK_THROUGH_MM")
        limit, why = cam.thickness + through, f"cam.thickness = {cam.thickness:g} mm plus {through:g} mm break-through"
    else:
        limit, why = cam.groove_depth, f"cam.groove_depth = {cam.groove_depth:g} mm"
    if m.depth_mm > limit + 1e-9:
        raise SpecError("machining.depth", f"{m.depth_mm:g} mm is deeper than {why}")


def load_spec(path: str | Path) -> Spec:
    """Read and validate the spec file at ``path``.

    Parameters
    ----------
    path : str or Path
        A TOML spec (README "Spec reference"); relative paths inside it are
        taken from its folder.

    Returns
    -------
    Spec
        Frozen, validated tables: ``motion``, ``cam``, ``follower``, ``machining``, ...

    Raises
    ------
    SpecError
        One line naming the key path and what was expected.

    Examples
    --------
    >>> spec = load_spec("samples/disc-translating-roller.toml")
    >>> spec.name, spec.cam.kind, spec.follower.kind, spec.machining.tolerance_mm
    ('disc-translating-roller', 'disc', 'translating-roller', 0.01)
    """
    path = Path(path)
    try:
        raw = read_limited(path, MAX_SPEC_BYTES)
    except FileNotFoundError:
        raise SpecError(str(path), "no such file") from None
    except OSError as err:
        raise SpecError(str(path), f"cannot read: {os_reason(err)}") from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as err:
        raise SpecError(str(path), f"not UTF-8 text (byte {err.start})") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise SpecError(str(path), f"not valid TOML: {err}") from None
    return parse_spec(data, path)
