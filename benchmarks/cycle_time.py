"""Cycle time with acceleration (camcam.verify.motion_time) beside the feed-only figure, on the samples.

Prints three tables and a timing:

1. every machining sample: its post, feed-only and motion-model totals and their ratio;
2. one program (``samples/disc-translating-roller.toml`` as printed, and again at 0.001 mm in lines at
   2000 mm/min) timed with each bundled post's limits (rapid rate, accelerations, junction deviation): what
   the same moves take on each controller;
3. the GRBL sample at other accelerations and feeds: the model beside GRBL's planner as transcribed in
   ``tests/verify/grbl_planner.py`` (16-block look-ahead, arcs cut into chords);
4. CPU seconds of :func:`motion_time` and :func:`cycle_time` on a disc job at 0.001 mm in lines (best of 5).

Run from the repository:

    PYTHONPATH=. python benchmarks/cycle_time.py
"""

from __future__ import annotations

import sys
import time
from dataclasses import replace
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "verify"))

from camcam.errors import CamcamError  # noqa: E402
from camcam.geometry.build import build_cam  # noqa: E402
from camcam.nc.job import machine_program  # noqa: E402
from camcam.post.post import known_posts, load_post  # noqa: E402
from camcam.spec import load_spec  # noqa: E402
from camcam.verify.cycle_time import cycle_time  # noqa: E402
from camcam.verify.motion_time import motion_time  # noqa: E402
from grbl_planner import grbl_time_s  # noqa: E402


def _program(spec, machining=None):
    built = build_cam(spec.cam, spec.follower, spec.motion.program(spec.unit))
    return machine_program(built, machining or spec.machining, spec.name, spec.stock)


def _clock(seconds: float) -> str:
    h, rest = divmod(seconds, 3600)
    return f"{int(h)} h {int(rest // 60):02d} min" if h else f"{int(rest // 60)} min {rest % 60:02.0f} s"


def samples_table() -> None:
    print(f"{'sample':<40} {'post':<10} {'feed-only':>14} {'model':>14} {'ratio':>6}")
    for path in sorted(ROOT.glob("samples/*.toml")) + sorted(ROOT.glob("samples/posts/*.toml")):
        try:
            spec = load_spec(path)
        except CamcamError:
            continue
        if getattr(spec, "machining", None) is None:
            continue
        r = _program(spec)
        t = motion_time(r.program.printed_moves, r.post)
        print(f"{str(path.relative_to(ROOT)):<40} {r.post.name:<10} {_clock(t.feed_only_s):>14} {_clock(t.total_s):>14} "
              f"{t.total_s / t.feed_only_s:>6.3f}")


def posts_table() -> None:
    spec = load_spec(ROOT / "samples" / "disc-translating-roller.toml")
    fine = replace(spec.machining, tolerance_mm=0.001, mode="lines", feed_mm_min=2000.0)
    for label, machining in (("as the sample", spec.machining), ("at 0.001 mm in lines, feed 2000 mm/min", fine)):
        r = _program(spec, machining)
        moves = r.program.printed_moves
        print(f"samples/disc-translating-roller.toml {label} (printed by {r.post.name}), timed with each post's limits")
        print(f"{'post':<11} {'a mm/s²':>8} {'δ mm':>6} {'rapid':>7} {'feed-only':>14} {'model':>14} {'ratio':>6}")
        for name in known_posts():
            post = load_post(name)
            t = motion_time(moves, post)
            print(f"{name:<11} {post.max_accel_mm_s2:>8g} {post.junction_deviation_mm:>6g} {post.rapid_mm_min:>7g} "
                  f"{_clock(t.feed_only_s):>14} {_clock(t.total_s):>14} {t.total_s / t.feed_only_s:>6.3f}")


def grbl_table() -> None:
    spec = load_spec(ROOT / "samples" / "posts" / "grbl.toml")
    print("samples/posts/grbl.toml: the model against GRBL's planner (tests/verify/grbl_planner.py)")
    print(f"{'feed':>6} {'a mm/s²':>8} {'feed-only s':>12} {'model s':>9} {'GRBL s':>9} {'model/GRBL':>11}")
    for feed in (400.0, 3000.0):
        r = _program(spec, replace(spec.machining, feed_mm_min=feed))
        moves = r.program.printed_moves
        for a in (1.0, 10.0, 100.0, 1000.0):
            post = replace(r.post, max_accel_mm_s2=a)
            t = motion_time(moves, post)
            g = grbl_time_s(moves, acceleration_mm_s2=a, rapid_mm_min=post.rapid_mm_min,
                            junction_deviation_mm=post.junction_deviation_mm)
            print(f"{feed:>6g} {a:>8g} {t.feed_only_s:>12.1f} {t.total_s:>9.1f} {g:>9.1f} {t.total_s / g:>11.4f}")


def cpu_cost() -> None:
    spec = load_spec(ROOT / "samples" / "disc-translating-roller.toml")
    r = _program(spec, replace(spec.machining, tolerance_mm=0.001, mode="lines"))
    for label, moves in (("", r.program.printed_moves), (", the program 80 times over", r.program.printed_moves * 80)):
        best = {}
        for name, f in (("motion_time", lambda: motion_time(moves, r.post)),
                        ("cycle_time", lambda: cycle_time(moves, r.post.rapid_mm_min))):
            runs = []
            for _ in range(5):
                t0 = time.process_time()
                f()
                runs.append(time.process_time() - t0)
            best[name] = min(runs)
        print(f"disc-translating-roller at 0.001 mm in lines{label}: {len(moves)} printed moves; CPU s (best of 5): "
              + ", ".join(f"{k} {v:.4f}" for k, v in best.items()))


def main() -> None:
    samples_table()
    print()
    posts_table()
    print()
    grbl_table()
    print()
    cpu_cost()


if __name__ == "__main__":
    main()
