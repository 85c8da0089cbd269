"""Reading the user's data files (lift tables, point sets, law files) as text.

Every reader names the file in its one-line :class:`~camcam.errors.InputError`.
"""

from __future__ import annotations

from pathlib import Path

from camcam.errors import InputError

__all__ = ["read_text"]


def read_text(path: str | Path) -> str:
    """The UTF-8 text of ``path``; :class:`InputError` naming the file when it is missing or unreadable."""
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise InputError(f"{path}: no such file") from None
    except (OSError, UnicodeDecodeError) as err:
        raise InputError(f"{path}: cannot read: {err}") from None
