"""Reading the user's data files (lift tables, point sets, law files) as text.

Every reader names the file in its one-line :class:`~camcam.errors.InputError`.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Iterator

from camcam.errors import InputError

__all__ = ["read_text", "data_rows", "parse_number"]

#: Fields are separated by a comma (with any spaces around it) or by white space.
_SPLIT = re.compile(r"\s*,\s*|\s+")


def read_text(path: str | Path) -> str:
    """The UTF-8 text of ``path``; :class:`InputError` naming the file when it is missing or unreadable."""
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise InputError(f"{path}: cannot read: {err}") from None


def data_rows(text: str, source: str) -> Iterator[tuple[str, int, str, list[str]]]:
    r"""(``"<source> row <n>"``, n, the stripped line, its fields) for every line that is
    neither blank nor a ``#`` comment.

    Examples
    --------
    >>> list(data_rows("# a table\n0, 1.5\n\n1 2\n", "t.csv"))
    [('t.csv row 2', 2, '0, 1.5', ['0', '1.5']), ('t.csv row 4', 4, '1 2', ['1', '2'])]
    """
    for lineno, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        yield f"{source} row {lineno}", lineno, stripped, _SPLIT.split(stripped)


def parse_number(text: str, what: str, where: str) -> float:
    """The finite number a data field holds; :class:`InputError` naming ``where`` and ``what`` otherwise.

    Examples
    --------
    >>> parse_number("2.5", "lift", "t.csv row 3")
    2.5
    >>> parse_number("nan", "lift", "t.csv row 3")
    Traceback (most recent call last):
    camcam.errors.InputError: t.csv row 3: lift nan is not a finite number
    """
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{where}: {what} {text!r} is not a number") from None
    if not math.isfinite(value):
        raise InputError(f"{where}: {what} {text} is not a finite number")
    return value
