"""Issue 47: the tool holder ([machining] holder_diameter, stick_out) is checked against the blank at every
move of the printed program; a holder that hits is refused with one line naming the move (exit 2)."""

import re
from pathlib import Path

import pytest

from camcam.cli import main
from camcam.errors import SpecError
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]


def _spec(tmp_path: Path, sample: str, extra: str) -> Path:
    text = re.sub(r"^(holder_diameter|stick_out) = .*\n", "", (ROOT / "samples" / f"{sample}.toml").read_text(),
                  flags=re.M)  # the sample's own holder (disc-translating-roller: Ø40 at 30 mm, clear)
    spec = tmp_path / f"{sample}.toml"
    spec.write_text(text.replace("[machining]\n", "[machining]\n" + extra, 1))
    return spec


def test_disc_holder_that_hits_the_blank_is_refused_naming_the_move(tmp_path, capsys):
    # the sample cuts to Z-12 inside a Ø125 blank whose top is Z0: a 10 mm stick-out puts the holder's
    # face at Z-2 on the last level; 12 mm is the least that clears
    spec = _spec(tmp_path, "disc-translating-roller", "holder_diameter = 40.0\nstick_out = 10.0\n")
    out = tmp_path / "out"
    assert main(["run", str(spec), "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1, err
    assert re.match(r"camcam: error: machining\.stick_out: 10 mm: the holder Ø40 mm hits the blank at move \d+ "
                    r"\(pass \d+/\d+, G[0-3] to X[-\d.]+ Y[-\d.]+ Z-12\): holder face at Z-2; a stick-out of at least "
                    r"12 mm clears every move", err[0]), err[0]
    assert not out.exists() or not any(out.iterdir())  # nothing written


def test_disc_holder_that_clears_runs(tmp_path, capsys):
    spec = _spec(tmp_path, "disc-translating-roller", "holder_diameter = 40.0\nstick_out = 12.0\n")
    assert main(["run", str(spec), "-o", str(tmp_path / "out")]) == 0  # the face just reaches Z0 at Z-12
    html = (tmp_path / "out" / "disc-translating-roller-report.html").read_text()
    assert "; holder Ø40 mm at stick-out 12 mm (clear of the blank at every move)</td>" in html  # the setup sheet


def test_barrel_holder_hits_the_cylinder_then_clears(tmp_path, capsys):
    # R50 cylinder, groove 10 mm deep: the tip goes to about Z40, so an 8 mm stick-out puts the face inside
    spec = _spec(tmp_path, "cylindrical-translating", "holder_diameter = 30.0\nstick_out = 8.0\n")
    assert main(["run", str(spec), "-o", str(tmp_path / "a")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "machining.stick_out: 8 mm: the holder Ø30 mm hits the blank at pose" in err[0], err
    need = float(re.search(r"at least ([\d.]+) mm clears", err[0]).group(1))
    # the deepest tip is the groove floor (R40) or up to one printed step and the 4-axis corner dip below it
    assert 10.0 <= need <= 11.0, need
    ok = _spec(tmp_path, "cylindrical-translating", f"holder_diameter = 30.0\nstick_out = {need:g}\n")
    assert main(["run", str(ok), "-o", str(tmp_path / "b")]) == 0  # the stick-out it names clears


def test_the_disc_sample_states_a_clearing_holder():
    spec = load_spec(ROOT / "samples" / "disc-translating-roller.toml")
    assert (spec.machining.holder_diameter_mm, spec.machining.stick_out_mm) == (40.0, 30.0)  # exact: TOML literals


def test_holder_keys_go_together(tmp_path):
    spec = _spec(tmp_path, "disc-translating-roller", "holder_diameter = 40.0\n")
    with pytest.raises(SpecError, match=r"machining\.holder_diameter: 40 mm needs \[machining\] stick_out too"):
        load_spec(spec)
