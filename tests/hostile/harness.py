"""Shared checks of the hostile-input suite (issue 16).

Each hostile input must end in one of two ways:

- a clean error: exit status 2, exactly one stderr line ``camcam: error: …``,
  no traceback, and nothing new on disk (:func:`snapshot` before and after);
- a correct result: exit status 0, and every program line is one the spec
  asked for (:func:`assert_program_safe`).
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import subprocess
import sys
from pathlib import Path

from camcam.cli import main

ROOT = Path(__file__).resolve().parents[2]
SAMPLES = ROOT / "samples"
INJECT = Path(__file__).with_name("inject.py")


def run_inproc(args) -> tuple[int, str, str]:
    """``camcam ARGS`` in this process: (status, stdout, stderr)."""
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        code = main([str(a) for a in args])
    return code, out.getvalue(), err.getvalue()


def run_sub(args, env=None, inject=None, timeout=600) -> subprocess.CompletedProcess:
    """``camcam ARGS`` in a fresh interpreter (optionally through ``inject.py MODE …``)."""
    cmd = [sys.executable, str(INJECT), *inject, "--"] if inject else [sys.executable, "-m", "camcam"]
    full_env = dict(os.environ, **(env or {}))
    full_env.pop("CAMCAM_PROGRESS", None)
    return subprocess.run(cmd + [str(a) for a in args], capture_output=True, text=True, env=full_env,
                          timeout=timeout, cwd=str(ROOT))


#: A progress line (camcam.cli.progress.Progress.step): "camcam: NAME …" or "camcam: NAME done in 1.2 s".
_PROGRESS = re.compile(r"camcam: (?!error:).+ (…|done in \d+\.\d s)")


def error_lines(stderr: str) -> list[str]:
    """stderr without progress lines (warnings and notes are on stdout unless --verbose: issue 43).

    Only whole progress lines go: an error may quote a value with "…" in it (hypothesis found the
    angle '…' in a lift table, whose error line an "…" anywhere filter dropped)."""
    return [ln for ln in stderr.splitlines() if ln and not _PROGRESS.fullmatch(ln)]


def assert_clean_error(code: int, stderr: str, status: int = 2, prefix: str = "camcam: error: ") -> str:
    lines = error_lines(stderr)
    assert "Traceback" not in stderr, stderr
    assert code == status, (code, stderr)
    assert len(lines) == 1 and lines[0].startswith(prefix), stderr
    return lines[0]


def snapshot(folder: Path) -> dict[str, bytes | None]:
    """Every path under ``folder`` (hidden ones included) with its bytes (None for a folder)."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(folder):
        for d in dirnames:
            out[os.path.relpath(os.path.join(dirpath, d), folder)] = None
        for f in filenames:
            p = os.path.join(dirpath, f)
            out[os.path.relpath(p, folder)] = Path(p).read_bytes() if os.path.isfile(p) else b"<special>"
    return out


_CODE = {
    # the words a camcam program is made of (motion, setup, the header/footer words of the bundled posts)
    # address words (G21, Z-5.) and capital controller keywords (Sinumerik's TRAORI)
    "gcode": re.compile(r"(?:[A-Z]-?[0-9]+\.?[0-9]*|[A-Z]{2,}[A-Z0-9_]*)(?: (?:[A-Z]-?[0-9]+\.?[0-9]*|[A-Z]{2,}[A-Z0-9_]*))*|%|"),
    "heidenhain": re.compile(r"(?:BEGIN PGM [A-Za-z0-9_-]+ MM|END PGM [A-Za-z0-9_-]+ MM|TOOL CALL [0-9]+ Z S[0-9]+|"
                             r"STOP M5|CC X[+-][0-9.]+ Y[+-][0-9.]+|C X[+-][0-9.]+ Y[+-][0-9.]+ DR[+-] R0 F[0-9.]+|"
                             r"L(?: [XYZ][+-][0-9.]+)+ R0 F(?:MAX|[0-9.]+)(?: M3)?(?: M[789])?|"
                             # the work offset (preset) cycle and its continuation line; coolant rides on L blocks
                             r"CYCL DEF 247 DATUM SETTING ~|Q339=\+[1-6]|)"),
}


def assert_program_safe(text: str, post, marker: str = "Z-50") -> None:
    """Every line of ``text`` is one program line: its code part is made of words only, its comment
    (if any) is closed on the line and the hostile ``marker`` never appears outside a comment."""
    assert "\r" not in text and "\x00" not in text
    for line in text.splitlines():
        if post.line_numbers:
            line = re.sub(r"^N?[0-9]+ ", "", line)
        if post.comment == "parentheses":
            assert line.count("(") == line.count(")") <= 1, line
            code = re.sub(r"\([^()]*\)", "", line).strip()
            assert ";" not in code, line
        else:
            code = line.split(";", 1)[0].strip()
        assert marker not in code, line
        assert _CODE[post.dialect].fullmatch(code), f"not a program line: {line!r}"
