"""Writing a spec back as TOML: the sized design as a file `camcam run` takes as is.

Only what a parsed spec holds: tables, arrays (of inline tables), strings,
booleans, integers and finite floats.  Floats are written with ``repr``, the
shortest text that reads back to the same float.
"""

from __future__ import annotations

import json
import math
import re
from typing import Any

__all__ = ["dumps", "sized_spec_data"]

_BARE = re.compile(r"^[A-Za-z0-9_-]+$")


def _key(k: str) -> str:
    return k if _BARE.match(k) else json.dumps(k, ensure_ascii=False)


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"TOML spec values must be finite, got {v!r}")
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        if v and all(isinstance(x, dict) for x in v):
            return "[\n" + "".join(f"  {_value(x)},\n" for x in v) + "]"
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise ValueError(f"cannot write {type(v).__name__} as TOML")


def _table(path: list[str], data: dict, out: list[str]) -> None:
    scalars = {k: v for k, v in data.items() if not isinstance(v, dict)}
    tables = {k: v for k, v in data.items() if isinstance(v, dict)}
    if path:
        out.append("")
        out.append("[" + ".".join(_key(p) for p in path) + "]")
    for k, v in scalars.items():
        out.append(f"{_key(k)} = {_value(v)}")
    for k, v in tables.items():
        _table([*path, k], v, out)


def dumps(data: dict, header: str = "") -> str:
    """TOML text of ``data`` (a parsed spec), with ``header`` as leading comment lines.

    Examples
    --------
    >>> import tomllib
    >>> d = {"name": "x", "motion": {"rpm": 60.0, "segments": [{"law": "cycloidal", "from": 0, "to": 360, "rise": 0.1}]}}
    >>> tomllib.loads(dumps(d)) == d
    True
    """
    out = [f"# {line}" if line else "#" for line in header.splitlines()]
    _table([], data, out)
    return "\n".join(out).lstrip("\n") + "\n"


def sized_spec_data(data: dict, name: str, params: dict[str, float], laws: dict[int, str]) -> dict:
    """The parsed spec ``data`` turned into one design: ``[size]`` dropped, the axes and laws set."""
    out = {k: v for k, v in data.items() if k != "size"}
    out["name"] = name
    cam = dict(out["cam"])
    follower = dict(out["follower"])
    for axis, value in params.items():
        if axis == "base_radius":
            cam["base_radius"] = float(value)
        else:
            follower[axis] = float(value)
    out["cam"], out["follower"] = cam, follower
    motion = dict(out["motion"])
    segments = [dict(s) for s in motion["segments"]]
    for k, law in laws.items():
        row = segments[k]
        segments[k] = {"law": law, "from": row["from"], "to": row["to"], "rise": row["rise"]}
    motion["segments"] = segments
    out["motion"] = motion
    return out
