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

from camcam.cli import main

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "disc-translating-roller.toml"


def test_the_fitting_process_imports_no_plot_or_export_library(tmp_path):
    code = (
        "import json, sys\n"
        "from camcam.cli import main\n"
        f"rc = main(['run', {str(SAMPLE)!r}, '-o', {str(tmp_path / 'out')!r}])\n"
        "sys.stdout.flush()\n"
        "print(json.dumps({'rc': rc, 'loaded': [m for m in ('matplotlib', 'ezdxf', 'trimesh', 'scipy') "
        "if m in sys.modules]}))\n"
    )
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, check=True)
    result = json.loads(r.stdout.strip().splitlines()[-1])
    # matplotlib is imported by the plot server, ezdxf, trimesh and scipy by the drawing's prepared child,
    # which also makes the mesh and forks the material check (camcam.forked): the process that fits the
    # NC path measures its deviations with shapely's STRtree, and imports no scipy at all
    assert result == {"rc": 0, "loaded": []}
    assert {p.name for p in (tmp_path / "out").iterdir()} >= {
        "disc-translating-roller.ngc", "disc-translating-roller.dxf", "disc-translating-roller.stl",
        "disc-translating-roller-svaj.png", "disc-translating-roller-profile.png",
        "disc-translating-roller-deviation.png", "disc-translating-roller-fitted-motion.png"}


@pytest.mark.skipif(not hasattr(os, "fork"), reason="no fork: every run is in process already")
def test_children_give_the_in_process_bytes(tmp_path, monkeypatch, capsys):
    assert main(["run", str(SAMPLE), "-o", str(tmp_path / "forked")]) == 0
    monkeypatch.delattr(os, "fork")  # camcam.forked then runs every job at once, in process
    assert main(["run", str(SAMPLE), "-o", str(tmp_path / "inline")]) == 0
    forked = {p.name: p.read_bytes() for p in (tmp_path / "forked").iterdir()}
    inline = {p.name: p.read_bytes() for p in (tmp_path / "inline").iterdir()}
    assert forked.keys() == inline.keys() and len(forked) >= 12
    assert [n for n in forked if forked[n] != inline[n]] == []
