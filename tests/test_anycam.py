"""A fixed subset of the design-space campaign (issue 43, ``benchmarks/anycam.py``) held to the issue's targets.

Five cases of each of the eight families of :mod:`tests.designspace` (disc cams with each follower kind,
face-groove disc cams, barrel cams: translating on 4 axes, oscillating on 4 and 5 axes) on every post
that supports them, drawn with ``quick=True`` (base radius up to 45 mm, rise up to 15 mm, tolerance
0.02–0.05 mm, at most two depth passes) so that the 40 ``camcam run`` subprocesses take one or two minutes
on two cores (they run two
at a time, in a pool, the first time a test asks for them).  Each case must:

* never end in an internal fault (exit 1);
* as an exit-0 disc program on a post LinuxCNC reads, be within its tolerance as rs274 reads it back,
  every finishing pass both ways against the exact tool-centre curve rebuilt from the spec
  (:func:`tests.designspace.read_back`): multiple ≤ 1.0 with no margin — the posts print at most
  4 decimals, which rs274 reproduces exactly (``print_margin_mm`` is 0), and the two-sided measurement
  (``measure_deviation``) is an upper bound (the sampled figure plus its between-samples bound, 2 % of the
  tolerance, re-measured with a bound of 0.1 % when it comes within 2 % of the limit: a groove's first-level
  flank pass, whose ramp splits an arc at a printed point, measured 1.00002 × then 0.981 ×); an exit-0 barrel
  program (not accepted out of tolerance) within its
  tolerance by the report's 3-D groove figure, and accepted by rs274 where it reads the dialect;
* never fail the roughing's radial-engagement check;
* as an exit 2 or 3, print exactly one line on stderr.

:data:`PINNED` adds full-size campaign cases that found a fault.  Cases that miss a target today because
of a product bug are marked ``xfail(strict=False)`` in :data:`KNOWN` with the bug; remove the mark when the
fix lands.  (At 6610d2d, with the roughing engagement fix 1bf2a05 in, none of the 40 drawn cases misses a
target: no PostError max_arc_sweep_deg, engagement FAIL or extra stderr line among them.)
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor

import pytest

from tests.designspace import FAMILIES, draw_case, run_case

SEED = 4343
PER_FAMILY = 5
#: case id -> (family, index): index 100·k + i for the i-th case of the k-th family
CASES = {f"{fam}-{i}": (fam, 100 * k + i) for k, fam in enumerate(FAMILIES) for i in range(PER_FAMILY)}
#: full-size cases of ``benchmarks/anycam.py --seed 43`` that found a fault, pinned: case id -> index
PINNED = {"seed43-28": 28, "seed43-67": 67, "seed43-140": 140, "seed43-250": 250}

#: case id -> reason: cases that miss a target because of a known product bug (none today).  (The
#: pinned seed 43 cases 28, 67 and 250, FitError 'the march found no printed arc spline', and 140, a face groove's
#: rough ring 6.687 mm wide for 6.4, were marked here until issue 43 C and E landed: 2e98892, 5fb0363.)
KNOWN: dict[str, str] = {}


def _case(case_id: str):
    if case_id in PINNED:
        return draw_case(43, PINNED[case_id])
    fam, index = CASES[case_id]
    return draw_case(SEED, index, families=(fam,), quick=True)


def _run(case_id: str) -> dict:
    return run_case(_case(case_id), follow=False)


@pytest.fixture(scope="module")
def outcomes(request) -> dict:
    """The records of every case this session selected, run two at a time."""
    wanted = [item.callspec.params["case_id"] for item in request.session.items
              if getattr(item, "originalname", None) == "test_design_space_case" and hasattr(item, "callspec")]
    wanted = list(dict.fromkeys(wanted)) or [*CASES, *PINNED]
    with ProcessPoolExecutor(max_workers=2) as pool:
        return dict(zip(wanted, pool.map(_run, wanted)))


def test_subset_covers_every_family_and_post():
    cases = [_case(c) for c in CASES]
    assert {c.family for c in cases} == set(FAMILIES)
    assert {c.post for c in cases} == {"linuxcnc", "fanuc", "haas", "grbl", "sinumerik", "heidenhain"}
    assert {c.spec["cam"]["rotation"] for c in cases} == {"cw", "ccw"}
    assert any("stock" in c.spec for c in cases) and any("stock" not in c.spec for c in cases)
    assert _case("disc-groove-0").toml() == _case("disc-groove-0").toml()  # deterministic from (seed, index)
    # the pinned cases are still the specs that found their fault (a change to the draw would move them)
    assert (_case("seed43-28").family, _case("seed43-28").spec["cam"]["base_radius"]) == ("disc-groove", 84.1)
    assert (_case("seed43-67").family, _case("seed43-67").spec["cam"]["base_radius"]) == ("disc-oscillating-roller", 134.7)
    assert _case("seed43-140").family == "disc-groove"
    assert _case("seed43-250").spec["motion"]["segments"][0]["rise"] == 0.12


@pytest.mark.parametrize("case_id", [pytest.param(c, marks=pytest.mark.xfail(strict=False, reason=KNOWN[c]))
                                     if c in KNOWN else c for c in [*CASES, *PINNED]])
def test_design_space_case(outcomes, case_id):
    rec = outcomes[case_id]
    spec = _case(case_id).toml()
    assert rec["status"] != 1, f"internal fault: {rec['lines']}\n{spec}"
    assert rec["cause"] != "roughing engagement FAIL", f"{rec['lines']}\n{spec}"
    if rec["status"] in (2, 3):
        assert len(rec["lines"]) == 1, f"exit {rec['status']} printed {len(rec['lines'])} lines: {rec['lines']}\n{spec}"
    if rec["status"] == 0:
        rb = rec["readback"]
        assert "error" not in rb, f"read-back: {rb['error']}\n{spec}"
        accepted = rec["cause"] == "ok (accepted FAIL)"
        if rb["how"] == "rs274 read-back":
            assert rb["passes"] >= 1
            assert rb["multiple"] <= 1.0, f"rs274 read-back {rb['deviation']:.5f} mm of {rb['tolerance']} mm " \
                                          f"({rb['where']})\n{spec}"
        elif rb["how"] == "report 3-D groove" and not accepted:
            assert rb["multiple"] <= 1.0, f"3-D groove {rb['deviation']:.5f} mm of {rb['tolerance']} mm\n{spec}"
        if "rs274" in rb:
            assert rb["rs274"] == "read", f"{rb['rs274']}\n{spec}"
