"""Class 7: two runs with different PYTHONHASHSEED values write byte-identical files, DXF included."""

from __future__ import annotations

from tests.hostile.harness import SAMPLES, run_sub, snapshot


def test_two_hash_seeds_write_the_same_bytes(tmp_path):
    spec = SAMPLES / "disc-groove.toml"  # a DXF, a program, STL, plots, report
    sets = []
    for seed in ("1", "4"):  # 4: a seed whose set order put ACDBPLACEHOLDER after LAYOUT before the fix
        out = tmp_path / f"s{seed}"
        r = run_sub(["run", spec, "-o", out], env={"PYTHONHASHSEED": seed})
        assert r.returncode == 0, r.stderr
        sets.append(snapshot(out))
    assert sorted(sets[0]) == sorted(sets[1]) and any(n.endswith(".dxf") for n in sets[0])
    assert [n for n in sets[0] if sets[0][n] != sets[1][n]] == []
