"""Text that reaches a program: one comment encoder per post, and program names.

Every string a program prints that is not a word camcam made itself — the
title, the toolpath's comments, the spec's name and the post's name inside
them — goes through :func:`encode_comment` for the post it is printed by.  The
result can never end the comment or the line it sits in:

- every control, format or line-separator character (``\\n``, ``\\r``, NEL,
  U+2028, …) becomes a space, so one string stays one line;
- characters outside printable ASCII are spelled in ASCII (``°`` → ``deg``)
  or replaced by ``?`` (controllers read ASCII);
- ``parentheses`` dialect (LinuxCNC, Fanuc, Haas, GRBL): ``(`` and ``)``
  become ``[`` and ``]`` (a comment ends at the first ``)``), ``;`` becomes
  ``,`` (Fanuc's end of block) and ``%`` becomes ``#`` (the tape's end of
  record); a body that starts like one of LinuxCNC's active comments
  (``MSG,``, ``DEBUG,``, ``PRINT,``, ``LOG…``, ``PROBEOPEN``, ``PY,``,
  ``ABORT,``) is prefixed with ``_`` so it stays a plain comment;
- ``semicolon`` dialect (Sinumerik, Heidenhain): a comment runs to the end of
  the line, so one line is all it needs;
- at most :data:`MAX_COMMENT_CHARS` characters.

A program name printed as a word (Heidenhain's ``BEGIN PGM {name} MM``) is
checked by :func:`program_name` instead.
"""

from __future__ import annotations

import re
import unicodedata

from camcam.errors import InputError

__all__ = ["encode_comment", "program_name", "MAX_COMMENT_CHARS", "PROGRAM_NAME"]

#: Longest comment body printed (controllers limit the length of a block; Fanuc's is 256).
MAX_COMMENT_CHARS = 200

#: A program name that can be printed as a word in every dialect.
PROGRAM_NAME = re.compile(r"[A-Za-z0-9][A-Za-z0-9_-]{0,63}")

_SPELLED = {"°": " deg", "±": "+/-", "µ": "u", "μ": "u", "×": "x", "–": "-", "—": "-", "−": "-", "…": "...",
            "²": "^2", "³": "^3", "’": "'", "‘": "'", "“": '"', "”": '"', "≤": "<=", "≥": ">=", "δ": "delta",
            "φ": "phi", "θ": "theta", "κ": "kappa", "ρ": "rho"}
_PAREN = {"(": "[", ")": "]", ";": ",", "%": "#"}
_ACTIVE = re.compile(r"\s*(MSG|DEBUG|PRINT|LOG|LOGOPEN|LOGAPPEND|LOGCLOSE|PROBEOPEN|PROBECLOSE|PY|ABORT)(?=[\s,]|$)",
                     re.IGNORECASE)


def _ascii(ch: str) -> str:
    if ch in _SPELLED:
        return _SPELLED[ch]
    if unicodedata.category(ch)[0] in "CZ" and ch != " ":  # control, format, separators (incl. line/para)
        return " "
    if " " <= ch <= "~":
        return ch
    base = unicodedata.normalize("NFKD", ch).encode("ascii", "ignore").decode("ascii")
    return base if base and all(" " <= c <= "~" for c in base) else "?"


def encode_comment(text: str, comment: str) -> str:
    """The body of a comment for a post whose ``comment`` key is ``comment``.

    Examples
    --------
    >>> encode_comment("x\\nG0 Z-50 (y)", "parentheses")
    'x G0 Z-50 [y]'
    >>> encode_comment("tol ±0.01 mm; 90°", "semicolon")
    'tol +/-0.01 mm; 90 deg'
    >>> encode_comment("MSG, hello", "parentheses")
    '_MSG, hello'
    """
    out = "".join(_ascii(ch) for ch in str(text))
    if comment == "parentheses":
        out = "".join(_PAREN.get(ch, ch) for ch in out)
        if _ACTIVE.match(out):
            out = "_" + out
    elif comment != "semicolon":
        raise ValueError(f"unknown comment style {comment!r}")
    if len(out) > MAX_COMMENT_CHARS:
        out = out[: MAX_COMMENT_CHARS - 3] + "..."
    return out


def program_name(name: str, post_name: str = "") -> str:
    """``name`` if it can be printed as a program word, else :class:`InputError`.

    >>> program_name("cam_1")
    'cam_1'
    """
    if not PROGRAM_NAME.fullmatch(name):
        shown = name.encode("unicode_escape").decode("ascii")
        raise InputError(f"name: {shown!r} cannot be printed as a program name by post {post_name}; "
                         "expected 1-64 letters, digits, \"_\" or \"-\" (starting with a letter or digit)")
    return name
