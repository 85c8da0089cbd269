"""Generate the inspection samples: measured parts made from camcam's exact profiles with a stated defect.

Each part is the design's exact surface with (camcam.inspect.synthetic):

* ``disc-cmm.csv`` (CMM, ``../disc-translating-roller.toml``): 720 profile points at uneven cam angles;
  a bump of +0.03 mm (material left) of σ 4° at cam angle 200°; the part turned by 0.7° and its centre
  shifted by (0.05, 0) mm; normal noise σ 0.002 mm; 3 outliers of ±0.1 mm.  ``disc-bore.csv``: 36 points
  on the Ø12 bore of that part (same turn and shift, noise σ 0.002 mm), for ``--bore``.
* ``disc-cmm-clean.csv``: the same part without the bump (it passes).
* ``disc-dial.csv`` (dial indicator, probe tip radius 5 mm, ``../disc-translating-roller.toml``): a reading
  every 1°; a bump of −0.02 mm (overcut) of σ 4° at 60°; the dividing head's angle 0.7° off and its axis
  (0.05, 0) mm off the cam centre; readings from a zero 0.25 mm below the design's; noise σ 0.002 mm;
  3 outliers of ±0.1 mm.
* ``barrel-walls.csv`` (``../cylindrical-translating.toml``): 360 points on each groove wall at random depths;
  a bump of +0.03 mm on wall 1 (+X side) at 90°; the part turned 0.7° about X and shifted (0.05, 0, 0) mm;
  noise σ 0.002 mm; 3 outliers of ±0.1 mm.

numpy ``default_rng(SEED + k)``; run from the repository root:
``PYTHONPATH=. python samples/inspect/make_parts.py``.  Then, e.g.
``camcam inspect samples/disc-translating-roller.toml samples/inspect/disc-cmm.csv --align rigid -o out``.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from camcam.geometry.build import build_cam
from camcam.inspect.synthetic import Defect, barrel_part, cmm_part, dial_part
from camcam.spec import load_spec

SEED = 20261206
HERE = Path(__file__).resolve().parent
NOISE_MM = 0.002
PROBE_MM = 5.0


def built(name: str):
    spec = load_spec(HERE.parent / name)
    return build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit)).cam


def write(name: str, header: str, rows: np.ndarray, about: str) -> None:
    lines = [f"# {about}", header] + [", ".join(f"{v:.6f}" for v in r) for r in rows]
    (HERE / name).write_text("\n".join(lines) + "\n", encoding="utf-8")


def main() -> None:
    disc = built("disc-translating-roller.toml")
    cmm = Defect(bump_mm=0.03, bump_deg=200.0, rotation_deg=0.7, shift_mm=(0.05, 0.0), noise_mm=NOISE_MM, outliers=3)
    pts, _ = cmm_part(disc, 720, cmm, np.random.default_rng(SEED))
    write("disc-cmm.csv", "x_mm, y_mm", pts, "CMM, disc-translating-roller: +0.03 mm bump at 200 deg, turned 0.7 deg, "
          "centre shifted (0.05, 0) mm, noise 0.002 mm, 3 outliers (make_parts.py)")
    rng = np.random.default_rng(SEED + 1)
    t = np.radians(np.arange(0.0, 360.0, 10.0))
    bore = 6.0 * np.stack([np.cos(t), np.sin(t)], axis=-1)
    bore += rng.normal(0.0, NOISE_MM, t.size)[:, None] * np.stack([np.cos(t), np.sin(t)], axis=-1)
    a = math.radians(cmm.rotation_deg)
    R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
    write("disc-bore.csv", "x_mm, y_mm", bore @ R.T + np.array(cmm.shift_mm), "the bore of disc-cmm.csv's part")
    clean = Defect(rotation_deg=0.7, shift_mm=(0.05, 0.0), noise_mm=NOISE_MM, outliers=3)
    pts, _ = cmm_part(disc, 720, clean, np.random.default_rng(SEED + 2))
    write("disc-cmm-clean.csv", "x_mm, y_mm", pts, "CMM, disc-translating-roller: no bump, turned 0.7 deg, centre "
          "shifted (0.05, 0) mm, noise 0.002 mm, 3 outliers (make_parts.py)")
    dial = Defect(bump_mm=-0.02, bump_deg=60.0, rotation_deg=0.7, shift_mm=(0.05, 0.0), noise_mm=NOISE_MM, outliers=3)
    rows, _ = dial_part(disc, PROBE_MM, 1.0, dial, np.random.default_rng(SEED + 3))
    write("disc-dial.csv", "angle_deg, reading_mm", rows, f"dial indicator, probe radius {PROBE_MM:g} mm, "
          "disc-translating-roller: -0.02 mm bump at 60 deg, angle 0.7 deg off, axis (0.05, 0) mm off, zero 0.25 mm "
          "low, noise 0.002 mm, 3 outliers (make_parts.py)")
    barrel = built("cylindrical-translating.toml")
    walls = Defect(bump_mm=0.03, bump_deg=90.0, rotation_deg=0.7, shift_mm=(0.05, 0.0, 0.0), noise_mm=NOISE_MM,
                   outliers=3, wall=1)
    pts, _ = barrel_part(barrel, 360, walls, np.random.default_rng(SEED + 4))
    write("barrel-walls.csv", "x_mm, y_mm, z_mm", pts, "groove walls, cylindrical-translating: +0.03 mm bump on wall 1 "
          "at 90 deg, turned 0.7 deg about X, shifted (0.05, 0, 0) mm, noise 0.002 mm, 3 outliers (make_parts.py)")


if __name__ == "__main__":
    main()
