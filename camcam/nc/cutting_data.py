"""Cutting data per pass kind: spindle speed and feed from a cutting speed and a chip load, and material presets.

For an end mill of diameter D (mm) with z flutes, a cutting speed vc (m/min) and a chip load (feed per
tooth) fz (mm) give

    n  = 1000 · vc / (π · D)      rev/min
    vf = fz · z · n               mm/min

(every catalogue's formulas, e.g. WIDIA's "Calculating Speed and Feed": n = vc·1000/(π·D1), vf = fz·Z·n).
Both are rounded to whole rev/min and mm/min, as a machinist types them, and the feed is taken from the
rounded speed.  ``[machining] flutes`` turns the model on; each of ``rough``, ``finish`` and ``spring``
then takes a ``[machining.<kind>]`` table with ``fz_mm`` and ``vc_m_min`` or ``rpm`` and ``feed_mm_min``,
or a preset from ``[cam] material`` (:data:`PRESETS`), or the single ``feed`` and ``spindle`` (a spring
pass without its own table cuts as the finish pass does).  A groove's full-width centre pass and the
helical bore cut with the rough data.

Presets: a carbide end mill (uncoated or TiAlN), starting values from two published tables, the figures
below are the middle of each published range unless said otherwise:

* steel, cast iron, aluminium: Tungaloy general catalogue 2020-2021, solid carbide end mills, "Standard
  cutting conditions" (p. 1091): roughing row "Slotting / Roughing (ae = 0.4 × D or over)" and
  finishing row "Finishing (ae = 0.05~0.1 × D)", the ø10-ø12 column; carbon steel rough vc 140-180,
  fz 0.045-0.07, finish vc 170-280, fz 0.11-0.12; cast iron rough vc 80-180, fz 0.045-0.08, finish
  vc 180-280, fz 0.09-0.1; aluminium alloy rough vc 300-750, fz 0.045-0.08, finish vc 350-900,
  fz 0.11-0.15 (aluminium: the lower end of vc, 300 and 350 m/min, a cam shop's spindle rather than
  a high-speed one);
* brass: G.W. Schultz Tool, "Speeds and Feeds for Carbide End Mill Cutting Tools", row "Brass / Bronze
  Soft": 400-700 SFM (122-213 m/min), fz 0.003 in (0.0762 mm) at ½ in diameter; rough at the middle,
  168 m/min, finish at the top, 213 m/min ("speeds should be increased … when taking light cuts").

The chip loads are scaled in proportion to the diameter from the column's middle diameter (ø11 mm;
brass ø12.7 mm), as ISCAR's Multi-Master user guide states them (fz = k × D).  They are starting
values: the tool maker's data for the actual tool come first.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["CUT_KINDS", "KIND_DATA", "MaterialPreset", "PRESETS", "CuttingData", "preset_for", "spindle_rpm",
           "feed_mm_min", "from_chip_load", "from_speed_and_feed"]

#: The pass kinds that take their own cutting data.
CUT_KINDS = ("rough", "finish", "spring")

#: Which cutting data each pass kind (:data:`camcam.toolpath.path.PASS_KINDS`) cuts with.
KIND_DATA = {"rough": "rough", "slot": "rough", "bore": "rough", "finish": "finish", "spring": "spring"}


@dataclass(frozen=True, kw_only=True)
class MaterialPreset:
    """Starting cutting data of a carbide end mill in one material: vc (m/min) and fz per mm of diameter."""

    name: str
    rough_vc_m_min: float
    finish_vc_m_min: float
    rough_fz_per_mm: float  # fz = this × D
    finish_fz_per_mm: float
    source: str

    def data(self, kind: str) -> tuple[float, float]:
        """(vc m/min, fz per mm of diameter) for ``kind`` (rough, finish or spring: spring cuts as finish)."""
        if kind == "rough":
            return self.rough_vc_m_min, self.rough_fz_per_mm
        return self.finish_vc_m_min, self.finish_fz_per_mm


_TUNGALOY = "Tungaloy general catalogue 2020-2021 p. 1091, solid carbide end mills, standard cutting conditions"

#: The presets ``[cam] material`` may name (see the module notes for the figures' sources).
PRESETS = {
    "steel": MaterialPreset(name="steel", rough_vc_m_min=160.0, finish_vc_m_min=225.0,
                            rough_fz_per_mm=0.0575 / 11, finish_fz_per_mm=0.115 / 11,
                            source=f"{_TUNGALOY}, carbon steel"),
    "cast iron": MaterialPreset(name="cast iron", rough_vc_m_min=130.0, finish_vc_m_min=230.0,
                                rough_fz_per_mm=0.0625 / 11, finish_fz_per_mm=0.095 / 11,
                                source=f"{_TUNGALOY}, cast iron"),
    "aluminium": MaterialPreset(name="aluminium", rough_vc_m_min=300.0, finish_vc_m_min=350.0,
                                rough_fz_per_mm=0.0625 / 11, finish_fz_per_mm=0.13 / 11,
                                source=f"{_TUNGALOY}, aluminium alloy (vc at the range's lower end)"),
    "brass": MaterialPreset(name="brass", rough_vc_m_min=168.0, finish_vc_m_min=213.0,
                            rough_fz_per_mm=0.0762 / 12.7, finish_fz_per_mm=0.0762 / 12.7,
                            source="G.W. Schultz Tool, Speeds and Feeds for Carbide End Mills, brass/bronze soft"),
}

#: Words of a ``[cam] material`` that name a preset, tried in this order ("cast steel" is steel, "cast
#: iron" is not).
_NAMES = (("cast iron", "cast iron"), ("grey iron", "cast iron"), ("gray iron", "cast iron"),
          ("steel", "steel"), ("aluminium", "aluminium"), ("aluminum", "aluminium"), ("brass", "brass"))


def preset_for(material: str | None) -> MaterialPreset | None:
    """The preset a free-text ``[cam] material`` names, or None.

    Examples
    --------
    >>> preset_for("C45 steel").name, preset_for("EN-GJL-250 grey iron").name, preset_for("PEEK")
    ('steel', 'cast iron', None)
    """
    text = (material or "").lower()
    return next((PRESETS[p] for word, p in _NAMES if word in text), None)


def spindle_rpm(vc_m_min: float, diameter_mm: float) -> float:
    """n = 1000 · vc / (π · D), rounded to whole rev/min.

    Examples
    --------
    >>> spindle_rpm(160.0, 16.0)
    3183.0
    """
    return float(round(1000.0 * vc_m_min / (math.pi * diameter_mm)))


def feed_mm_min(fz_mm: float, flutes: int, rpm: float) -> float:
    """vf = fz · z · n, rounded to whole mm/min.

    Examples
    --------
    >>> feed_mm_min(0.0836, 3, 3183.0)
    798.0
    """
    return float(round(fz_mm * flutes * rpm))


@dataclass(frozen=True, kw_only=True)
class CuttingData:
    """One pass kind's cutting data: what the program prints (``rpm``, ``feed_mm_min``) and where it came from.

    ``vc_m_min`` and ``fz_mm`` are the given ones, or those the given speed and feed make (from rpm
    and feed).  ``origin`` says which: "spec", "preset steel", "feed and spindle", "as finish" (a
    spring pass without its own table).
    """

    kind: str
    rpm: float
    feed_mm_min: float
    flutes: int
    vc_m_min: float
    fz_mm: float
    origin: str

    def describe(self) -> str:
        """The figures as a pass comment and the setup sheet state them.

        Examples
        --------
        >>> from_chip_load("rough", vc_m_min=160, fz_mm=0.0836, flutes=3, diameter_mm=16, origin="spec").describe()
        'vc 160 m/min, fz 0.0836 mm x 3 flutes: S3183 F798'
        """
        return (f"vc {self.vc_m_min:.4g} m/min, fz {self.fz_mm:.4g} mm x {self.flutes} flutes: "
                f"S{self.rpm:g} F{self.feed_mm_min:g}")


def from_chip_load(kind: str, *, vc_m_min: float, fz_mm: float, flutes: int, diameter_mm: float,
                   origin: str) -> CuttingData:
    """Cutting data from a cutting speed and a chip load (rpm and feed rounded, the feed from the rounded rpm)."""
    rpm = spindle_rpm(vc_m_min, diameter_mm)
    return CuttingData(kind=kind, rpm=rpm, feed_mm_min=feed_mm_min(fz_mm, flutes, rpm), flutes=flutes,
                       vc_m_min=vc_m_min, fz_mm=fz_mm, origin=origin)


def from_speed_and_feed(kind: str, *, rpm: float, feed: float, flutes: int, diameter_mm: float,
                        origin: str) -> CuttingData:
    """Cutting data from an explicit speed and feed; vc and fz are what they make with this tool."""
    return CuttingData(kind=kind, rpm=rpm, feed_mm_min=feed, flutes=flutes,
                       vc_m_min=math.pi * diameter_mm * rpm / 1000.0, fz_mm=feed / (flutes * rpm), origin=origin)
