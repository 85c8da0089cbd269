"""Validated access to a parsed TOML table, with the key path in every error.

Each spec table is read through a :class:`Table`: every value is taken with
its expected kind and range, and :meth:`Table.done` rejects the keys nobody
took.  Errors are :class:`~camcam.errors.SpecError` with the full key path,
e.g. ``motion.segments[2].to: 370 is past 360``.
"""

from __future__ import annotations

import json
import math
from typing import Any, Callable, Iterable

from camcam.errors import SpecError

__all__ = ["Table", "MISSING", "fmt"]


class _Missing:
    def __repr__(self) -> str:
        return "MISSING"


MISSING: Any = _Missing()

#: Magnitude caps applied by unit when a key states no range of its own: far beyond any
#: cam or machine (a 10 m cam, 10 turns, 1e6 mm/min), and they keep every derived
#: quantity (ω³·rise, areas, volumes) finite.
UNIT_LIMITS = {"mm": 1e4, "degrees": 3600.0, "mm/min": 1e6, "rev/min": 1e5}


def fmt(value: Any) -> str:
    """A value as the user wrote it (TOML-ish), for messages."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)  # quoted, control characters escaped: one line
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e15:
        return str(int(value))
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return "an array"
    return str(value)


class Table:
    """A TOML table being read.

    Parameters
    ----------
    data : dict
        The parsed table.
    path : str
        Its key path (``""`` for the document root).

    Examples
    --------
    >>> t = Table({"rpm": 120, "strict": True}, "motion")
    >>> t.number("rpm", minimum=0, inclusive=False), t.boolean("strict", False)
    (120.0, True)
    >>> t.done()
    >>> Table({"rmp": 1}, "motion").done()
    Traceback (most recent call last):
    ...
    camcam.errors.SpecError: motion.rmp: unknown key; expected one of: (none)
    """

    def __init__(self, data: Any, path: str) -> None:
        if not isinstance(data, dict):
            raise SpecError(path, f"expected a table, got {fmt(data)}")
        self.data = data
        self.path = path
        self._taken: set[str] = set()

    def key_path(self, key: str) -> str:
        return f"{self.path}.{key}" if self.path else key

    def has(self, key: str) -> bool:
        return key in self.data

    def error(self, key: str, message: str) -> SpecError:
        return SpecError(self.key_path(key), message)

    def raw(self, key: str, default: Any = MISSING, what: str = "a value") -> Any:
        self._taken.add(key)
        if key not in self.data:
            if default is MISSING:
                raise self.error(key, f"missing; expected {what}")
            return default
        return self.data[key]

    def number(
        self,
        key: str,
        default: Any = MISSING,
        *,
        minimum: float | None = None,
        maximum: float | None = None,
        inclusive: bool = True,
        unit: str = "",
    ) -> float:
        """A finite number (int or float, not bool) within the given range.

        Besides the given range, |value| is capped by :data:`UNIT_LIMITS` for ``unit``.
        """
        rng = _range_text(minimum, maximum, inclusive)
        what = f"a number{rng}{' ' + unit if unit else ''}"
        value = self.raw(key, default, what)
        if value is default and default is not MISSING:
            return value
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self.error(key, f"expected {what}, got {fmt(value)}")
        value = float(value)
        if not math.isfinite(value):
            raise self.error(key, f"expected {what}, got {fmt(value)}")
        lo_bad = minimum is not None and (value < minimum or (not inclusive and value == minimum))
        hi_bad = maximum is not None and (value > maximum or (not inclusive and value == maximum))
        if lo_bad or hi_bad:
            raise self.error(key, f"expected {what}, got {fmt(value)}")
        cap = UNIT_LIMITS.get(unit)
        if cap is not None and abs(value) > cap:
            raise self.error(key, f"{fmt(value)} {unit} is out of range; expected at most {fmt(cap)} {unit} in size")
        return value

    def integer(self, key: str, default: Any = MISSING, *, minimum: int | None = None, maximum: int | None = None) -> int:
        what = f"an integer{_range_text(minimum, maximum, True)}"
        value = self.raw(key, default, what)
        if value is default and default is not MISSING:
            return value
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(key, f"expected {what}, got {fmt(value)}")
        if (minimum is not None and value < minimum) or (maximum is not None and value > maximum):
            raise self.error(key, f"expected {what}, got {fmt(value)}")
        return value

    def boolean(self, key: str, default: Any = MISSING) -> bool:
        value = self.raw(key, default, "true or false")
        if not isinstance(value, bool):
            raise self.error(key, f"expected true or false, got {fmt(value)}")
        return value

    def string(self, key: str, default: Any = MISSING, *, choices: Iterable[str] | None = None) -> str:
        choices = tuple(choices) if choices is not None else None
        what = "one of " + ", ".join(f'"{c}"' for c in choices) if choices else "a string"
        value = self.raw(key, default, what)
        if value is default and default is not MISSING:
            return value
        if not isinstance(value, str) or (choices is not None and value not in choices):
            raise self.error(key, f"expected {what}, got {fmt(value)}")
        return value

    def table(self, key: str, default: Any = MISSING) -> "Table | Any":
        value = self.raw(key, default, "a table")
        if value is default and default is not MISSING:
            return value
        return Table(value, self.key_path(key))

    def tables(self, key: str, *, min_items: int = 1) -> list["Table"]:
        """An array of tables (``[[key]]`` or ``key = [{...}, ...]``)."""
        value = self.raw(key, what="an array of tables")
        if not isinstance(value, list) or len(value) < min_items:
            raise self.error(key, f"expected an array of at least {min_items} table(s), got {fmt(value)}")
        return [Table(v, f"{self.key_path(key)}[{i}]") for i, v in enumerate(value)]

    def check(self, key: str, ok: bool, message: str) -> None:
        if not ok:
            raise self.error(key, message)

    def done(self, allowed_extra: Callable[[str], bool] | None = None) -> None:
        """Reject keys that were not taken."""
        for key in self.data:
            if key not in self._taken and not (allowed_extra and allowed_extra(key)):
                known = ", ".join(sorted(self._taken)) or "(none)"
                raise self.error(key, f"unknown key; expected one of: {known}")


def _range_text(minimum, maximum, inclusive) -> str:
    lo = ">=" if inclusive else ">"
    hi = "<=" if inclusive else "<"
    if minimum is not None and maximum is not None:
        return f" {lo} {fmt(float(minimum))} and {hi} {fmt(float(maximum))}"
    if minimum is not None:
        return f" {lo} {fmt(float(minimum))}"
    if maximum is not None:
        return f" {hi} {fmt(float(maximum))}"
    return ""
