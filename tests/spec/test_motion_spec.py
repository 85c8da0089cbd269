"""Every validation message of the [motion] table."""

import textwrap

import pytest

from camcam.errors import SpecError
from camcam.spec import load_spec

GOOD = """
name = "demo"
[motion]
rpm = 120
segments = [
  { law = "modified-sine", from = 0, to = 120, rise = 20.0 },
  { law = "dwell", from = 120, to = 180 },
  { law = "cycloidal", from = 180, to = 300, rise = -20.0 },
  { law = "dwell", from = 300, to = 360 },
]
"""


def write(tmp_path, text, name="s.toml"):
    p = tmp_path / name
    p.write_text(textwrap.dedent(text))
    return p


def test_good_spec(tmp_path):
    spec = load_spec(write(tmp_path, GOOD))
    assert spec.name == "demo"
    prog = spec.motion.program()
    assert float(prog.lift(2.5)) == pytest.approx(20.0, abs=1e-12)  # 143°: in the dwell at 20 mm


BAD = [
    (GOOD.replace("to = 300, rise", "to = 370, rise"), "motion.segments[2].to: 370 is past 360"),
    (GOOD.replace("rpm = 120", "rpm = -5"), "motion.rpm: expected a number > 0 rev/min, got -5"),
    (GOOD.replace("rpm = 120", 'rpm = "fast"'), 'motion.rpm: expected a number > 0 rev/min, got "fast"'),
    (GOOD.replace("rpm = 120", ""), "motion.rpm: missing; expected a number > 0 rev/min"),
    (GOOD.replace("rpm = 120", "rpm = 120\nrmp = 3"), "motion.rmp: unknown key"),
    (GOOD.replace('"modified-sine"', '"sine"'), 'motion.segments[0].law: unknown law "sine"; known: cycloidal'),
    (GOOD.replace("from = 0,", "from = 10,"), "motion.segments[0].from: 10 must be 0"),
    (GOOD.replace("from = 120, to = 180", "from = 130, to = 180"), "motion.segments[1].from: 130 leaves a gap after the previous segment, which ends at 120"),
    (GOOD.replace("from = 120, to = 180", "from = 110, to = 180"), "motion.segments[1].from: 110 overlaps the previous segment"),
    (GOOD.replace("from = 300, to = 360", "from = 300, to = 350"), "motion.segments[3].to: 350: the last segment must end at 360"),
    (GOOD.replace("from = 120, to = 180", "from = 120, to = 120"), "motion.segments[1].to: 120 is not after from = 120"),
    (GOOD.replace("to = 180 }", "to = 180, rise = 3 }"), "motion.segments[1].rise: 3: a dwell has no rise"),
    (GOOD.replace(", rise = 20.0", ""), "motion.segments[0].rise: missing; expected a number mm"),
    (GOOD.replace("rise = -20.0", "rise = -19.0"), "motion.segments: rises add up to +1 mm"),
    (GOOD.replace("rise = 20.0 }", "rise = 20.0, beta7 = 1 }"), "motion.segments[0].beta7: unknown key"),
    (GOOD.replace('name = "demo"', 'name = "a b"'), 'name: "a b" must be 1–64 letters'),
    (GOOD + "\n[bogus]\n", "bogus: unknown key"),
    ("name = \n", "not valid TOML"),
    (GOOD.replace("rpm = 120", "rpm = 120\nstrict = 1"), "motion.strict: expected true or false, got 1"),
]


@pytest.mark.parametrize("text, message", BAD, ids=[m[:40] for _, m in BAD])
def test_bad_specs(tmp_path, text, message):
    with pytest.raises(SpecError) as err:
        load_spec(write(tmp_path, text))
    assert message in str(err.value)
    assert "\n" not in str(err.value)


def test_strict_rejects_jumps(tmp_path):
    text = GOOD.replace("rpm = 120", "rpm = 120\nstrict = true").replace('"cycloidal"', '"harmonic"')
    with pytest.raises(SpecError, match=r"motion.strict: acceleration jumps by .* at 180°"):
        load_spec(write(tmp_path, text))


def test_yu_lee_parameters(tmp_path):
    text = GOOD.replace('"modified-sine", from = 0, to = 120, rise = 20.0', '"yu-lee", from = 0, to = 120, rise = 20.0, beta7 = 0.5')
    spec = load_spec(write(tmp_path, text))
    assert spec.motion.segments[0].law_name == "yu-lee"


def test_missing_file(tmp_path):
    with pytest.raises(SpecError, match="no such file"):
        load_spec(tmp_path / "nope.toml")
