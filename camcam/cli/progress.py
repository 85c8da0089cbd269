"""Progress on stderr for steps that take longer than a second — only when asked.

Progress is shown when stderr is a terminal, or with ``--progress``; never
otherwise, so a script reading stderr gets exactly the one line an error
promises however long a step takes on a loaded machine.  A step that ends
within ``delay_s`` prints nothing; a longer one announces itself when the
delay has passed and prints its time when it ends.  stdout is untouched, so
``--json`` output stays one object.
"""

from __future__ import annotations

import sys
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Iterator, TextIO

__all__ = ["Progress", "add_progress_flag"]


def add_progress_flag(parser) -> None:
    """The ``--progress`` option of a sub-command that has long steps."""
    parser.add_argument("--progress", action="store_true",
                        help="report steps over 1 s on stderr even when it is not a terminal")


@dataclass(frozen=True)
class Progress:
    """Where and whether long steps are announced.

    Examples
    --------
    >>> import io
    >>> buf = io.StringIO()
    >>> with Progress(True, buf).step("quick"):
    ...     pass
    >>> buf.getvalue()
    ''
    >>> with Progress(False, buf).step("slow", delay_s=0.0):
    ...     pass
    >>> buf.getvalue()
    ''
    """

    enabled: bool
    stream: TextIO | None = None

    @classmethod
    def from_args(cls, args) -> "Progress":
        """Enabled by ``--progress`` or a terminal on stderr."""
        return cls(bool(getattr(args, "progress", False)) or sys.stderr.isatty())

    @contextmanager
    def step(self, name: str, delay_s: float = 1.0) -> Iterator[None]:
        """Announce ``name`` if it runs longer than ``delay_s`` (and progress is enabled)."""
        if not self.enabled:
            yield
            return
        out = self.stream if self.stream is not None else sys.stderr
        shown = threading.Event()

        def announce() -> None:
            shown.set()
            out.write(f"camcam: {name} …\n")
            out.flush()

        timer = threading.Timer(delay_s, announce)
        timer.daemon = True
        start = time.perf_counter()
        timer.start()
        try:
            yield
        finally:
            timer.cancel()
            if shown.is_set():
                out.write(f"camcam: {name} done in {time.perf_counter() - start:.1f} s\n")
                out.flush()
