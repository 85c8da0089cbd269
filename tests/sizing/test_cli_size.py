"""`camcam size` on bad input: one line naming the key, exit 2, nothing written; the in-process
path and its scale-out hint."""

from __future__ import annotations

import contextlib
import io

import pytest

from camcam.cli import main
from camcam.dask_batch import engine
from tests.sizing.helpers import BASE, ROOT, cli




BAD = [
    ("base_radius = [60, 30, 0.5]", "size.base_radius: to = 30 is below from = 60: the range is empty"),
    ("base_radius = [30, 60, 0]", "size.base_radius: step 0 must be > 0"),
    ("base_radius = [30, 60]", "size.base_radius: expected [from, to, step]"),
    ("base_radius = [-5, 10, 1]", "size.base_radius: sizes must be > 0 mm"),
    ("roller_radius = []", "size.roller_radius: expected a non-empty list"),
    ("roller_radius = [6, -8]", "size.roller_radius[1]: expected a size > 0"),
    ('law = [{ segment = 0, choices = ["cycloidal", "cubic"] }]', 'size.law[0].choices[1]: unknown law "cubic"'),
    ('law = [{ segment = 1, choices = ["cycloidal"] }]', "size.law[0].segment: segment 1 is a dwell"),
    ('law = [{ segment = 9, choices = ["cycloidal"] }]', "size.law[0].segment: expected an integer >= 0 and <= 3"),
    ('law = [{ segment = 0, choices = [] }]', "size.law[0].choices: expected a non-empty list of law names"),
    ("base_radius = [1, 10000, 0.001]", "size.base_radius: 9999001 values; a sweep is capped at 1,000,000 designs"),
    ("base_radius = [10, 1000, 0.1]\noffset = [-10, 10, 0.1]", "size: the sweep has 1,990,101 designs; it is capped at 1,000,000"),
    ("pivot_distance = [90, 100, 5]", "size.pivot_distance: a translating-roller follower has no pivot_distance to sweep"),
    ("min_curvature_radius_mm = 3\nmin_curvature_radius_rollers = 1", "size.min_curvature_radius_rollers: give min_curvature_radius_mm"),
    ("objective = \"cheapest\"", 'size.objective: expected one of "outer-radius", "pressure-angle"'),
    ("samples = 10", "size.samples: expected an integer >= 360"),
    ("colour = 1", "size.colour: unknown key"),
]


@pytest.mark.parametrize("text,message", BAD, ids=[b[0].split("=")[0].strip() + str(i) for i, b in enumerate(BAD)])
def test_bad_size_table_is_one_line_exit_2_and_writes_nothing(text, message, tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(BASE + "[size]\n" + text + "\n")
    out = tmp_path / "out"
    code, stdout, err = cli("size", str(spec), "-o", str(out))
    assert code == 2
    assert err.count("\n") == 1 and message in err, err
    assert stdout == "" and not out.exists()


def test_a_spec_without_size_table_says_so(tmp_path):
    code, _, err = cli("size", str(ROOT / "samples" / "disc-translating-roller.toml"), "-o", str(tmp_path / "o"))
    assert code == 2 and "size: missing; `camcam size` needs a [size] table" in err and err.count("\n") == 1


def test_oscillating_flat_is_not_swept(tmp_path):
    text = (ROOT / "samples" / "disc-oscillating-flat.toml").read_text() + "\n[size]\nbase_radius = [30, 40, 1]\n"
    spec = tmp_path / "s.toml"
    spec.write_text(text)
    code, _, err = cli("size", str(spec), "-o", str(tmp_path / "o"))
    assert code == 2 and "sizes translating-roller, oscillating-roller, translating-flat followers" in err


def test_workers_must_be_positive(tmp_path):
    err = io.StringIO()
    with pytest.raises(SystemExit) as stop, contextlib.redirect_stderr(err):
        main(["size", "x.toml", "--workers", "0", "-o", str(tmp_path / "o")])
    err = err.getvalue()
    assert stop.value.code == 2 and "expected a whole number of workers >= 1" in err and err.count("\n") == 1


def test_without_dask_it_runs_in_process_and_says_how_to_scale(tmp_path, monkeypatch):
    monkeypatch.setattr(engine, "dask_available", lambda: False)
    spec = tmp_path / "s.toml"
    spec.write_text(BASE.replace("[machining]", "[unused]").split("[unused]")[0]
                    + "[size]\nbase_radius = [20, 30, 5]\noffset = [0, 4, 4]\nsamples = 720\n")
    code, out, err = cli("size", str(spec), "-o", str(tmp_path / "o"), "--json")
    assert code == 0, err
    assert engine.SCALE_HINT in out  # the hint rides in the printed summary, never in the files
    assert err == ""  # stderr is not a terminal here: no hint line there
    assert not any(engine.SCALE_HINT in p.read_text(errors="ignore") for p in (tmp_path / "o").iterdir())
    # and --scheduler without dask is bad input
    code, _, err = cli("size", str(spec), "-o", str(tmp_path / "o2"), "--scheduler", "tcp://127.0.0.1:8786")
    assert code == 2 and "--scheduler: needs dask.distributed: pip install 'camcam[scale]'" in err
    assert not (tmp_path / "o2").exists()


def test_no_feasible_design_writes_the_chart_and_exits_3(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(BASE + "[size]\nbase_radius = [10, 12, 1]\noffset = 0\nmax_pressure_angle_deg = 10\nsamples = 720\n")
    code, out, err = cli("size", str(spec), "-o", str(tmp_path / "o"), "--in-process", "--table", "csv")
    assert code == 3
    assert err.startswith("camcam: FAIL: none of the 3 designs meets every constraint") and err.count("\n") == 1
    names = sorted(p.name for p in (tmp_path / "o").iterdir())
    assert "size-translating-roller-sizing.png" in names and not any(n.endswith("best.toml") for n in names)


def test_progress_bar_only_when_asked(tmp_path):
    spec = tmp_path / "s.toml"
    # 2 law combinations: two chunks, so there is a bar to draw
    spec.write_text(BASE + '[size]\nbase_radius = [20, 30, 5]\nlaw = [{ segment = 0, choices = ["cycloidal", "harmonic"] }]\n'
                    "samples = 720\n")
    code, _, err = cli("size", str(spec), "-o", str(tmp_path / "a"), "--in-process")
    assert code == 0 and err == ""  # stderr is no terminal here and --progress was not given
    code, _, err = cli("size", str(spec), "-o", str(tmp_path / "b"), "--in-process", "--progress")
    assert code == 0
    assert "\rcamcam: 6 designs [###############...............] 1/2" in err and err.endswith("2/2\n")
    assert sorted(p.read_bytes() for p in (tmp_path / "a").iterdir()) == sorted(p.read_bytes() for p in (tmp_path / "b").iterdir())


def test_size_takes_force_as_its_own_advice(tmp_path):
    """Issue 50 item 11: `size` suggested --force for an earlier run's folder, then rejected the flag."""
    spec = tmp_path / "s.toml"
    spec.write_text(BASE + "[size]\nbase_radius = [10, 12, 1]\noffset = 0\nmax_pressure_angle_deg = 10\nsamples = 720\n")
    args = ("size", str(spec), "-o", str(tmp_path / "o"), "--in-process", "--table", "csv")
    assert cli(*args)[0] == 3
    code, _, err = cli(*args)
    assert code == 2 and "add --force" in err and err.count("\n") == 1
    assert cli(*args, "--force")[0] == 3  # replaced; still no feasible design
