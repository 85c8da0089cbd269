"""The machining stage on the real samples: rs274 reads every program back, within tolerance both ways."""

import functools
import math
from pathlib import Path

import ezdxf
import pytest

from camcam.errors import GeometryError
from camcam.export.nc import nc_dxf, nc_files
from camcam.geometry.build import build_cam
from camcam.spec import load_spec
from camcam.toolpath.deviation import measure_deviation
from camcam.toolpath.elements import Line
from camcam.verify import checked
from camcam.verify.rs274 import feed_passes, print_margin_mm, rs274_available, run_rs274

ROOT = Path(__file__).resolve().parents[2]
CAM_SAMPLES = ["disc-translating-roller", "disc-translating-flat", "disc-oscillating-flat", "disc-oscillating-roller",
               "disc-groove", "cylindrical-translating", "cylindrical-oscillating"]
POST_SAMPLES = ["fanuc", "haas", "grbl", "sinumerik", "heidenhain"]  # linuxcnc's is disc-translating-roller's
FIVE_AXIS_SAMPLES = ["cylindrical-oscillating"]  # measured in 3-D by tests/nc/test_fiveaxis.py
RS274_READS = {"linuxcnc", "fanuc", "haas", "grbl"}  # ISO G-code; Sinumerik's G71 and Klartext it cannot read
needs_rs274 = pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")


def _path(sample: str) -> Path:
    return ROOT / "samples" / (f"posts/{sample[5:]}.toml" if sample.startswith("post-") else f"{sample}.toml")


@functools.lru_cache(maxsize=None)
def built_and_result(sample: str):
    spec = load_spec(_path(sample))
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    return spec, built, checked(built, spec.machining, spec.name, spec.stock)


def _interpreted_disc(result, moves):
    passes = feed_passes(moves)
    assert len(passes) == len(result.passes)
    for (z, elements), p in zip(passes, result.passes):
        c = result.contours[p.contour]
        # the interpreted pass runs at the depth its record states (rs274 prints 4 decimals)
        assert z == pytest.approx(p.z, abs=1e-4)
        yield c, (elements[1:-1] if c.leads else elements), p.finishes


def _interpreted_rotary(result, moves):
    """Feed runs at constant Z with A moving: (X, A) → lines developed at the reference radius (u, x)."""
    rho, runs, cur, z = result.reference_radius_mm, [], [], None
    for m in moves:
        if m.kind == "line" and z is not None and m.z == z:
            cur.append((m.x, m.a))
            continue
        if len(cur) > 2:
            runs.append(cur)
        cur, z = [(m.x, m.a)], (m.z if m.kind == "line" else None)
    if len(cur) > 2:
        runs.append(cur)
    assert len(runs) == len(result.passes)
    for run, k in zip(runs, (p.contour for p in result.passes)):
        uv = [(math.radians(a) * rho, x) for x, a in run]
        yield result.contours[k], tuple(Line(p, q) for p, q in zip(uv[:-1], uv[1:]) if p != q), True


@needs_rs274
@pytest.mark.parametrize("sample", [s for s in CAM_SAMPLES if s not in FIVE_AXIS_SAMPLES]
                         + [f"post-{p}" for p in POST_SAMPLES])
def test_sample_program_through_rs274(tmp_path, sample):
    spec, built, result = built_and_result(sample)
    if result.post.name not in RS274_READS:
        pytest.skip(f"rs274 does not read the {result.post.name} dialect")
    f = tmp_path / result.program_filename
    f.write_text(result.program.text)
    moves = run_rs274(f)
    tol = result.tolerance_mm
    # rs274 prints 4 decimals; with ≤ 4 decimals it reproduces the program exactly (margin 0); an A word
    # printed to 1e-4° moves a point by ≤ 0.5e-4° · ρ, already inside the fit's rounding budget
    margin = print_margin_mm(result.post.decimals)
    interpreted = _interpreted_rotary(result, moves) if result.rotary else _interpreted_disc(result, moves)
    checked = 0
    for contour, elements, finish in interpreted:
        if not finish:
            continue
        dev = measure_deviation(contour.curve, elements, margin_mm=0.02 * tol)
        assert dev.max_deviation_mm <= tol + margin, contour.label
        checked += 1
    assert checked >= len(result.contours)


@pytest.mark.parametrize("sample", ["disc-groove", "cylindrical-oscillating"])
def test_same_spec_same_bytes(sample):
    spec, built, result = built_and_result(sample)
    again = checked(built, spec.machining, spec.name)
    assert nc_files(built, again) == nc_files(built, result)


@pytest.mark.parametrize("sample", ["disc-translating-roller", "disc-groove", "cylindrical-translating"])
def test_dxf_reads_and_audits(tmp_path, sample):
    spec, built, result = built_and_result(sample)
    f = tmp_path / "cam.dxf"
    f.write_bytes(nc_dxf(built, result).data)
    doc = ezdxf.readfile(f)
    auditor = doc.audit()
    assert not auditor.has_errors
    assert doc.header["$INSUNITS"] == 4  # millimetres
    layers = {e.dxf.layer for e in doc.modelspace()}
    assert {"TOOL_CENTRE", "PROFILE", "TITLE-BLOCK", "ANGLE-ZERO", "ROLLER", "PITCH"} <= layers
    kinds = {e.dxftype() for e in doc.modelspace().query("*[layer=='TOOL_CENTRE']")}
    assert kinds <= {"LINE", "ARC"} and kinds


def test_report_blocks_against_lower_bound():
    _, _, result = built_and_result("disc-translating-roller")
    for c in result.contours:
        for s in c.segments:
            assert s.blocks <= s.target  # the target: ≤ 1.5·N_lb + 2 per motion segment


def _with_tool(sample, diameter):
    spec, built, _ = built_and_result(sample)
    from dataclasses import replace
    return built, replace(spec.machining, tool_diameter_mm=diameter)


def test_tool_wider_than_groove_fails():
    built, m = _with_tool("disc-groove", 22.0)
    with pytest.raises(GeometryError, match="wider than the groove"):
        checked(built, m, "g")


def test_tool_wider_than_cylindrical_groove_fails():
    built, m = _with_tool("cylindrical-oscillating", 31.0)
    with pytest.raises(GeometryError, match="wider than the groove"):
        checked(built, m, "c")


def test_tool_too_small_for_groove_fails():
    built, m = _with_tool("disc-groove", 6.0)
    with pytest.raises(GeometryError, match="below a third"):
        checked(built, m, "g")


def test_tool_larger_than_concave_radius_fails():
    from camcam.spec.document import parse_spec

    # a steep 25 mm cycloidal rise over 60°: the profile is concave (radius 82.66 mm) near 12°
    law = {"law": "cycloidal", "from": 0, "to": 60, "rise": 25.0}
    data = {"motion": {"rpm": 60, "segments": [law, {"law": "dwell", "from": 60, "to": 180},
                                               {"law": "cycloidal", "from": 180, "to": 240, "rise": -25.0},
                                               {"law": "dwell", "from": 240, "to": 360}]},
            "cam": {"kind": "disc", "base_radius": 60.0, "thickness": 10.0},
            "follower": {"kind": "translating-roller", "roller_radius": 5.0},
            "machining": {"tool_diameter": 170.0, "feed": 300.0, "spindle": 2000, "depth": 10.0}}
    spec = parse_spec(data, Path("concave.toml"))
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    assert built.analysis.profile.min_concave_radius is not None
    with pytest.raises(GeometryError, match="smallest concave radius is 82.661 mm"):
        checked(built, spec.machining, "d")


def test_roughing_spiral_made_beside_the_fit_is_the_same_program():
    """With a second process the NC step makes a disc profile's roughing spiral in a child beside the contour's
    fit (camcam.nc.job): the same program text as made in process, and the spiral's error raised as itself."""
    from camcam.nc import machine_program

    spec, built, _ = built_and_result("disc-translating-roller")
    one = machine_program(built, spec.machining, spec.name, spec.stock, workers=1)
    two = machine_program(built, spec.machining, spec.name, spec.stock, workers=2)
    assert any(p.kind == "rough" for p in two.toolpath.passes)  # the sample has a spiral to make
    assert two.program.text == one.program.text


def test_roughing_spiral_error_from_its_child_is_the_users_error(monkeypatch):
    import camcam.nc.job as job

    def falls_apart(*args, **kwargs):
        raise GeometryError("roughing: an offset of the part falls apart; cannot spiral to it")

    monkeypatch.setattr(job, "disc_spiral", falls_apart)  # the child forked after this inherits it
    spec, built, _ = built_and_result("disc-translating-roller")
    with pytest.raises(GeometryError, match="falls apart"):
        job.machine_program(built, spec.machining, spec.name, spec.stock, workers=2)
