"""The ``[report]`` table: what the tolerance report shows.

```toml
[report]
inspection_step = 10.0    # degrees of cam angle between inspection-table rows
strict = false            # true: a design check's miss (pressure angle, cut depth,
                          # finish allowance) fails the run (exit 3) instead of warning
step_file = true          # with the cad extra: write <name>.step (false: no STEP, and no OpenCascade
                          # import, about a CPU second a job: for batches that fill every core)
```
"""

from __future__ import annotations

from dataclasses import dataclass

from camcam.spec.reader import Table

__all__ = ["ReportSpec", "read_report", "DEFAULT_REPORT", "MIN_INSPECTION_STEP_DEG"]

#: Finest inspection step (degrees): 3600 rows, each solved against the printed path.
MIN_INSPECTION_STEP_DEG = 0.1


@dataclass(frozen=True)
class ReportSpec:
    inspection_step_deg: float = 10.0
    strict: bool = False
    step_file: bool = True


DEFAULT_REPORT = ReportSpec()


def read_report(t: Table) -> ReportSpec:
    step = t.number("inspection_step", DEFAULT_REPORT.inspection_step_deg, minimum=MIN_INSPECTION_STEP_DEG, maximum=90.0, unit="degrees")
    strict = t.boolean("strict", DEFAULT_REPORT.strict)
    step_file = t.boolean("step_file", DEFAULT_REPORT.step_file)
    t.done()
    return ReportSpec(step, strict, step_file)
