"""The verdict of a job: every check that can fail, with its figure and its limit.

Each stage that measures something a user relies on (the NC deviation, the
3-D groove, the material left, the pressure angle) returns :class:`Check`
values; ``camcam run`` gathers them in one :class:`Verdict`, puts it at the
top of the report, and exits with status 3 when it fails (files written, out
of tolerance) unless the spec accepts that.

Examples
--------
>>> c = Check("NC deviation", 0.012, 0.01, "mm", ok=False, where="contour profile",
...           advice="tighten nothing: use a smaller tolerance floor")
>>> v = Verdict((c,))
>>> v.status
'FAIL'
>>> v.line()
'FAIL: NC deviation 0.012 mm over the limit 0.01 mm (contour profile); tighten nothing: use a smaller tolerance floor'
>>> Verdict((c,), accepted=True).exit_status
0
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Check", "Verdict", "OUT_OF_TOLERANCE"]

#: Exit status of a run whose files were written but whose verdict is FAIL.
OUT_OF_TOLERANCE = 3

_SEVERITIES = ("fail", "warn")


@dataclass(frozen=True)
class Check:
    """One measured figure held to a limit.

    Parameters
    ----------
    name : str
        What was measured, short ("3-D groove deviation", "pressure angle").
    value, limit : float
        The figure and the limit it is held to, in ``unit``.
    unit : str
        "mm", "deg", ...
    ok : bool
        Whether the figure meets the limit.
    severity : {"fail", "warn"}
        What a miss means: the run fails (exit 3) or it only warns.
    where : str
        Where the figure occurs ("flank 0, r = 75.00 mm, cam angle 123.40°").
    advice : str
        The way out of a miss, one sentence.
    """

    name: str
    value: float
    limit: float
    unit: str
    ok: bool
    severity: str = "fail"
    where: str = ""
    advice: str = ""

    def __post_init__(self) -> None:
        if self.severity not in _SEVERITIES:
            raise ValueError(f"severity must be one of {_SEVERITIES}, got {self.severity!r}")

    @property
    def fails(self) -> bool:
        """A miss that fails the run."""
        return not self.ok and self.severity == "fail"

    def describe(self) -> str:
        """One line: the figure against its limit, where, and the way out of a miss."""
        rel = "within" if self.ok else "over"
        text = f"{self.name} {self.value:.4g} {self.unit} {rel} the limit {self.limit:g} {self.unit}"
        if self.where:
            text += f" ({self.where})"
        if not self.ok and self.advice:
            text += f"; {self.advice}"
        return text

    def as_dict(self) -> dict:
        return {"name": self.name, "value": self.value, "limit": self.limit, "unit": self.unit, "ok": self.ok,
                "severity": self.severity, "where": self.where, "advice": self.advice}


@dataclass(frozen=True)
class Verdict:
    """All the checks of one job; FAIL when any failing check misses.

    ``accepted`` (``[machining] accept_out_of_tolerance = true``) keeps the
    FAIL on the page but turns the exit status to 0.
    """

    checks: tuple[Check, ...]
    accepted: bool = False

    @property
    def failures(self) -> tuple[Check, ...]:
        return tuple(c for c in self.checks if c.fails)

    @property
    def warnings(self) -> tuple[Check, ...]:
        return tuple(c for c in self.checks if not c.ok and c.severity == "warn")

    @property
    def passed(self) -> bool:
        return not self.failures

    @property
    def status(self) -> str:
        return "PASS" if self.passed else "FAIL"

    @property
    def exit_status(self) -> int:
        """0 when passed or accepted, else :data:`OUT_OF_TOLERANCE`."""
        return 0 if self.passed or self.accepted else OUT_OF_TOLERANCE

    def line(self) -> str:
        """One line: the status and, on FAIL, the worst failing check with its way out."""
        if self.passed:
            n = len(self.checks)
            return f"PASS: {n} check{'' if n == 1 else 's'} within {'its limit' if n == 1 else 'their limits'}"
        first = self.failures[0]
        more = f" (and {len(self.failures) - 1} more)" if len(self.failures) > 1 else ""
        return f"FAIL: {first.describe()}{more}"

    def as_dict(self) -> dict:
        return {"status": self.status, "accepted": self.accepted, "checks": [c.as_dict() for c in self.checks]}
