"""Stock to part on every disc sample: the passes and the material-removal figures of the printed program.

For each disc or face-groove sample (and the disc cut through each post): the blank, the passes by
kind, the largest radial engagement against the stepover (outside slot passes) and in slot passes,
plunges into material, rapids touching material, material left over the profile and overcut (the
program read back from its printed numbers, checked 2.5-D against the blank), the roughing's stock
over the profile, and the program's blocks.  Run from the repository:

    PYTHONPATH=. python benchmarks/run_roughing.py
"""

from __future__ import annotations

from pathlib import Path

from camcam.geometry.build import build_cam
from camcam.verify import checked
from camcam.spec import load_spec

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = ["disc-translating-roller", "disc-translating-flat", "disc-oscillating-flat", "disc-oscillating-roller",
           "disc-groove", "posts/fanuc", "posts/grbl", "posts/haas", "posts/heidenhain", "posts/linuxcnc",
           "posts/sinumerik"]


def main() -> None:
    print("| sample | blank | passes | engagement / stepover mm | slot mm | plunges | rapids | left mm | overcut mm "
          "| rough stock mm | blocks G0/G1/G2-3 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name in SAMPLES:
        spec = load_spec(ROOT / "samples" / f"{name}.toml")
        built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
        r = checked(built, spec.machining, spec.name, spec.stock)
        rem, b = r.removal, r.blank
        kinds: dict[str, int] = {}
        for p in r.passes:
            kinds[p.kind] = kinds.get(p.kind, 0) + 1
        blank = f"Ø{b.diameter_mm:.3f}" if b.kind == "round" else f"+{b.allowance_mm:g} offset"
        blank += "" if b.stated else " (default)"
        stock = f"{rem.rough_clearance_mm:.4f}" if rem.rough_clearance_mm is not None else "—"
        pr = r.program
        print(f"| {name} | {blank} | {', '.join(f'{n} {k}' for k, n in kinds.items())} | "
              f"{rem.max_engagement_mm:.3f} / {rem.stepover_mm:g} | {rem.max_slot_engagement_mm:.3f} | {rem.plunges} | "
              f"{rem.rapid_touches} | {rem.material_left_mm:.4f} | {rem.overcut_mm:.4f} | {stock} | "
              f"{pr.rapid_blocks}/{pr.line_blocks}/{pr.arc_blocks} |", flush=True)


if __name__ == "__main__":
    main()
