"""The laws a spec can name, with their parameters and defaults.

Other stages add sources of laws without touching this table: a spec may also
name a law file (``law = "file:…"``, optimised laws) that the spec reader loads.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import MappingProxyType
from typing import Callable, Mapping

from camcam.motion import standard
from camcam.motion.law import MotionLaw

__all__ = ["LawEntry", "LAWS", "make_law"]


@dataclass(frozen=True)
class LawEntry:
    """A named law: its factory, its parameters with defaults, and one line of description."""

    name: str
    factory: Callable[..., MotionLaw]
    parameters: Mapping[str, float]
    description: str


def _entry(name, factory, description, **parameters) -> tuple[str, LawEntry]:
    return name, LawEntry(name, factory, MappingProxyType(parameters), description)


#: Spec name → entry.  ``dwell`` is listed separately: it has no rise.
LAWS: Mapping[str, LawEntry] = MappingProxyType(
    dict(
        [
            _entry("cycloidal", standard.cycloidal, "cycloidal (sine acceleration)"),
            _entry("harmonic", standard.harmonic, "simple harmonic"),
            _entry("polynomial-345", standard.polynomial_345, "polynomial 3-4-5"),
            _entry("polynomial-4567", standard.polynomial_4567, "polynomial 4-5-6-7"),
            _entry("modified-trapezoid", standard.modified_trapezoid, "modified trapezoid"),
            _entry("modified-sine", standard.modified_sine, "modified sine"),
            _entry(
                "modified-constant-velocity",
                standard.modified_constant_velocity,
                "modified constant velocity (MCV 50)",
            ),
            _entry("parabolic", standard.parabolic, "constant acceleration (parabolic)"),
            _entry(
                "yu-lee",
                standard.yu_lee,
                "Yu and Lee's parameterised polynomial (seed 000, eq. 9)",
                beta7=0.65,
                beta9=-0.665,
                beta11=1.33,
            ),
        ]
    )
)


def make_law(name: str, **parameters: float) -> MotionLaw:
    """The law ``name`` with ``parameters`` over its defaults.

    Raises
    ------
    KeyError
        For an unknown name or parameter (the message lists the known ones).

    Examples
    --------
    >>> round(make_law("yu-lee").characteristics().Jm, 6)
    81.0
    """
    if name not in LAWS:
        raise KeyError(f"unknown law {name!r}; known: {', '.join(sorted(LAWS))}, dwell")
    entry = LAWS[name]
    unknown = set(parameters) - set(entry.parameters)
    if unknown:
        known = ", ".join(entry.parameters) or "none"
        raise KeyError(f"law {name!r} has no parameter {sorted(unknown)[0]!r}; known: {known}")
    return entry.factory(**{**entry.parameters, **parameters})
