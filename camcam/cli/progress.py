"""Progress on stderr for steps that take longer than a second.

A step that ends within ``delay_s`` prints nothing; a longer one announces
itself when the delay has passed and prints its time when it ends.  stdout is
untouched, so ``--json`` output stays one object.
"""

from __future__ import annotations

import sys
import threading
import time
from contextlib import contextmanager
from typing import Iterator, TextIO

__all__ = ["step"]


@contextmanager
def step(name: str, delay_s: float = 1.0, stream: TextIO | None = None) -> Iterator[None]:
    """Announce ``name`` on ``stream`` (stderr) if it runs longer than ``delay_s``.

    Examples
    --------
    >>> import io
    >>> buf = io.StringIO()
    >>> with step("quick", stream=buf):
    ...     pass
    >>> buf.getvalue()
    ''
    """
    out = stream if stream is not None else sys.stderr
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
