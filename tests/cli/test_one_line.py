"""Issue 43, one honest line: warnings and notes go to stdout (and the report), to stderr only with --verbose;
exit 2 and exit 3 print exactly one stderr line; a default the user never set gives no warning."""

from __future__ import annotations

import json
from pathlib import Path

from camcam.spec import load_spec
from tests.cli.test_exit_status import cli

ROOT = Path(__file__).resolve().parents[2]
BARREL = ROOT / "samples" / "cylindrical-translating.toml"

#: Harmonic laws meet dwells with an acceleration jump, so each join is warned about (motion.strict = false).
JUMPS = """name = "jumps"
[motion]
rpm = 60
segments = [
  { law = "harmonic", from = 0, to = 180, rise = 10.0 },
  { law = "dwell", from = 180, to = 200 },
  { law = "harmonic", from = 200, to = 360, rise = -10.0 },
]
"""


def test_join_warnings_go_to_stdout_or_with_verbose_to_stderr(tmp_path):
    spec = tmp_path / "jumps.toml"
    spec.write_text(JUMPS)
    code, out, err = cli("motion", str(spec), "-o", str(tmp_path / "a"))
    assert code == 0 and err == ""
    warned = [ln for ln in out.splitlines() if ln.startswith("warning: ")]
    assert warned and "acceleration" in warned[0]
    code, out, err = cli("motion", str(spec), "-o", str(tmp_path / "b"), "--json")
    assert code == 0 and err == ""
    assert [f"warning: {w}" for w in json.loads(out)["warnings"]] == warned  # one JSON object, warnings in it
    code, out, err = cli("motion", str(spec), "-o", str(tmp_path / "c"), "--verbose")
    assert code == 0 and [f"camcam: {ln}" for ln in warned] == err.splitlines()


def test_a_barrel_mode_default_is_lines_so_it_is_never_warned_about(tmp_path):
    spec = load_spec(BARREL)
    assert "mode" not in BARREL.read_text() and spec.machining.mode == "lines"
    explicit = tmp_path / "arcs.toml"
    explicit.write_text(BARREL.read_text().replace("[machining]\n", '[machining]\nmode = "arcs"\n'))
    assert load_spec(explicit).machining.mode == "arcs"  # what the user asked for (the run notes it has lines only)
    disc = load_spec(ROOT / "samples" / "disc-translating-flat.toml")
    assert disc.machining.mode == "arcs"


def test_exit_3_is_one_stderr_line_and_the_notes_are_on_stdout(tmp_path):
    small = ROOT / "samples" / "cylindrical-translating-small-tool.toml"
    spec = tmp_path / "small.toml"
    spec.write_text(small.read_text().replace("accept_out_of_tolerance = true", "accept_out_of_tolerance = false"))
    code, out, err = cli("run", str(spec), "-o", str(tmp_path / "out"))
    assert code == 3
    assert len(err.splitlines()) == 1 and err.startswith("camcam: FAIL: 3-D groove deviation"), err
    assert "note: 4-axis: X along the cam axis" in out
    assert "mode arcs" not in out  # the mode was never set: no note about it
    # the pressure angle (37.38° over the 30° default) is on the verdict's page, not on stderr
    report = json.loads((tmp_path / "out" / "cylindrical-translating-small-tool-report.json").read_text())
    states = {c["name"]: c["state"] for c in report["verdict"]["checks"]}
    assert states["pressure angle"] == "WARN" and report["verdict"]["status"] == "FAIL"
    assert "pressure angle 37.38 deg over the advisory limit 30 deg" in out
    code, out, err = cli("run", str(spec), "-o", str(tmp_path / "verbose"), "--verbose")
    lines = err.splitlines()
    assert code == 3 and lines[-1].startswith("camcam: FAIL: ")
    assert any(ln.startswith("camcam: note: 4-axis: X along the cam axis") for ln in lines[:-1])
