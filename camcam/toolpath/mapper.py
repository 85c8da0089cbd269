"""How the fitter shares out independent work: a map it is handed, in this process unless told otherwise.

The fitter has work that splits into independent calls (the pieces of a
contour, the further starts of a closed arc spline).  It never starts
processes itself: it takes a :class:`Mapper`, a callable
``mapper(fn, items) -> [fn(x) for x in items]`` with a ``width`` (how many
calls it runs at once), as scipy's ``workers`` takes a map-like callable.
:data:`IN_PROCESS` is the plain loop; :class:`camcam.workers.ProcessMap` shares
the items between forked processes (the NC stage hands it in).  Every call is
the same call as in the plain loop, so the result is the same for any mapper.

Examples
--------
>>> IN_PROCESS(lambda x: x * x, range(4)), IN_PROCESS.width
([0, 1, 4, 9], 1)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Iterable, Protocol

__all__ = ["Mapper", "InProcess", "IN_PROCESS"]


class Mapper(Protocol):
    """A map-like callable: ``mapper(fn, items)`` is ``[fn(x) for x in items]``, ``width`` calls at a time."""

    width: int

    def __call__(self, fn: Callable, items: Iterable) -> list:
        """``[fn(x) for x in items]``, in the items' order."""


@dataclass(frozen=True)
class InProcess:
    """The plain loop, in this process (``width`` 1)."""

    width: int = 1

    def __call__(self, fn: Callable, items: Iterable) -> list:
        return [fn(x) for x in items]


#: The plain loop: what the fitter uses unless it is handed another mapper.
IN_PROCESS = InProcess()
