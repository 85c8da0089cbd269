"""A second reader of the STEP (issue 48): FreeCAD's ``freecadcmd`` (Debian ``freecad``, OpenCascade 7.6, a
different build and version from the cad extra's) opens the file and reports its solid and volume.

Skips with the reason where ``freecadcmd`` is not installed (``.ci/run`` installs it).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess

import pytest

pytest.importorskip("OCP", reason="the cad extra (cadquery-ocp-novtk) is not installed: pip install '.[cad]'")
if shutil.which("freecadcmd") is None:
    pytest.skip("freecadcmd is not installed (Debian: apt-get install --no-install-recommends freecad)",
                allow_module_level=True)

from camcam.geometry.exact_volume import cam_volume  # noqa: E402
from tests.export.test_step import BARRELS, DISCS, job  # noqa: E402

_READ = """import json, os
import Part
shape = Part.Shape()
shape.read(os.environ["CAMCAM_STEP"])
print("CAMCAM " + json.dumps({"valid": shape.isValid(), "solids": len(shape.Solids),
                              "closed": all(s.isClosed() for s in shape.Shells), "volume_mm3": shape.Volume,
                              "area_mm2": shape.Area}))
"""


def freecad_reads(step, tmp_path) -> dict:
    script = tmp_path / "read.py"
    script.write_text(_READ)
    r = subprocess.run(["freecadcmd", str(script)], capture_output=True, text=True, timeout=300,
                       env={**os.environ, "CAMCAM_STEP": str(step)})
    lines = [ln for ln in r.stdout.splitlines() if ln.startswith("CAMCAM ")]
    assert lines, f"freecadcmd printed no result ({r.returncode}): {r.stdout[-300:]} {r.stderr[-300:]}"
    return json.loads(lines[-1][len("CAMCAM "):])


@pytest.mark.parametrize("name", DISCS + BARRELS[:1])
def test_freecad_opens_the_step_as_one_closed_valid_solid_of_the_exact_volume(name, tmp_path):
    spec, built, data, _ = job(name)
    step = tmp_path / f"{spec.name}.step"
    step.write_bytes(data)
    got = freecad_reads(step, tmp_path)
    assert got["valid"] and got["closed"] and got["solids"] == 1
    exact = cam_volume(built)
    # FreeCAD's own volume integration (its default accuracy, 1e-5 seen on OpenCascade's side) and the faces'
    # 1e-4 mm: within 0.1 % as the issue asks, and within 1e-5 of the exact volume on these samples
    assert abs(got["volume_mm3"] - exact) <= 1e-5 * exact
