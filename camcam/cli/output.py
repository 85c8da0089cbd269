"""Helpers the commands share: publishing the output set with its summary, JSON printing and warnings."""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any, Callable, Sequence

__all__ = ["to_json", "print_json", "warn", "publish"]


def _clean(value: Any) -> Any:
    """Replace ±inf and NaN (not JSON) by the strings "inf", "-inf", "nan"."""
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, dict):
        return {k: _clean(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_clean(v) for v in value]
    if hasattr(value, "item") and callable(value.item):  # numpy scalars
        return _clean(value.item())
    return value


def to_json(obj: Any, indent: int | None = 2) -> str:
    """Strict JSON (no NaN/Infinity tokens): infinite values become "inf"/"-inf"."""
    return json.dumps(_clean(obj), indent=indent, allow_nan=False, ensure_ascii=False)


def print_json(obj: Any) -> None:
    sys.stdout.write(to_json(obj) + "\n")


def warn(message: str) -> None:
    print(f"camcam: warning: {message}", file=sys.stderr)


def publish(out, summary: dict, as_json: bool, show: Callable[[dict], None],
            after: Sequence[str] = ()) -> list[Path]:
    """Write ``out`` (all or nothing), then print ``summary`` as one JSON object, or as text.

    The text is ``show(summary)``, a "wrote <file>" line per file, then the
    lines of ``after``.  ``summary["files"]`` lists the files written.
    """
    written = out.commit()
    summary["files"] = [str(p) for p in written]
    if as_json:
        print_json(summary)
    else:
        show(summary)
        for p in written:
            print(f"wrote {p}")
        for line in after:
            print(line)
    return written
