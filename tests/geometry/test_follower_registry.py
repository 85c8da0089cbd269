"""The follower registry (issue 44): each kind is one class, and no stage outside it compares kind strings.

Two proofs: a source scan (no module of the package outside ``camcam/geometry/followers/`` holds a
kind string in its code, or asks a kind's name for a prefix or suffix), and a fifth, toy kind that
this module registers, without touching any other file, and runs through the spec, the geometry,
the design checks, the NC job, the report, sizing and reverse design.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pytest

from camcam.geometry.followers import FOLLOWER_KINDS, FOLLOWERS, TranslatingRoller, follower_kind, register, unregister

PACKAGE = Path(__file__).resolve().parents[2] / "camcam"
REGISTRY = PACKAGE / "geometry" / "followers"
SAMPLE = PACKAGE.parent / "samples" / "disc-translating-roller.toml"


def _documentation(tree: ast.AST) -> set[int]:
    """ids of the string constants that are documentation: docstrings and other bare string statements."""
    return {id(node.value) for node in ast.walk(tree)
            if isinstance(node, ast.Expr) and isinstance(node.value, ast.Constant) and isinstance(node.value.value, str)}


def kind_dispatch(source: str) -> list[tuple[int, str]]:
    """(line, text) of every place in ``source`` that names a follower kind in code.

    A string constant holding a kind (``kind == "oscillating-roller"``, ``{"translating-roller": 30.0}``,
    ``f"... translating-flat ..."``), or ``startswith``/``endswith`` of a part of one (``kind.startswith("oscillating")``).
    Docstrings and comments (doctests among them) are documentation, not dispatch.
    """
    tree = ast.parse(source)
    docs = _documentation(tree)
    parts = {p for k in FOLLOWER_KINDS for p in k.split("-")}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs:
            if any(k in node.value for k in FOLLOWER_KINDS):
                found.append((node.lineno, node.value))
        elif (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
              and node.func.attr in ("startswith", "endswith")):
            for arg in node.args:
                if isinstance(arg, ast.Constant) and isinstance(arg.value, str) and arg.value.strip("-") in parts:
                    found.append((node.lineno, f".{node.func.attr}({arg.value!r})"))
    return sorted(found)


def test_the_scan_finds_what_it_guards_against():
    src = ('"""translating-roller in a docstring is fine."""\n'
           'if f.kind == "oscillating-roller": pass\n'
           'unit = "deg" if kind.startswith("oscillating") else "mm"\n'
           'roller = kind.endswith("roller")\n'
           'title = f"a translating-flat follower"\n')
    assert [line for line, _ in kind_dispatch(src)] == [2, 3, 4, 5]


def test_no_module_outside_the_registry_dispatches_on_kind_strings():
    """Adding a kind touches its module and the registry (and a sample), no other module of the package."""
    bad = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if REGISTRY in path.parents:
            continue
        for line, text in kind_dispatch(path.read_text(encoding="utf-8")):
            bad.append(f"{path.relative_to(PACKAGE.parent)}:{line}: {text!r}")
    assert not bad, "kind strings outside camcam/geometry/followers/:\n" + "\n".join(bad)


def test_every_kind_declares_what_the_stages_ask():
    for kind, cls in FOLLOWERS.items():
        assert cls.kind == kind and follower_kind(kind) is cls
        assert cls.unit in ("mm", "deg") and isinstance(cls.is_roller, bool)
        assert set(cls.spec_keys) <= {"roller_radius", "offset", "pivot_distance", "arm_length"}
        assert ("roller_radius" in cls.spec_keys) == cls.is_roller
        assert 0 < cls.default_max_pressure_angle_deg < 90
        assert cls.barrel is None or (cls.barrel.kind == kind and cls.barrel.unit == cls.unit and cls.is_roller)
        assert cls.size_axes is None or cls.size_axes[0] == "base_radius"
    with pytest.raises(KeyError, match="unknown follower kind 'knife-edge'; known: translating-roller"):
        follower_kind("knife-edge")


# --- a fifth kind, registered here and nowhere else ---------------------------------------------------


@dataclass(frozen=True)
class ToyRoller(TranslatingRoller):
    """A translating roller on the cam's centre line, with its own pressure-angle limit and sizing axes."""

    kind = "toy-roller"
    spec_keys = ("roller_radius",)
    default_max_pressure_angle_deg = 21.0
    barrel = None
    size_axes = ("base_radius", "roller_radius")

    @classmethod
    def from_spec(cls, f) -> "ToyRoller":
        return cls(f.roller_radius)

    @classmethod
    def from_params(cls, params) -> "ToyRoller":
        return cls(params["roller_radius"])

    @staticmethod
    def size_figures(ps, sigma, params):
        rb = np.asarray(params["base_radius"], float)
        return TranslatingRoller.figures(ps, sigma, rb, np.zeros_like(rb), params["roller_radius"])

    @classmethod
    def datum_note(cls, offset: float) -> str:
        return "the toy roller rides on the Y axis"


@pytest.fixture
def toy():
    register(ToyRoller)
    try:
        yield ToyRoller
    finally:
        unregister(ToyRoller.kind)
    assert "toy-roller" not in FOLLOWERS


def _spec_text(kind: str, size: bool = False) -> str:
    text = SAMPLE.read_text(encoding="utf-8")
    text = text.replace('kind = "translating-roller"\nroller_radius = 10.0\noffset = 5.0\n',
                        f'kind = "{kind}"\nroller_radius = 10.0\n')
    assert f'kind = "{kind}"' in text
    if size:
        text += ('\n[size]\nbase_radius = [30, 50, 5]\nroller_radius = [8, 10]\n'
                 'min_curvature_radius_mm = 5.0\nsamples = 720\n')
    return text


def test_register_refuses_a_taken_kind():
    with pytest.raises(ValueError, match="registered already"):
        register(TranslatingRoller)
    with pytest.raises(ValueError, match="built in"):
        unregister("translating-roller")


def test_a_registered_kind_runs_through_every_stage(toy, tmp_path):
    """The toy kind is read, built, checked, machined, reported, sized and reversed by asking its class."""
    from camcam.flow import run_job
    from camcam.geometry.build import build_cam
    from camcam.reverse import MeasuredPoints, ReverseOptions, design_motion, reverse_design
    from camcam.reverse.synth import measure_disc
    from camcam.spec import load_spec

    path = tmp_path / "toy.toml"
    path.write_text(_spec_text("toy-roller"), encoding="utf-8")
    spec = load_spec(path)
    assert spec.follower.kind == "toy-roller" and spec.unit == "mm" and spec.follower.is_roller

    # geometry: the toy's disc follower, the same cam as a translating roller without offset
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    assert isinstance(built.cam.follower, ToyRoller)
    ref = tmp_path / "ref.toml"
    ref.write_text(_spec_text("translating-roller"), encoding="utf-8")
    ref_spec = load_spec(ref)
    ref_built = build_cam(ref_spec.cam, ref_spec.follower, ref_spec.motion.program(ref_spec.unit))
    assert built.analysis.max_pressure_angle_deg.value == ref_built.analysis.max_pressure_angle_deg.value

    # the whole job: design checks take the toy's own limit (21°), the setup sheet its own datum
    job = run_job(spec)
    pa = next(c for c in job.verdict.checks if c.name == "pressure angle")
    assert pa.limit == 21.0 and "toy-roller follower" in pa.where
    html = job.files[f"{spec.name}-report.html"].decode("utf-8")
    assert "the toy roller rides on the Y axis" in html
    program = next(data for name, data in job.files.items() if name.endswith(".ngc")).decode("ascii")
    assert "toy-roller follower" in program

    # sizing: the toy's axes and kernel
    sized = tmp_path / "sized.toml"
    sized.write_text(_spec_text("toy-roller", size=True), encoding="utf-8")
    size = load_spec(sized).size
    assert [a.name for a in size.axes] == ["base_radius", "roller_radius"]
    assert size.max_pressure_angle_deg == 21.0
    from camcam.sizing.exact_check import exact_figures
    from camcam.sizing.kernels import block_figures
    from camcam.sizing.samples import sample_program

    prog = spec.motion.program(spec.unit)
    figs = block_figures("toy-roller", sample_program(prog, 3600), 1,
                         {"base_radius": np.array([40.0]), "roller_radius": np.array([10.0])})
    exact = exact_figures("toy-roller", prog, {"base_radius": 40.0, "roller_radius": 10.0}, "ccw")
    assert figs["max_pressure_angle_deg"][0] == pytest.approx(exact.max_pressure_angle_deg, abs=1e-3)

    # reverse design: the toy's inverse kinematics
    xy = measure_disc(built.cam, 360, np.random.default_rng(3), shuffle=True)
    points = MeasuredPoints(np.round(xy, 6), tuple(range(2, xy.shape[0] + 2)), "p.csv")
    res = reverse_design(points, spec.cam, spec.follower, ReverseOptions(smoothing=False))
    angles = np.arange(360.0)
    assert res.follower_kind == "toy-roller"
    assert np.abs(res.motion(angles, 0) - design_motion(prog, "disc", angles, 0)).max() < 1e-4


def test_a_kind_missing_a_declaration_cannot_be_made():
    """FollowerKind's required methods are abstract: a kind that leaves out its inverse kinematics fails when
    made, naming the method, instead of raising NotImplementedError in the middle of a reverse design."""
    import dataclasses

    from camcam.geometry.followers.base import FollowerKind

    @dataclasses.dataclass(frozen=True)
    class Half(FollowerKind):
        kind = "half"

        @classmethod
        def from_spec(cls, f):
            return cls()

        def element(self, s, base_radius, sigma):
            raise AssertionError("not called")

        @classmethod
        def datum_note(cls, offset):
            return ""

    with pytest.raises(TypeError, match="invert"):
        Half()
