"""A whole spec file: reading the TOML and validating each table.

The spec is the only place that reads files named by the user besides the
exporters; the stages receive the frozen values built here.
"""

from __future__ import annotations

import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

from camcam.errors import SpecError
from camcam.spec.machining import MachiningSpec, read_machining
from camcam.spec.motion import MotionSpec, read_motion
from camcam.spec.reader import Table

__all__ = ["Spec", "load_spec", "parse_spec"]

_NAME = re.compile(r"^[A-Za-z0-9][A-Za-z0-9_.-]{0,63}$")


@dataclass(frozen=True)
class Spec:
    """A validated spec.  Tables a file leaves out are ``None``; commands say which they need."""

    name: str
    source: Path
    motion: MotionSpec | None
    machining: MachiningSpec | None = None

    def need(self, table: str, command: str):
        """The table ``table``, or a :class:`SpecError` saying ``command`` needs it."""
        value = getattr(self, table)
        if value is None:
            raise SpecError(table, f"missing; `camcam {command}` needs a [{table}] table")
        return value


def parse_spec(data: dict, source: Path) -> Spec:
    """Validate a parsed TOML document (``source`` names it and anchors relative paths)."""
    root = Table(data, "")
    name = root.string("name", source.stem)
    root.check("name", bool(_NAME.match(name)), f'"{name}" must be 1–64 letters, digits, "_", "-" or "." (it names the output files)')
    base = source.parent
    unit = "mm"
    motion = root.table("motion", None)
    motion_spec = read_motion(motion, base, unit) if motion is not None else None
    if motion is not None:
        motion.done()
    machining = root.table("machining", None)
    machining_spec = read_machining(machining, base) if machining is not None else None
    root.done()
    return Spec(name, source, motion_spec, machining_spec)


def load_spec(path: str | Path) -> Spec:
    """Read and validate the spec file at ``path``."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise SpecError(str(path), "no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise SpecError(str(path), f"cannot read: {err}") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise SpecError(str(path), f"not valid TOML: {err}") from None
    return parse_spec(data, path)
