"""The report opens with the verdict and the setup sheet, states a cycle time equal to the sum of the
moves LinuxCNC's interpreter reads, prints to A4 from Chromium without cut-offs; design checks warn or fail."""

import html
import json
import math
import re
import shutil
import subprocess
from collections import Counter
from pathlib import Path
from types import SimpleNamespace

import pytest

from camcam.cli import main
from camcam.nc.design_checks import design_checks
from camcam.verify.rs274 import rs274_available

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = ROOT / "samples" / "disc-translating-roller.toml"


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    out = tmp_path_factory.mktemp("dtr")
    assert main(["run", str(SAMPLE), "-o", str(out)]) == 0
    return out


def test_report_opens_with_verdict_then_setup(run_dir):
    html = (run_dir / "disc-translating-roller-report.html").read_text()
    titles = re.findall(r"<h2>([^<]+)</h2>", html)
    assert titles[:3] == ["Verdict", "Setup", "Job"]
    assert '<p class="verdict pass">PASS</p>' in html
    setup = html.split("<h2>Setup</h2>")[1].split("<h2>Job</h2>")[0]
    for label in ("part", "blank", "material", "work zero", "angular datum", "work offset", "tool",
                  "tool length offset", "coolant", "cycle time (estimate)"):
        assert f"<td>{label}</td>" in setup
    # issue 47: the blank's size (the sample's [stock] Ø125 bar, the cam's 12 mm) and [cam] material
    assert "<td>blank</td><td>round blank Ø125 mm, centred on the cam axis, 12 mm thick</td>" in setup
    assert "<td>material</td><td>C45 steel</td>" in setup
    assert "H1 (G43 in the program)" in setup and "flute length ≥ 12 mm" in setup
    # the passes table, in cutting order: roughing from the blank, then finish and spring at full depth
    rows = re.findall(r"<tr><td>(\d+/\d+)</td><td>(\w+)</td><td>profile</td><td>([-\d.]+)</td>", setup)
    kinds = [k for _, k, _ in rows]
    assert rows and kinds[-2:] == ["finish", "spring"] and set(kinds[:-2]) == {"rough"}
    assert rows[-1][2] == "-12" and rows[-1][0] == f"{len(rows)}/{len(rows)}"
    report = json.loads((run_dir / "disc-translating-roller-report.json").read_text())
    assert report["verdict"]["status"] == "PASS"
    assert {c["name"] for c in report["verdict"]["checks"]} >= {"pressure angle", "cut depth", "finish allowance"}


def _canonical_seconds(canon: str, rapid_mm_min: float, tool_change_s: float) -> float:
    """Sum of the interpreted moves: feeds at the last SET_FEED_RATE, rapids at ``rapid_mm_min``, tool changes."""
    pos, feed, minutes, changes = (0.0, 0.0, 0.0), None, 0.0, 0
    for line in canon.splitlines():
        m = re.search(r"(STRAIGHT_TRAVERSE|STRAIGHT_FEED|ARC_FEED|SET_FEED_RATE|CHANGE_TOOL)\((.*)\)", line)
        if not m:
            continue
        kind, args = m.group(1), [float(v) for v in re.split(r"[ ,]+", m.group(2).strip())]
        if kind == "SET_FEED_RATE":
            feed = args[0]
        elif kind == "CHANGE_TOOL":
            changes += 1
        elif kind == "ARC_FEED":
            x, y, cx, cy, rot, z = args[:6]
            a0 = math.atan2(pos[1] - cy, pos[0] - cx)
            a1 = math.atan2(y - cy, x - cx)
            sweep = ((a1 - a0) if rot > 0 else (a0 - a1)) % (2 * math.pi)
            r = math.hypot(x - cx, y - cy)
            minutes += math.hypot(r * sweep, z - pos[2]) / feed
            pos = (x, y, z)
        else:
            new = tuple(args[:3])
            minutes += math.dist(pos, new) / (rapid_mm_min if kind == "STRAIGHT_TRAVERSE" else feed)
            pos = new
    return 60.0 * minutes + changes * tool_change_s


@pytest.mark.skipif(not rs274_available(), reason="rs274 (Debian linuxcnc-uspace) is not installed")
def test_cycle_time_is_the_sum_of_the_interpreted_moves(run_dir, capsys):
    from camcam.post.post import load_post

    post = load_post("linuxcnc")
    report = json.loads((run_dir / "disc-translating-roller-report.json").read_text())
    canon = subprocess.run(["rs274", "-g", str(run_dir / "disc-translating-roller.ngc")], stdin=subprocess.DEVNULL,
                           capture_output=True, text=True, timeout=60, check=True).stdout
    expected = _canonical_seconds(canon, post.rapid_mm_min, post.tool_change_s)
    # the bound is 2 %; both sums use the same constant-rate model on the same printed numbers,
    # so they agree to rs274's 4-decimal printing (1e-6 relative is far above that)
    assert report["cycle_time_s"] == pytest.approx(expected, rel=1e-6)
    assert abs(report["cycle_time_s"] - expected) <= 0.02 * expected
    assert 60 < report["cycle_time_s"] < 3600  # metres of feed at 200–400 mm/min: minutes, not seconds or hours


def _lost(html_file: Path, pdf: Path) -> dict:
    """Characters of the page's text that the printed PDF lacks (cut off at a page edge), by count.

    Chromium clips what runs past the paper; poppler's text then lacks it.
    Whitespace and line breaks (a word hyphenated over two lines) do not count.
    """
    text = re.sub(r"<style.*?</style>|<title>.*?</title>", " ", html_file.read_text(), flags=re.S)
    text = html.unescape(re.sub(r"<[^>]+>", " ", text))
    printed = subprocess.run(["pdftotext", "-raw", str(pdf), "-"], capture_output=True, text=True, check=True,
                             timeout=60).stdout
    return dict(Counter(re.sub(r"\s", "", text)) - Counter(re.sub(r"\s", "", printed)))


def _print(html: Path, pdf: Path) -> None:
    subprocess.run(["timeout", "120", "chromium", "--headless", "--no-sandbox", "--disable-gpu", "--no-pdf-header-footer",
                    f"--print-to-pdf={pdf}", html.as_uri()], capture_output=True, timeout=150, check=True)


def _page_texts(pdf: Path) -> list[str]:
    pages = int(re.search(r"Pages:\s+(\d+)", subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True,
                                                             check=True, timeout=60).stdout).group(1))
    return [subprocess.run(["pdftotext", "-layout", "-f", str(i), "-l", str(i), str(pdf), "-"], capture_output=True,
                           text=True, check=True, timeout=60).stdout for i in range(1, pages + 1)]


def _ink_bottom(pdf: Path, tmp_path: Path) -> list[float]:
    """Per page, how far down the page (0 top, 1 bottom edge) the lowest printed pixel lies (poppler's pdftoppm)."""
    import numpy as np

    subprocess.run(["pdftoppm", "-gray", "-r", "20", str(pdf), str(tmp_path / "ink")], check=True, timeout=60)
    out = []
    for f in sorted(tmp_path.glob("ink-*.pgm"), key=lambda p: int(p.stem.split("-")[1])):
        head, data = f.read_bytes(), None
        w, h = map(int, head.split(b"\n")[1].split())  # P5 / width height / 255 / pixels, as pdftoppm writes it
        data = np.frombuffer(head[-w * h:], dtype=np.uint8).reshape(h, w)
        rows = np.nonzero((data < 200).any(axis=1))[0]
        out.append((rows.max() + 1) / h if len(rows) else 0.0)
    return out


def _check_printed_sheet(html_file: Path, pdf: Path, tmp_path: Path) -> list[str]:
    """Issue 47: the setup sheet (verdict + setup) is page 1 alone; no later page is (almost) blank."""
    _print(html_file, pdf)
    pages = _page_texts(pdf)
    first = pages[0]
    assert first.index("PASS" if "PASS" in first else "WARN") < first.index("Setup") < first.index("cycle time")
    assert "plan" in first  # the passes table's header: the last block of the setup ends on page 1
    assert pages[1].lstrip().startswith("Job")  # the rest starts on page 2, not under the sheet
    # (almost) no text: under 100 printed characters (a figure's caption alone has over 100)
    assert all(len(re.sub(r"\s", "", t)) >= 100 for t in pages), [len(re.sub(r"\s", "", t)) for t in pages]
    # a page the next block skipped (a figure moved on whole) would end in its top half: every page but the
    # last is printed below its middle (the bottom margin is 12 mm of 297, so a full page reaches ~0.96)
    bottoms = _ink_bottom(pdf, tmp_path)
    assert len(bottoms) == len(pages) and all(b > 0.5 for b in bottoms[:-1]), bottoms
    return pages


@pytest.mark.skipif(shutil.which("chromium") is None or shutil.which("pdftotext") is None,
                    reason="chromium or poppler-utils (pdftotext, pdfinfo) missing")
def test_printed_setup_sheet_is_page_one_and_no_page_is_blank(run_dir, tmp_path):
    pages = _check_printed_sheet(run_dir / "disc-translating-roller-report.html", tmp_path / "disc.pdf", tmp_path)
    # the whole report is not one page: the inspection table's 36 rows, four plots and the program's first
    # 24 lines need six; the sheet is one, the rest follows without forced breaks
    assert len(pages) <= 6, len(pages)
    barrel = tmp_path / "barrel"
    assert main(["run", str(ROOT / "samples" / "cylindrical-translating.toml"), "-o", str(barrel)]) == 0
    assert len(_check_printed_sheet(barrel / "cylindrical-translating-report.html", tmp_path / "barrel.pdf",
                                    tmp_path / "barrel")) <= 4
    # with cutting data per pass kind (issue 47, Shop II) the sheet states them and still fits page 1
    feeds = tmp_path / "feeds"
    assert main(["run", str(ROOT / "samples" / "disc-cutting-data.toml"), "-o", str(feeds)]) == 0
    first = _check_printed_sheet(feeds / "disc-cutting-data-report.html", tmp_path / "feeds.pdf", tmp_path / "feeds")[0]
    assert "cutting data" in first and "S3979" in first


@pytest.mark.skipif(shutil.which("chromium") is None or shutil.which("pdftotext") is None,
                    reason="chromium or poppler-utils (pdftotext, pdfinfo) missing")
def test_report_prints_to_a4_without_cut_offs(run_dir, tmp_path):
    pdf = tmp_path / "report.pdf"
    _print(run_dir / "disc-translating-roller-report.html", pdf)
    info = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True, check=True, timeout=60).stdout
    w, h = map(float, re.search(r"Page size:\s+([\d.]+) x ([\d.]+) pts", info).groups())
    assert w == pytest.approx(595.28, abs=1.0) and h == pytest.approx(841.89, abs=1.0)  # A4: 210 × 297 mm in points
    assert _lost(run_dir / "disc-translating-roller-report.html", pdf) == {}
    text = subprocess.run(["pdftotext", "-layout", "-f", "1", "-l", "1", str(pdf), "-"], capture_output=True,
                          text=True, check=True, timeout=60).stdout
    assert text.index("PASS") < text.index("Setup") < text.index("cycle time")  # verdict and setup on page 1
    everything = subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True, check=True).stdout
    assert "band [mm]" in everything and "350" in everything  # the inspection table's last column and row
    # a page that does overflow is caught (the check can fail)
    wide = tmp_path / "wide.html"
    wide.write_text('<html><body><pre style="white-space:pre">' + "overflowing " * 80 + "</pre></body></html>")
    _print(wide, tmp_path / "wide.pdf")
    assert _lost(wide, tmp_path / "wide.pdf").get("o", 0) > 100  # most of 80 × "overflowing" is cut off


def _spec_without_machining(tmp_path: Path, extra_cam: str = "", report: str = "") -> Path:
    text = SAMPLE.read_text().split("[machining]")[0]
    text = text.replace('rotation = "ccw"\n', 'rotation = "ccw"\n' + extra_cam)
    spec = tmp_path / "pa.toml"
    spec.write_text(text + report)
    return spec


def test_pressure_angle_warns_then_fails_when_strict(tmp_path, capsys):
    # the sample's largest pressure angle is 22.26° (its report): a 20° limit is missed
    spec = _spec_without_machining(tmp_path, "max_pressure_angle_deg = 20.0\n")
    assert main(["run", str(spec), "-o", str(tmp_path / "a")]) == 0
    # issue 43: an advisory limit missed is the verdict (WARN) on stdout and in the report, never on stderr
    got = capsys.readouterr()
    assert got.err == ""
    assert re.search(r"^WARN: pressure angle 22\.26 deg over the advisory limit 20 deg", got.out, re.M)
    strict = _spec_without_machining(tmp_path, "max_pressure_angle_deg = 20.0\n", "\n[report]\nstrict = true\n")
    assert main(["run", str(strict), "-o", str(tmp_path / "b")]) == 3
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("camcam: FAIL: pressure angle 22.26 deg over the limit 20 deg")
    html = (tmp_path / "b" / "disc-translating-roller-report.html").read_text()
    assert html.index('<p class="verdict fail">FAIL</p>') < html.index("pressure angle")  # written, opens with FAIL
    assert main(["run", str(_spec_without_machining(tmp_path)), "-o", str(tmp_path / "c")]) == 0
    assert "pressure angle" not in capsys.readouterr().err  # 22.26° within the 30° default for a translating roller


def _fake(kind="disc", thickness=12.0, groove_depth=None, depth=12.0, stepdown=4.0, allowance=0.3):
    built = SimpleNamespace(spec=SimpleNamespace(kind=kind, thickness=thickness, groove_depth=groove_depth,
                                                 max_pressure_angle_deg=None),
                            cam=SimpleNamespace(kind="oscillating-roller", roller_radius=5.0),
                            analysis=SimpleNamespace(max_pressure_angle_deg=SimpleNamespace(value=34.0, angle_deg=10.0),
                                                     profile=SimpleNamespace(min_radius_mm=20.0, at_deg=30.0)))
    m = SimpleNamespace(depth_mm=depth, stepdown_mm=stepdown, finish_allowance_mm=allowance)
    return built, m


def test_cut_depth_and_allowance_checks():
    checks = {c.name: c for c in design_checks(*_fake())}
    assert all(c.ok for c in checks.values())
    assert checks["pressure angle"].limit == 35.0  # oscillating default
    checks = {c.name: c for c in design_checks(*_fake(depth=13.0, allowance=5.0))}
    assert not checks["cut depth"].ok and checks["cut depth"].limit == 12.0 and checks["cut depth"].severity == "warn"
    assert not checks["finish allowance"].ok and checks["finish allowance"].limit == 4.0
    groove = {c.name: c for c in design_checks(*_fake("disc-groove", 16.0, 8.0, depth=9.0), strict=True)}
    assert not groove["cut depth"].ok and groove["cut depth"].limit == 8.0 and groove["cut depth"].severity == "fail"
    assert "finish allowance" not in groove  # a groove's flanks have their own passes
