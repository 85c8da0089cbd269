"""Make the README's tour pictures from the samples' own runs.

    PYTHONPATH=. python docs/make_tour.py

Runs `camcam run` on samples/disc-translating-roller.toml,
samples/cylindrical-translating.toml and samples/cylindrical-translating-small-tool.toml
(its 3-D groove deviation map), copies their plots into docs/tour/, takes
a headless-Chromium screenshot of the report (top part) and writes the first
lines of the NC program to docs/tour/program-head.ngc; the sizing chart of
samples/size/translating-roller.toml goes to docs/tour/sizing.png.
"""

from __future__ import annotations

import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TOUR = ROOT / "docs" / "tour"
sys.path.insert(0, str(ROOT))

from camcam.cli import main  # noqa: E402


def shoot(html: Path, png: Path, work: Path) -> None:
    chromium = shutil.which("chromium")
    if chromium is None:
        raise SystemExit("chromium is needed for the report screenshot (apt-get install chromium)")
    subprocess.run(
        [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         f"--user-data-dir={work / 'profile'}", "--window-size=1100,1500", f"--screenshot={png}", f"file://{html}"],
        check=True, capture_output=True, timeout=120,
    )


def run() -> None:
    TOUR.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as d:
        work = Path(d)
        for sample in ("disc-translating-roller", "cylindrical-translating", "cylindrical-translating-small-tool"):
            out = work / sample
            assert main(["run", str(ROOT / "samples" / f"{sample}.toml"), "-o", str(out)]) == 0
        disc = work / "disc-translating-roller"
        for src, dst in [
            ("disc-translating-roller-svaj.png", "svaj.png"),
            ("disc-translating-roller-profile.png", "cam.png"),
            ("disc-translating-roller-fitted-motion.png", "fitted-motion.png"),
            ("disc-translating-roller-deviation.png", "deviation.png"),
        ]:
            shutil.copy(disc / src, TOUR / dst)
        shutil.copy(work / "cylindrical-translating" / "cylindrical-translating-profile.png", TOUR / "cylindrical.png")
        small = "cylindrical-translating-small-tool"
        shutil.copy(work / small / f"{small}-groove-map.png", TOUR / "groove-map.png")
        head = (disc / "disc-translating-roller.ngc").read_text().splitlines()[:16]
        (TOUR / "program-head.ngc").write_text("\n".join(head) + "\n")
        shoot(disc / "disc-translating-roller-report.html", TOUR / "report.png", work)
        sized = work / "size"
        assert main(["size", str(ROOT / "samples" / "size" / "translating-roller.toml"), "-o", str(sized), "--in-process"]) == 0
        shutil.copy(sized / "size-translating-roller-sizing.png", TOUR / "sizing.png")


if __name__ == "__main__":
    run()
