"""The follower registry: kind string → the class that owns the kind.

Each follower kind is one module here holding one class (a
:class:`~camcam.geometry.followers.base.FollowerKind`): its disc-frame geometry,
its barrel-frame follower (if it runs on a barrel cam), its ``[follower]`` keys,
the unit of its lift, its default pressure-angle limit, its closed-form sizing
kernel and its inverse kinematics for reverse design.  The other stages look
the kind up here (:func:`follower_kind`) and ask the class; none compares kind
strings (``tests/geometry/test_follower_registry.py``).

Adding a kind: its module (a ``FollowerKind`` subclass), one line in
:data:`FOLLOWERS` below, and a sample spec that runs it.  :func:`register`
adds one at run time (the tests register a toy kind).

Examples
--------
>>> FOLLOWER_KINDS
('translating-roller', 'oscillating-roller', 'translating-flat', 'oscillating-flat')
>>> f = follower_kind("oscillating-roller")
>>> f.unit, f.is_roller, f.default_max_pressure_angle_deg, f.barrel_axes
('deg', True, 35.0, (5, 4))
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Mapping

from camcam.geometry.followers.base import Element, FollowerKind
from camcam.geometry.followers.oscillating_flat import OscillatingFlat
from camcam.geometry.followers.oscillating_roller import BarrelOscillatingRoller, OscillatingRoller
from camcam.geometry.followers.translating_flat import TranslatingFlat
from camcam.geometry.followers.translating_roller import BarrelTranslatingRoller, TranslatingRoller

__all__ = ["FOLLOWERS", "FOLLOWER_KINDS", "follower_kind", "register", "unregister", "FollowerKind", "Element",
           "TranslatingRoller", "OscillatingRoller", "TranslatingFlat", "OscillatingFlat",
           "BarrelTranslatingRoller", "BarrelOscillatingRoller"]

_KINDS: dict[str, type[FollowerKind]] = {
    cls.kind: cls for cls in (TranslatingRoller, OscillatingRoller, TranslatingFlat, OscillatingFlat)
}

#: Kind string → class, in the order the spec documents them (a read-only view: :func:`register` adds to it).
FOLLOWERS: Mapping[str, type[FollowerKind]] = MappingProxyType(_KINDS)

#: The built-in kinds (``tuple(FOLLOWERS)`` also lists registered ones).
FOLLOWER_KINDS = tuple(_KINDS)


def follower_kind(kind: str) -> type[FollowerKind]:
    """The class of follower ``kind``.

    Raises
    ------
    KeyError
        For an unknown kind (the message lists the known ones).
    """
    try:
        return _KINDS[kind]
    except KeyError:
        raise KeyError(f"unknown follower kind {kind!r}; known: {', '.join(_KINDS)}") from None


def register(cls: type[FollowerKind]) -> type[FollowerKind]:
    """Add the kind ``cls`` (a :class:`FollowerKind` with its own ``kind`` string); returns ``cls``.

    Raises
    ------
    ValueError
        When the kind string is taken.
    """
    if cls.kind in _KINDS:
        raise ValueError(f"follower kind {cls.kind!r} is registered already")
    _KINDS[cls.kind] = cls
    return cls


def unregister(kind: str) -> None:
    """Remove a kind added by :func:`register` (the built-in ones stay)."""
    if kind in FOLLOWER_KINDS:
        raise ValueError(f"follower kind {kind!r} is built in")
    _KINDS.pop(kind, None)
