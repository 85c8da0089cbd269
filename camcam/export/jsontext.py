"""Strict JSON text of a report or summary: no NaN/Infinity tokens, numpy scalars as numbers."""

from __future__ import annotations

import json
import math
from typing import Any

__all__ = ["to_json"]


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
