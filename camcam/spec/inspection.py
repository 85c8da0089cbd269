"""The ``[inspection]`` table: how `camcam inspect` judges a measured part.

```toml
[inspection]
tolerance = 0.02     # mm, ± band of the measured part's normal deviation; default: [machining] tolerance
```
"""

from __future__ import annotations

from dataclasses import dataclass

from camcam.spec.reader import Table

__all__ = ["InspectionSpec", "read_inspection"]


@dataclass(frozen=True, kw_only=True)
class InspectionSpec:
    """``tolerance_mm`` None: the machining tolerance is the band."""

    tolerance_mm: float | None = None


def read_inspection(t: Table) -> InspectionSpec:
    tol = t.number("tolerance", None, minimum=0.0, inclusive=False, unit="mm")
    t.done()
    return InspectionSpec(tolerance_mm=tol)
