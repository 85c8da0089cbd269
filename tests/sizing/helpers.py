"""What the sizing and batch tests share: the CLI in-process, and the sizing sample without its sweep."""

from __future__ import annotations

import contextlib
import io
from pathlib import Path

from camcam.cli import main

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "size" / "translating-roller.toml"
#: The sizing sample up to its [size] table: a cam spec to add a sweep to.
BASE = SAMPLE.read_text().split("[size]")[0]


def cli(*args) -> tuple[int, str, str]:
    """(exit status, stdout, stderr) of `camcam ARGS` run in this process."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    return code, out.getvalue(), err.getvalue()
