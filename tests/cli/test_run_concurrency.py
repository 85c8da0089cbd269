"""`camcam run` works beside itself: plots, drawing, model and material check in child processes.

The wall time of a run rests on two facts tested here (never the time itself:
machines are shared): the process that fits the NC path imports none of the
plotting and export libraries, and the children give the very bytes an
in-process run gives.
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

from camcam import flow
from camcam.cli import main

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "disc-translating-roller.toml"


def _json_of(code: str):
    """What the Python ``code``, run in a fresh interpreter from the project's root, prints last, as JSON."""
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    return json.loads(r.stdout.strip().splitlines()[-1])


def _at_forks_of_run(spec: Path, out: Path, probe: str) -> dict:
    """``camcam run spec`` in a fresh interpreter: its exit status and the value of the Python expression ``probe``
    in it before each fork, {"rc": …, "at_fork": […]}."""
    return _json_of(
        "import json, os, sys\n"
        "from camcam import flow\n"
        "at_fork = []\n"
        f"os.register_at_fork(before=lambda: at_fork.append({probe}))\n"
        "from camcam.cli import main\n"
        f"rc = main(['run', {str(spec)!r}, '-o', {str(out)!r}])\n"
        "sys.stdout.flush()\n"
        "print(json.dumps({'rc': rc, 'at_fork': at_fork}))\n")


def _loaded_after_run(spec: Path, out: Path) -> dict:
    code = (
        "import json, sys\n"
        "from camcam.cli import main\n"
        f"rc = main(['run', {str(spec)!r}, '-o', {str(out)!r}])\n"
        "sys.stdout.flush()\n"
        "print(json.dumps({'rc': rc, 'loaded': [m for m in ('matplotlib', 'ezdxf', 'trimesh', 'scipy', 'OCP') "
        "if m in sys.modules]}))\n"
    )
    return _json_of(code)


def test_the_fitting_process_imports_no_plot_or_export_library(tmp_path):
    result = _loaded_after_run(SAMPLE, tmp_path / "out")
    # matplotlib is imported by the plot server, ezdxf and scipy.spatial by the drawing's prepared child (OCP, for
    # the STEP, by a child of its own), which also makes the STL and runs the material check (camcam.workers): the
    # process that fits the NC path measures its deviations with shapely's STRtree, and imports no scipy at all
    assert result == {"rc": 0, "loaded": []}
    assert {p.name for p in (tmp_path / "out").iterdir()} >= {
        "disc-translating-roller.ngc", "disc-translating-roller.dxf", "disc-translating-roller.stl",
        "disc-translating-roller-svaj.png", "disc-translating-roller-profile.png",
        "disc-translating-roller-deviation.png", "disc-translating-roller-fitted-motion.png"}


def test_the_drawing_model_and_material_check_import_no_trimesh():
    # what the drawing's child runs (camcam.flow.model, drawing_and_check), here in one fresh process: the STL and
    # its figures are numpy's (trimesh, 0.2 CPU s, stays the tests' reader); the DXF's splines numpy's Hermite
    # cubics (ezdxf's dense interpolation took 23 GB on case 43:57); the check's k-d tree is scipy's, loaded
    # without the scipy.spatial package (camcam.verify.kdtree)
    code = (
        "import json, sys\n"
        "from camcam.spec import load_spec\n"
        "from camcam.geometry.build import build_cam\n"
        "from camcam import flow\n"
        f"spec = load_spec({str(SAMPLE)!r})\n"
        "built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))\n"
        "machining = flow.nc_step(spec, built)\n"
        "files, figures = flow.model(built, spec.name)\n"
        "drawn, deviation, checks = flow.drawing_and_check(built, machining, spec.machining)\n"
        "print(json.dumps({'stl': len(files), 'dxf': sum(n.endswith('.dxf') for n in drawn), 'checked': checks is not None,\n"
        "                  'loaded': [m for m in ('trimesh', 'scipy.interpolate', 'scipy.spatial') if m in sys.modules]}))\n"
    )
    assert _json_of(code) == {"stl": 1, "dxf": 1, "checked": True, "loaded": []}


def test_a_barrel_jobs_drawing_imports_no_scipy():
    # a barrel job has no blank and no material check (its groove is measured in 3-D by the NC step): its drawing's
    # child loads ezdxf only, not the check's k-d tree with scipy.sparse (0.1 CPU s, issue 49)
    code = (
        "import importlib, json, sys\n"
        "from camcam.spec import load_spec\n"
        "from camcam.geometry.build import build_cam\n"
        "from camcam import flow\n"
        f"spec = load_spec({str(ROOT / 'samples' / 'cylindrical-translating.toml')!r})\n"
        "built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))\n"
        "machining = flow.nc_step(spec, built)\n"
        "for name in flow.drawing_modules(built.spec.kind): importlib.import_module(name)\n"
        "files, figures = flow.model(built, spec.name)\n"
        "drawn, deviation, checks = flow.drawing_and_check(built, machining, spec.machining)\n"
        "print(json.dumps({'dxf': sum(n.endswith('.dxf') for n in drawn), 'checked': checks is not None,\n"
        "                  'loaded': [m for m in ('scipy', 'trimesh') if m in sys.modules]}))\n"
    )
    assert _json_of(code) == {"dxf": 1, "checked": False, "loaded": []}


@pytest.mark.parametrize("sample", ["cylindrical-translating", "cylindrical-translating-small-tool"])
def test_a_4_axis_barrel_job_imports_no_scipy(tmp_path, sample):
    # nothing of a 4-axis barrel job needs scipy, with a tool of the roller's size or a thinner one: a thinner
    # tool's flank plan q(θ) was scipy's quintic splines, which the run imported (0.26 CPU s, and 0.5 s where
    # nothing else had) before it forked the drawing's child that unpickles the plan; it is numpy's Chebyshev
    # series now (issue 49).  A barrel's drawing loads none either (test_a_barrel_jobs_drawing_imports_no_scipy)
    result = _loaded_after_run(ROOT / "samples" / f"{sample}.toml", tmp_path / "out")
    assert result == {"rc": 0, "loaded": []}


@pytest.mark.parametrize("modules", [flow.PLOT_MODULES, flow.drawing_modules("disc")], ids=["plot server", "drawing"])
def test_what_the_run_imports_for_its_children_both_of_them_import(modules):
    # flow.CHILDREN_SHARE is imported once, before the plot server and the drawing's child are forked, because
    # each would import every one of them (matplotlib's, and ezdxf's with the material check's scipy): one that
    # neither needs any more would only cost the run
    code = (
        "import importlib, json, sys\n"
        "from camcam import flow\n"
        f"for name in {list(modules)!r}: importlib.import_module(name)\n"
        "print(json.dumps([m for m in flow.CHILDREN_SHARE if m not in sys.modules]))\n"
    )
    assert _json_of(code) == []


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork: every run is in process already")
def test_every_child_of_a_run_inherits_what_its_children_share(tmp_path):
    result = _at_forks_of_run(SAMPLE, tmp_path / "out", "[m for m in flow.CHILDREN_SHARE if m not in sys.modules]")
    # the plot server, the drawing's child, the STEP's and the roughing's: none imports them again
    assert result["rc"] == 0 and len(result["at_fork"]) >= 2
    assert all(missing == [] for missing in result["at_fork"])


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork: every run is in process already")
def test_children_give_the_in_process_bytes(tmp_path, monkeypatch, capsys):
    assert main(["run", str(SAMPLE), "-o", str(tmp_path / "forked")]) == 0
    monkeypatch.delattr(os, "fork")  # camcam.workers then runs every job at once, in process
    assert main(["run", str(SAMPLE), "-o", str(tmp_path / "inline")]) == 0
    forked = {p.name: p.read_bytes() for p in (tmp_path / "forked").iterdir()}
    inline = {p.name: p.read_bytes() for p in (tmp_path / "inline").iterdir()}
    assert forked.keys() == inline.keys() and len(forked) >= 12
    assert [n for n in forked if forked[n] != inline[n]] == []


def test_single_process_forks_nothing_and_gives_the_same_bytes(tmp_path):
    # `--single-process` (issue 49: the fewest CPU seconds on a shared machine) runs the plot server's, the drawing
    # child's, the STEP's and the NC step's jobs in this one process: no fork at all, and every file the very bytes
    # of a default run, whose jobs run in child processes
    code = (
        "import json, os, sys\n"
        "forks = []\n"
        "os.register_at_fork(before=lambda: forks.append(1))\n"
        "from camcam.cli import main\n"
        f"rc = main(['run', {str(SAMPLE)!r}, '-o', {str(tmp_path / 'single')!r}, '--single-process'])\n"
        "sys.stdout.flush()\n"
        "print(json.dumps({'rc': rc, 'forks': len(forks)}))\n"
    )
    assert _json_of(code) == {"rc": 0, "forks": 0}
    assert main(["run", str(SAMPLE), "-o", str(tmp_path / "default")]) == 0
    single = {p.name: p.read_bytes() for p in (tmp_path / "single").iterdir()}
    default = {p.name: p.read_bytes() for p in (tmp_path / "default").iterdir()}
    assert single.keys() == default.keys() and len(single) >= 12
    assert [n for n in single if single[n] != default[n]] == []
