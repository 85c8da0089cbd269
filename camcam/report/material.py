"""The report's "Stock and material removal" section: the blank, the passes and the 2.5-D check of the program."""

from __future__ import annotations

from camcam.nc.passes import SLOT_KINDS
from camcam.report.html import DataTable, KeyValues, Paragraph, Section

__all__ = ["material_section"]


def _fig(v, unit="mm", digits=4) -> str:
    return "—" if v is None else f"{v:.{digits}f} {unit}"


def material_section(m) -> Section | None:
    """The section for a disc or face-groove :class:`~camcam.nc.job.MachiningResult` (None for other jobs)."""
    if m.removal is None or m.blank is None:
        return None
    b, r = m.blank, m.removal
    status = {c.name: ("ok" if c.ok else "FAIL") for c in m.checks}
    rows = (
        ("blank", b.describe()),
        ("top face", b.top_note()),
        ("bore", b.bore_note()),
        ("depth levels", ", ".join(f"Z{z:g}" for z in r.levels)),
        ("largest radial engagement (outside slot passes)",
         "none: every pass is a slot" if all(p.kind in SLOT_KINDS for p in m.passes) else
         f"{_fig(r.max_engagement_mm)} of the stepover {r.stepover_mm:g} mm — {status['radial engagement']}"
         + (f" ({r.engagement_where})" if r.engagement_where else "")),
        ("largest engagement in slot passes (stated)", _fig(r.max_slot_engagement_mm)),
        ("plunges into material", f"{r.plunges} — {status['plunges into material']}"
         + (f" (first: {r.plunge_where})" if r.plunge_where else "")),
        ("rapids touching material", f"{r.rapid_touches} — {status['rapids touching material']}"
         + (f" (first: {r.rapid_where})" if r.rapid_where else "")),
        ("material left over the profile", f"{_fig(r.material_left_mm)} of ±{r.tolerance_mm:g} mm — "
         f"{status['material left over the profile']} ({r.left_where})"),
        ("overcut into the profile", f"{_fig(r.overcut_mm)} of ±{r.tolerance_mm:g} mm — "
         f"{status['overcut into the profile']}" + (f" ({r.overcut_where})" if r.overcut_where else "")),
    )
    if r.rough_clearance_mm is not None:
        rows += (("roughing stock left on the profile", f"{_fig(r.rough_clearance_mm)} (finish allowance "
                  f"{r.allowance_mm:g} mm)"),)
    table = DataTable(("pass", "kind", "cuts", "Z (mm)"),
                      tuple((str(i + 1), p.kind, m.contours[p.contour].label if p.contour is not None else
                             ("bore" if p.kind == "bore" else "blank → finish allowance"), f"{p.z:g}")
                            for i, p in enumerate(m.passes)))
    return Section("Stock and material removal", (
        Paragraph("The printed program read back move by move and checked against the blank, 2.5-D, at every depth "
                  "level: the width of material the tool's leading half meets (radial engagement), feed moves that "
                  "descend into material steeper than the ramp angle, rapids that touch material, and the part left "
                  "at the final depth against the design profile."),
        KeyValues(rows), table))
