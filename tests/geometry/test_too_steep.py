"""A cusp no base radius avoids names the segment it is in (campaign case 50:7,
tests/geometry/data/too-steep-oscillating-flat-50-7.toml): five of seed 50's sixty cases, oscillating flat-faced
followers, were told only "no base radius up to 100 m avoids the undercut; the motion is too steep for this
follower", with no field and nothing to change."""

import math
from dataclasses import replace
from pathlib import Path

import pytest

from camcam.cli import main
from camcam.errors import GeometryError
from camcam.geometry.analysis import check_undercut, undercut_margin
from camcam.geometry.build import disc_follower
from camcam.geometry.disc import DiscCam
from camcam.motion.program import MotionProgram, Segment
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
SPEC = Path(__file__).parent / "data" / "too-steep-oscillating-flat-50-7.toml"


def _cam(spec, base_radius_mm, pivot_mm, program=None):
    program = spec.motion.program(spec.unit) if program is None else program
    return DiscCam(disc_follower(replace(spec.follower, pivot_distance=pivot_mm)), program, base_radius_mm,
                   spec.cam.rotation)


def test_the_cusp_of_case_50_7_is_beyond_any_base_radius():
    """Why no base radius is advised: the cusp's radius of curvature stays negative as the base radius grows
    towards the pivot (where the face loses contact) and as the pivot moves out (deeper)."""
    spec = load_spec(SPEC)
    d = spec.follower.pivot_distance
    margins = [undercut_margin(_cam(spec, f * d, d))[0] for f in (0.5, 0.8, 0.9)]
    assert margins[0] < margins[1] < margins[2] < 0  # -56.3, -19.8, -4.1 mm: closer, never there
    with pytest.raises(GeometryError, match="loses contact"):
        _cam(spec, 0.95 * d, d)
    assert undercut_margin(_cam(spec, 30.0, 80.0))[0] < undercut_margin(_cam(spec, 30.0, d))[0]


def test_the_error_names_the_segment_and_what_avoids_it(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["run", str(SPEC), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and not out.exists()  # one line, nothing written
    assert err.startswith("camcam: error: motion.segments[2]: cusp at cam angle 221.")  # the return, 181–285°
    assert "in its cycloidal from 181° to 285° (rise -25°)" in err
    assert err.endswith("for this oscillating-flat follower; expected a longer segment or a smaller rise")


def test_a_lift_table_is_named_as_the_table():
    """A table program is one segment the spec does not list: the error names ``motion.lift_table``."""
    spec = load_spec(SPEC)
    table = load_spec(ROOT / "samples" / "lift" / "noisy-lift.toml")
    law = table.motion.program(table.unit).segments[0].law
    steep = MotionProgram((Segment(law, 0.0, 360.0, 3.0, base=0.0),), 120, "deg")  # the 10 mm table as 30°
    cam = _cam(spec, 20.0, 30.0, steep)
    margin, t = undercut_margin(cam)
    assert margin < 0 and 220.0 < math.degrees(t) < 235.0  # -28.2 mm at 227°
    with pytest.raises(GeometryError, match=r"^motion\.lift_table: cusp at cam angle 22[0-9]\.[0-9]{2}°, and no "
                                            r"base radius up to 100 m avoids it: .*expected a gentler lift"):
        check_undercut(cam)


def test_a_cusp_at_a_dwells_start_names_the_segment_that_moves_there():
    """Campaign case 53:30: the cusp lies at 59°, the end of a parabolic rise and the start of a dwell; the
    error named "its dwell from 59° to 97° (rise 0°)" and asked for a smaller rise of it."""
    with pytest.raises(GeometryError) as err:
        spec = load_spec(Path(__file__).parent / "data" / "too-steep-at-a-dwell-53-30.toml")
        check_undercut(_cam(spec, spec.cam.base_radius, spec.follower.pivot_distance))
    assert str(err.value).startswith("motion.segments[1]: cusp at cam angle 59.00° in its parabolic from 19° to 59° "
                                     "(rise 25°)")
