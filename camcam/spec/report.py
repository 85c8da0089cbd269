"""The ``[report]`` table: what the tolerance report shows.

```toml
[report]
inspection_step = 10.0    # degrees of cam angle between inspection-table rows
strict = false            # true: a design check's miss (pressure angle, cut depth,
                          # finish allowance) fails the run (exit 3) instead of warning
```
"""

from __future__ import annotations

from dataclasses import dataclass

from camcam.spec.reader import Table

__all__ = ["ReportSpec", "read_report", "DEFAULT_REPORT"]


@dataclass(frozen=True)
class ReportSpec:
    inspection_step_deg: float = 10.0
    strict: bool = False


DEFAULT_REPORT = ReportSpec()


def read_report(t: Table) -> ReportSpec:
    step = t.number("inspection_step", DEFAULT_REPORT.inspection_step_deg, minimum=0.0, maximum=90.0, inclusive=False, unit="degrees")
    strict = t.boolean("strict", DEFAULT_REPORT.strict)
    t.done()
    return ReportSpec(step, strict)
