"""Package faces that load their modules on first use (PEP 562).

A sub-package lists its public names and the module each lives in; importing
the package stays cheap (no matplotlib, ezdxf or trimesh until a name that
needs them is used), and ``from camcam.<package> import name`` works as usual.

Examples
--------
>>> getattr_, dir_, names = lazy_exports("demo", {"sqrt": "math"})
>>> getattr_("sqrt")(9.0), names
(3.0, ['sqrt'])
"""

from __future__ import annotations

import importlib
from typing import Callable

__all__ = ["lazy_exports"]


def lazy_exports(package: str, exports: dict[str, str]) -> tuple[Callable[[str], object], Callable[[], list], list]:
    """(``__getattr__``, ``__dir__``, ``__all__``) of a package exporting ``{name: module}`` lazily."""

    def getattr_(name: str):
        if name in exports:
            return getattr(importlib.import_module(exports[name]), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def dir_() -> list:
        return sorted(set(exports) | {"__all__", "__doc__", "__name__"})

    return getattr_, dir_, sorted(exports)
