"""``[stock]`` and the roughing keys at the boundary: one line naming the key, exit 2, nothing written."""

from pathlib import Path

import pytest

from camcam.cli import main

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.parametrize("sample, old, new, start", [
    ("disc-translating-roller", "diameter = 125.0", "diameter = 110.0",
     "camcam: error: stock.diameter: 110 mm is smaller than the cam: its largest radius is 59.928 mm"),
    ("disc-translating-roller", 'kind = "round"        # a', 'kind = "square"        # a',
     'camcam: error: stock.kind: expected one of "round", "offset", got "square"'),
    ("disc-translating-roller", "top_allowance = 0.0", "top_allowance = -1.0",
     "camcam: error: stock.top_allowance: expected a number >= 0 mm, got -1"),
    ("disc-groove", 'kind = "round"        # a Ø180', 'kind = "offset"\nallowance = 2.0 # a Ø180',
     'camcam: error: stock.kind: "offset" needs an open disc cam'),
    ("disc-translating-roller", "bore = 12.0", "bore = 62.0",
     "camcam: error: cam.bore: Ø62 mm is larger than the base circle minus the roller; expected at most Ø60 mm"),
    ("disc-translating-roller", "spring_pass = true", "spring_pass = true\nstepover = 1.5",
     "camcam: error: machining.stepover: expected a number > 0 and < 1, got 1.5"),
    ("disc-translating-roller", "spring_pass = true", "spring_pass = true\nbore = true",
     "camcam: error: machining.bore: the tool Ø16 mm does not fit the bore Ø12 mm"),
])
def test_bad_stock_is_one_line(tmp_path, capsys, sample, old, new, start):
    text = (ROOT / "samples" / f"{sample}.toml").read_text()
    assert old in text
    spec = tmp_path / "bad.toml"
    spec.write_text(text.replace(old, new))
    assert main(["run", str(spec), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(start) and len(err.splitlines()) == 1, err
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").iterdir())


def test_a_groove_of_slots_says_so_instead_of_engagement_zero(tmp_path, capsys):
    """disc-groove is cut by slot passes alone: the radial engagement is measured outside slots only, so the
    summary printed "largest engagement 0.000 mm of 8 mm" (a figure over no moves); it now names the slots and
    their width, the tool's diameter (Ø20 mm: a slot engages all of it; 0.01 mm is the probe's resolution)."""
    assert main(["run", str(ROOT / "samples" / "disc-groove.toml"), "-o", str(tmp_path)]) == 0
    line = next(x for x in capsys.readouterr().out.splitlines() if x.startswith("material:"))
    assert "every pass a slot (engagement " in line and "largest engagement" not in line, line
    width = float(line.split("every pass a slot (engagement ")[1].split(" mm")[0])
    assert width == pytest.approx(20.0, abs=0.01), line
    html = (tmp_path / "disc-groove-report.html").read_text()
    assert "none: every pass is a slot" in html
