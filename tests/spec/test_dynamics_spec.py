"""Every validation message of the [dynamics] table (issue 45): one line naming the key and what it expects."""

from __future__ import annotations

from pathlib import Path

import pytest

from camcam.dynamics.train import MATERIALS
from camcam.errors import SpecError
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[2]
DISC = (ROOT / "samples" / "disc-translating-roller.toml").read_text()
OSC_FLAT = (ROOT / "samples" / "disc-oscillating-flat.toml").read_text()
GROOVE = (ROOT / "samples" / "disc-groove.toml").read_text()

TRAIN = """
[dynamics]
mass_kg = 0.8
spring_rate_n_per_mm = 2.5
preload_n = 60.0
damping_ratio = 0.05
external_load_n = 20.0
friction = 0.05
roller_width_mm = 12.0
materials = { cam = "cast-iron", follower = "steel" }
allowable_contact_stress_mpa = 900.0
"""


def load(tmp_path, text):
    p = tmp_path / "s.toml"
    p.write_text(text)
    return load_spec(p)


def test_good_table(tmp_path):
    d = load(tmp_path, DISC + TRAIN).dynamics
    assert (d.mass_kg, d.spring_rate_n_per_mm, d.preload_n, d.damping_ratio) == (0.8, 2.5, 60.0, 0.05)
    assert d.cam_material == MATERIALS["cast-iron"] and d.follower_material == MATERIALS["steel"]
    assert (d.overspeed, d.speed_fluctuation, d.min_contact_force_n, d.size_spring) == (1.25, 0.05, 0.0, False)


def test_without_the_table_nothing(tmp_path):
    assert load(tmp_path, DISC).dynamics is None


def test_load_table_and_custom_material(tmp_path):
    text = DISC + TRAIN.replace("external_load_n = 20.0", "external_load_n = [[0, 10], [90, 30.5], [200, 10]]") \
        .replace('follower = "steel"', "follower = { e_gpa = 3.0, poisson = 0.35 }")
    d = load(tmp_path, text).dynamics
    assert d.external_load_table == ((0.0, 10.0), (90.0, 30.5), (200.0, 10.0))
    assert (d.follower_material.e_gpa, d.follower_material.poisson) == (3.0, 0.35)


def test_size_and_oscillating_and_groove(tmp_path):
    d = load(tmp_path, OSC_FLAT + '[dynamics]\ninertia_kgm2 = 0.01\nspring = "size"\nload_arm_mm = 70\n').dynamics
    assert d.size_spring and d.inertia_kgm2 == 0.01 and d.load_arm_mm == 70.0
    g = load(tmp_path, GROOVE + "[dynamics]\nmass_kg = 0.3\nroller_width_mm = 8\ndamping_n_s_per_m = 5\n").dynamics
    assert (g.spring_rate_n_per_mm, g.preload_n, g.damping_n_s_per_m) == (0.0, 0.0, 5.0)


BAD = [
    (DISC + TRAIN.replace("mass_kg = 0.8", "mass_kg = -1"), "dynamics.mass_kg: expected a number > 0 and < 10000 kg, got -1"),
    (DISC + TRAIN.replace("roller_width_mm = 12.0", "roller_width_mm = 0"),
     "dynamics.roller_width_mm: expected a number > 0 mm, got 0"),
    (DISC + TRAIN.replace('follower = "steel"', "follower = { e_gpa = 200, poisson = 0.5 }"),
     "dynamics.materials.follower.poisson: expected a number >= 0 and < 0.5 (Poisson's ratio; 0.5 is incompressible), got 0.5"),
    (DISC + TRAIN.replace('cam = "cast-iron"', 'cam = "unobtainium"'),
     'dynamics.materials.cam: "unobtainium": expected one of "steel", "stainless-steel", "cast-iron", "ductile-iron", '
     '"bronze", "aluminum", "titanium", "nylon", or { e_gpa = …, poisson = … }'),
    (DISC + TRAIN.replace("mass_kg = 0.8", "inertia_kgm2 = 0.8"),
     "dynamics.inertia_kgm2: a translating follower is given by mass_kg"),
    (DISC + TRAIN.replace("spring_rate_n_per_mm = 2.5\npreload_n = 60.0\n", ""),
     'dynamics.spring_rate_n_per_mm: missing; expected spring_rate_n_per_mm and preload_n, or spring = "size"'),
    (DISC + TRAIN.replace("spring_rate_n_per_mm = 2.5", 'spring = "size"'),
     'dynamics.preload_n: spring = "size" sizes the rate and the preload: leave them out'),
    (DISC + TRAIN.replace("spring_rate_n_per_mm = 2.5\npreload_n = 60.0", 'spring = "size"'),
     'dynamics.damping_ratio: spring = "size" makes the rate unknown, and with it the damping a ratio gives: give '
     "damping_n_s_per_m"),
    (DISC + TRAIN + "damping_n_s_per_m = 3\n", "dynamics.damping_ratio: give damping_ratio or damping_n_s_per_m, not both"),
    (DISC + TRAIN.replace("external_load_n = 20.0", "external_load_n = [[0, 1], [0, 2]]"),
     "dynamics.external_load_n[1]: angle 0 must follow 0 (increasing)"),
    (DISC + TRAIN.replace("external_load_n = 20.0", "external_load_n = [[0, 1], [360, 2]]"),
     "dynamics.external_load_n[1]: angle 360: expected >= 0 and < 360 degrees"),
    (DISC + TRAIN.replace("external_load_n = 20.0", 'external_load_n = [["a", 2]]'),
     'dynamics.external_load_n[0]: expected [cam angle in degrees, force in N], got an array'),
    (DISC + TRAIN.replace("friction = 0.05", "friction = -0.1"),
     "dynamics.friction: expected a number >= 0 and <= 1, got -0.1"),
    (DISC + TRAIN.replace("overspeed", "x") + "overspeed = 0.9\n", "dynamics.overspeed: expected a number >= 1 and <= 10, got 0.9"),
    (DISC + TRAIN + "colour = 1\n", "dynamics.colour: unknown key; expected one of:"),
    (GROOVE + "[dynamics]\nmass_kg = 0.3\nroller_width_mm = 8\npreload_n = 5\n",
     "dynamics.preload_n: a disc-groove cam drives its follower both ways (positive drive): it takes no spring"),
    (OSC_FLAT + "[dynamics]\ninertia_kgm2 = 0.01\nspring_rate_n_per_mm = 1\nroller_width_mm = 5\n",
     "dynamics.roller_width_mm: a flat face has no roller: its contact runs across the cam's thickness"),
    (OSC_FLAT + "[dynamics]\ninertia_kgm2 = 0.01\nspring_rate_n_per_mm = 1\n",
     "dynamics.load_arm_mm: missing; expected a number > 0 mm"),
    (OSC_FLAT + "[dynamics]\ninertia_kgm2 = 0.01\nspring_rate_n_per_mm = 1\nload_arm_mm = 50\nfriction = 0.1\n",
     "dynamics.friction: guide friction applies to translating followers; an oscillating follower's pivot friction is not modelled"),
    ('name = "m"\n[motion]\nrpm = 60\nsegments = [{ law = "cycloidal", from = 0, to = 360, rise = 0 }]\n'
     "[dynamics]\nmass_kg = 1\n", "dynamics: needs [cam] and [follower] tables: the forces come from the cam's geometry"),
]


@pytest.mark.parametrize("text, message", BAD, ids=[m.split(":")[0] + str(i) for i, (_, m) in enumerate(BAD)])
def test_bad_input_names_the_key(tmp_path, text, message):
    with pytest.raises(SpecError) as err:
        load(tmp_path, text)
    assert str(err.value).startswith(message)
    assert "\n" not in str(err.value)
