"""A program's own printed path as a measured part (issue 46): inspecting the part outline the printed tool
path cuts reproduces `run`'s deviation figure within the sampling bound."""

from __future__ import annotations

import numpy as np

from camcam.inspect import InspectOptions, MeasuredPart, inspect_part
from camcam.nc import machine_program
from camcam.toolpath.elements import element_points
from camcam.toolpath.outline import part_outline
from tests.inspection.conftest import built

#: Points every 0.05 mm along the outline: between two of them the deviation (a smooth function along an
#: element, whose second derivative is at most the curvature difference of element and profile, < 1/5 mm⁻¹
#: on this cam) passes the larger end by at most ½·0.2·(0.025)² = 6e-5 mm; the elements' ends are points.
SPACING_MM = 0.05
SAMPLING_BOUND_MM = 6e-5


def test_printed_outline_reproduces_the_run_deviation():
    spec, prog, b = built("disc-translating-roller.toml")
    m = machine_program(b, spec.machining, spec.name)
    c = m.contours[0]
    # the outline the tool cuts: the printed tool-centre path offset by the tool radius towards the material
    pts, _ = element_points(part_outline(c.printed, -c.offset_mm), SPACING_MM)
    part = MeasuredPart(kind="cmm", values=pts, rows=tuple(range(2, len(pts) + 2)), source="readback")
    ins = inspect_part(b, spec.cam, spec.follower, prog, part,
                       InspectOptions(tolerance_mm=spec.machining.tolerance_mm, align="none", motion=False))
    assert not ins.outliers  # no measuring noise: nothing to flag
    measured = max(ins.max_deviation_mm, -ins.min_deviation_mm)
    run = c.deviation  # two-sided on the printed numbers; max_deviation_mm adds its own sampling margin
    assert abs(measured - max(run.path_to_curve_mm, run.curve_to_path_mm)) <= SAMPLING_BOUND_MM
    assert measured <= run.max_deviation_mm
    assert np.isfinite(ins.alignment.rotation_deg) and ins.alignment.rotation_deg == 0.0  # align none: nothing fitted
