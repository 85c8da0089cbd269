"""Reading the user's data files (lift tables, point sets, law files) as text.

Every reader names the file in its one-line :class:`~camcam.errors.InputError`.
"""

from __future__ import annotations

import math
import re
from pathlib import Path
from typing import Iterator

from camcam.errors import InputError

__all__ = ["read_text", "data_rows", "read_limited", "MAX_INPUT_BYTES", "InputTooLarge", "os_reason",
           "parse_number", "looks_numeric", "MAX_ROWS"]

#: Most data rows a table or point file may have (10⁵ rows fit in about 16 s of CPU, 10⁶ would take minutes).
MAX_ROWS = 200_000

#: A plain decimal number: ASCII digits, an optional point and exponent (no ``1_00``, ``inf``, ``0x10``).
_DECIMAL = re.compile(r"[+-]?(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")

#: Largest data file read (lift tables, point sets, law files).
MAX_INPUT_BYTES = 64 << 20


def os_reason(err: OSError) -> str:
    """The reason of an OS error as the end of a sentence: ``"no space left on device"``.

    >>> os_reason(OSError(28, "No space left on device"))
    'no space left on device'
    """
    text = err.strerror or str(err)
    return text[:1].lower() + text[1:]


class InputTooLarge(OSError):
    """A file is larger than the cap it is read with."""


def read_limited(path: str | Path, limit: int) -> bytes:
    """At most ``limit`` bytes of ``path``; :class:`InputTooLarge` when there are more
    (also for endless files such as ``/dev/zero``, which are never read past the cap)."""
    with open(path, "rb") as fh:
        data = fh.read(limit + 1)
    if len(data) > limit:
        raise InputTooLarge(0, f"larger than the {limit >> 20} MiB a file may have", str(path))
    return data

#: Fields are separated by a comma (with any spaces around it) or by white space.
_SPLIT = re.compile(r"\s*,\s*|\s+")


def read_text(path: str | Path, limit: int = MAX_INPUT_BYTES) -> str:
    """The UTF-8 text of ``path`` (a leading BOM dropped, at most ``limit`` bytes);
    :class:`InputError` naming the file when it is missing, unreadable or too large."""
    path = Path(path)
    try:
        return read_limited(path, limit).decode("utf-8-sig")  # a BOM is not part of the first field
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except UnicodeDecodeError as err:
        raise InputError(f"{path}: not UTF-8 text (byte {err.start})") from None
    except OSError as err:
        raise InputError(f"{path}: cannot read: {os_reason(err)}") from None


def data_rows(text: str, source: str) -> Iterator[tuple[str, int, str, list[str]]]:
    r"""(``"<source> row <n>"``, n, the stripped line, its fields) for every line that is
    neither blank nor a ``#`` comment.

    Examples
    --------
    >>> list(data_rows("# a table\n0, 1.5\n\n1 2\n", "t.csv"))
    [('t.csv row 2', 2, '0, 1.5', ['0', '1.5']), ('t.csv row 4', 4, '1 2', ['1', '2'])]
    """
    count = 0
    for lineno, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        count += 1
        if count > MAX_ROWS:
            raise InputError(f"{source} row {lineno}: more than {MAX_ROWS} data rows; at most {MAX_ROWS} are read")
        yield f"{source} row {lineno}", lineno, stripped, _SPLIT.split(stripped)


def parse_number(text: str, what: str, where: str) -> float:
    """``text`` as a finite float if it is a plain decimal number, else one :class:`InputError` line.

    Examples
    --------
    >>> parse_number("-1.5e3", "lift", "t.csv row 2")
    -1500.0
    >>> parse_number("1_00", "lift", "t.csv row 2")
    Traceback (most recent call last):
    ...
    camcam.errors.InputError: t.csv row 2: lift '1_00' is not a plain decimal number (digits, point, exponent)
    """
    if not _DECIMAL.fullmatch(text):
        try:
            float(text)
        except ValueError:
            raise InputError(f"{where}: {what} {text!r} is not a number") from None
        raise InputError(f"{where}: {what} {text!r} is not a plain decimal number (digits, point, exponent)")
    value = float(text)
    if not math.isfinite(value):
        raise InputError(f"{where}: {what} {text} is not a finite number")
    return value


def looks_numeric(text: str) -> bool:
    """True when Python would read ``text`` as a number (so a first line starting with it is data,
    not a header, even when it is not a plain decimal)."""
    try:
        float(text)
    except ValueError:
        return False
    return True
