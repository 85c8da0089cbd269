"""Record the SHA-256 of every output of every sample run (``tests/data/sample_checksums.json``).

Run it when a change alters outputs on purpose, and say which in the commit:

    PYTHONHASHSEED=0 PYTHONPATH=. python tests/make_sample_checksums.py

``python tests/make_sample_checksums.py --check SAMPLE...`` runs the named
samples in this fresh process and compares every output file with the record
(exit 1 naming the files that differ); ``tests/test_samples.py`` does that in a
subprocess, so a refactoring that changes a byte of a program, drawing, mesh,
plot, table or report fails there.  The outputs do not depend on the hash seed
(tests/hostile/test_determinism.py); it is pinned only for the record.

The bytes do depend on the CPU's instruction set: numpy picks its loops for
sin, cos, exp and the like at import by what the CPU has, and its AVX-512
loops (X86_V4 and up) round some results differently in the last bit from
its AVX2 ones (X86_V3), which moves digits of the DXF's exact splines, the
mesh's float32 vertices and the report's figures (seen on an AMD EPYC with
AVX-512: 41 files of 21 samples differed, none with AVX-512 disabled).  So
this script, in both modes (run as a script), turns numpy's AVX-512 loops off
(``NPY_DISABLE_CPU_FEATURES``, before numpy is imported; names a CPU or a
numpy version does not know are ignored), and the record is that of the AVX2
loops on every machine that has them.  camcam itself uses whatever the CPU
has: the same spec gives the same bytes on one machine, run after run.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import os
import sys
import tempfile
import tomllib
from pathlib import Path

# numpy's AVX-512 loops (numpy 2.x's X86_V4 group and its own names, numpy 1.x's names): see the notes above
AVX512 = ("X86_V4 AVX512_ICL AVX512_SPR AVX512F AVX512CD AVX512_KNL AVX512_KNM AVX512_SKX AVX512_CLX "
          "AVX512_CNL")

ROOT = Path(__file__).resolve().parents[1]
RECORD = ROOT / "tests" / "data" / "sample_checksums.json"


def run_specs() -> list[Path]:
    specs = sorted((ROOT / "samples").rglob("*.toml"))
    return [p for p in specs if "motion" in tomllib.loads(p.read_text())]


def digests(folder: Path) -> dict[str, str]:
    return {p.name: hashlib.sha256(p.read_bytes()).hexdigest() for p in sorted(folder.iterdir()) if p.is_file()}


def run_one(spec: Path) -> dict[str, str]:
    """The digests of every file ``camcam run`` writes for ``spec``."""
    from camcam.cli import main as camcam

    with tempfile.TemporaryDirectory() as tmp:
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            code = camcam(["run", str(spec), "-o", tmp])
        if code not in (0, 3):
            raise SystemExit(f"{spec}: exit {code}")
        return digests(Path(tmp))


def check(names: list[str]) -> int:
    record = json.loads(RECORD.read_text())
    bad = []
    for name in names:
        got, want = run_one(ROOT / name), record[name]
        bad += [f"{name}: {f}" for f in sorted(set(got) | set(want)) if got.get(f) != want.get(f)]
    print("\n".join(bad) if bad else f"{len(names)} samples as recorded")
    return 1 if bad else 0


def main() -> int:
    if sys.argv[1:2] == ["--check"]:
        return check(sys.argv[2:])
    if sys.argv[1:]:  # ``--help`` or a typo must not rewrite the record
        print("\n\n".join(__doc__.split("\n\n")[1:4]), file=sys.stderr)
        return 2
    from camcam.cli import main as camcam

    record = {}
    for spec in run_specs():
        with tempfile.TemporaryDirectory() as tmp:
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                code = camcam(["run", str(spec), "-o", tmp])
            if code not in (0, 3):
                print(f"{spec}: exit {code}", file=sys.stderr)
                return 1
            record[str(spec.relative_to(ROOT))] = digests(Path(tmp))
    RECORD.write_text(json.dumps(record, indent=1, sort_keys=True) + "\n")
    print(f"wrote {RECORD} ({sum(len(v) for v in record.values())} files of {len(record)} samples)")
    return 0


if __name__ == "__main__":
    # before anything imports numpy; only when run as a script: pytest imports this module for its doctests,
    # and the variable would then reach every process the test session starts (Dask's workers among them)
    os.environ["NPY_DISABLE_CPU_FEATURES"] = AVX512
    raise SystemExit(main())
