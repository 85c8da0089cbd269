"""The verdict of a job: every check that can fail, with its figure and its limit.

Each stage that measures something a user relies on (the NC deviation, the
3-D groove, the material left, the pressure angle) returns :class:`Check`
values; ``camcam run`` gathers them in one :class:`Verdict`, puts it at the
top of the report, and exits with status 3 when it fails (files written, out
of tolerance) unless the spec accepts that.  Each check's state is PASS (within
its limit), WARN (over an advisory limit: ``severity="warn"``) or FAIL; the
verdict is the worst of them, and only FAIL changes the exit status.

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
>>> pa = Check("pressure angle", 46.39, 35, "deg", ok=False, severity="warn", advice="raise the base radius")
>>> w = Verdict((pa, Check("NC deviation", 0.008, 0.01, "mm", ok=True)))
>>> pa.state, w.status, w.exit_status
('WARN', 'WARN', 0)
>>> w.line()
'WARN: pressure angle 46.39 deg over the advisory limit 35 deg; raise the base radius; 1 other check within its limit'
>>> Check("radius of curvature", 3.0, 7.5, "mm", ok=False, at_least=True).describe()
'radius of curvature 3 mm below the limit 7.5 mm'
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass

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
    at_least : bool
        The limit is a least value (a radius of curvature), not a largest one.
    """

    name: str
    value: float
    limit: float
    unit: str
    _: KW_ONLY
    ok: bool
    severity: str = "fail"
    where: str = ""
    advice: str = ""
    at_least: bool = False

    def __post_init__(self) -> None:
        if self.severity not in _SEVERITIES:
            raise ValueError(f"severity must be one of {_SEVERITIES}, got {self.severity!r}")

    @property
    def fails(self) -> bool:
        """A miss that fails the run."""
        return not self.ok and self.severity == "fail"

    @property
    def state(self) -> str:
        """"PASS" (within its limit), "WARN" (over an advisory limit) or "FAIL"."""
        return "PASS" if self.ok else ("FAIL" if self.severity == "fail" else "WARN")

    def describe(self) -> str:
        """One line: the figure against its limit, where, and the way out of a miss."""
        rel = "within" if self.ok else ("below" if self.at_least else "over")
        kind = "advisory limit" if self.state == "WARN" else "limit"
        text = f"{self.name} {self.value:.4g} {self.unit} {rel} the {kind} {self.limit:g} {self.unit}"
        if self.where:
            text += f" ({self.where})"
        if not self.ok and self.advice:
            text += f"; {self.advice}"
        return text

    def as_dict(self) -> dict:
        return {"name": self.name, "value": self.value, "limit": self.limit, "unit": self.unit, "ok": self.ok,
                "severity": self.severity, "state": self.state, "bound": "min" if self.at_least else "max",
                "where": self.where, "advice": self.advice}


@dataclass(frozen=True)
class Verdict:
    """All the checks of one job; FAIL when any failing check misses, WARN when only advisory ones do.

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
        """"FAIL", "WARN" (every miss is advisory: the run still exits 0) or "PASS"."""
        return "FAIL" if self.failures else ("WARN" if self.warnings else "PASS")

    @property
    def exit_status(self) -> int:
        """0 when passed or accepted, else :data:`OUT_OF_TOLERANCE`."""
        return 0 if self.passed or self.accepted else OUT_OF_TOLERANCE

    def line(self) -> str:
        """One line: the status and, on FAIL or WARN, the first check that missed with its way out."""
        if self.status == "PASS":
            n = len(self.checks)
            return f"PASS: {n} check{'' if n == 1 else 's'} within {'its limit' if n == 1 else 'their limits'}"
        if self.status == "WARN":
            first, n = self.warnings[0], len(self.warnings)
            more = f" (and {n - 1} more warning{'' if n == 2 else 's'})" if n > 1 else ""
            k = sum(c.ok for c in self.checks)
            within = f"; {k} other check{' within its limit' if k == 1 else 's within their limits'}" if k else ""
            return f"WARN: {first.describe()}{more}{within}"
        first = self.failures[0]
        more = f" (and {len(self.failures) - 1} more)" if len(self.failures) > 1 else ""
        return f"FAIL: {first.describe()}{more}"

    def as_dict(self) -> dict:
        return {"status": self.status, "accepted": self.accepted, "checks": [c.as_dict() for c in self.checks]}
