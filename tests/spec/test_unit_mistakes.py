"""Issue 43, likely unit mistakes refused with a clear line: a tolerance over 1 % of the cam's size (microns typed as
millimetres) and a feed under 50 mm/min (mm/s or in/min typed as mm/min), each unless ``units_checked = true``."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest
import tomli_w

from camcam.errors import SpecError
from camcam.spec import parse_spec
from tests.cli.test_exit_status import cli

ROOT = Path(__file__).resolve().parents[2]
DISC = ROOT / "samples" / "disc-translating-roller.toml"  # base radius 40 mm: Ø80, so at most 0.8 mm
BARREL = ROOT / "samples" / "cylindrical-translating.toml"


def _spec(sample: Path = DISC, **machining):
    doc = tomllib.loads(sample.read_text())
    doc["machining"].update(machining)
    return parse_spec(doc, sample)


def _refused(**machining) -> str:
    with pytest.raises(SpecError) as err:
        _spec(**machining)
    return str(err.value)


def test_tolerance_over_one_percent_of_the_cam_is_refused_unless_meant():
    message = _refused(tolerance=10)
    assert message == ("machining.tolerance: 10 mm is over 1 % of the cam's size (Ø80 mm: at most 0.8 mm expected); "
                       "if it is 10 µm give 0.01; or set [machining] units_checked = true if you mean 10 mm")
    assert _spec(tolerance=0.01).machining.tolerance_mm == 0.01  # the advice followed
    assert _spec(tolerance=10, units_checked=True).machining.tolerance_mm == 10.0  # "I mean it"
    assert _spec(tolerance=0.8).machining.tolerance_mm == 0.8  # 1 % itself is taken
    assert _refused(tolerance=0.81).startswith("machining.tolerance: 0.81 mm is over 1 % of the cam's size")
    # a barrel cam's size is its cylinder's diameter (radius 50 mm here)
    assert _refused(sample=BARREL, tolerance=1.5).startswith("machining.tolerance: 1.5 mm is over 1 % of the cam's "
                                                             "size (Ø100 mm: at most 1 mm expected)")


def test_feed_that_cannot_be_mm_per_min_is_refused_unless_meant():
    message = _refused(feed=6.5)
    assert message == ("machining.feed: 6.5 mm/min is slower than a cam is cut (at least 50 mm/min expected); "
                       "if it is 6.5 mm/s give 390, if it is 6.5 in/min give 165.1, or set [machining] units_checked "
                       "= true if you mean 6.5 mm/min")
    for value in re.findall(r"give ([0-9.]+)", message):  # each reading offered is taken as it stands
        assert _spec(feed=float(value)).machining.feed_mm_min == float(value)
    assert _spec(feed=6.5, units_checked=True).machining.feed_mm_min == 6.5
    assert _spec(feed=50.0).machining.feed_mm_min == 50.0
    # 1.5 in/min would still be under 50 mm/min: only the reading that makes sense is offered
    assert "in/min" not in _refused(feed=1.5)
    assert _refused(plunge_feed=20).startswith("machining.plunge_feed: 20 mm/min is slower than a cam is cut")
    # a plunge feed the user never wrote (half the feed) is no unit mistake of theirs
    assert _spec(feed=60.0).machining.plunge_feed_mm_min == 30.0
    with pytest.raises(SpecError, match=r"^machining\.units_checked: expected true or false"):
        _spec(units_checked="yes")


def test_the_cli_says_it_in_one_line_and_writes_nothing(tmp_path):
    doc = tomllib.loads(DISC.read_text())
    doc["machining"]["tolerance"] = 10
    spec = tmp_path / "microns.toml"
    spec.write_text(tomli_w.dumps(doc))
    code, out, err = cli("run", str(spec), "-o", str(tmp_path / "out"))
    assert code == 2 and out == "" and len(err.splitlines()) == 1
    assert err.startswith("camcam: error: machining.tolerance: 10 mm is over 1 % of the cam's size")
    assert not (tmp_path / "out").exists()
