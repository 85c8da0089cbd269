"""Make the README's tour pictures from the samples' own runs.

    PYTHONPATH=. python docs/make_tour.py

Runs `camcam run` on samples/disc-translating-roller.toml,
samples/cylindrical-translating.toml and samples/cylindrical-translating-small-tool.toml
(its 3-D groove deviation map), copies their plots into docs/tour/, takes
a headless-Chromium screenshot of the report (top part) and writes the first
lines of the NC program to docs/tour/program-head.ngc; the sizing chart of
samples/size/translating-roller.toml goes to docs/tour/sizing.png.  The barrel cam's
STEP, read back with OpenCascade and tessellated, is drawn to docs/tour/barrel-step.png
(``python docs/make_tour.py step`` draws only that one, from a fresh run).
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


def step_picture(step: Path, png: Path) -> None:
    """Draw the solid a STEP file holds, as OpenCascade reads it back: its faces tessellated to 0.05 mm, shaded."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    from OCP.BRep import BRep_Tool
    from OCP.BRepMesh import BRepMesh_IncrementalMesh
    from OCP.TopAbs import TopAbs_Orientation, TopAbs_ShapeEnum
    from OCP.TopExp import TopExp_Explorer
    from OCP.TopLoc import TopLoc_Location
    from OCP.TopoDS import TopoDS

    from camcam.export.step import read_step

    shape = read_step(step.read_bytes())
    BRepMesh_IncrementalMesh(shape, 0.05, False, 0.2, True)
    tris = []
    e = TopExp_Explorer(shape, TopAbs_ShapeEnum.TopAbs_FACE)
    while e.More():
        face = TopoDS.Face(e.Current())
        mesh = BRep_Tool.Triangulation_s(face, TopLoc_Location())
        nodes = np.array([[mesh.Node(i).X(), mesh.Node(i).Y(), mesh.Node(i).Z()] for i in range(1, mesh.NbNodes() + 1)])
        for i in range(1, mesh.NbTriangles() + 1):
            a, b, c = mesh.Triangle(i).Get()
            tri = nodes[[a - 1, b - 1, c - 1]]
            tris.append(tri[::-1] if face.Orientation() == TopAbs_Orientation.TopAbs_REVERSED else tri)
        e.Next()
    tris = np.array(tris)
    normal = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    normal /= np.maximum(np.linalg.norm(normal, axis=1), 1e-12)[:, None]
    light = np.array([0.4, -0.5, 0.77]) / np.linalg.norm([0.4, -0.5, 0.77])
    shade = 0.35 + 0.65 * np.clip(normal @ light, 0, 1)
    fig = plt.figure(figsize=(7, 5), dpi=110)
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(tris, facecolors=plt.cm.Greys(0.25 + 0.6 * shade), edgecolor="none"))
    lo, hi = tris.reshape(-1, 3).min(0), tris.reshape(-1, 3).max(0)
    ax.set_xlim(lo[0], hi[0]); ax.set_ylim(lo[1], hi[1]); ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect(hi - lo)
    ax.view_init(elev=22, azim=-58)
    ax.set_axis_off()
    ax.set_title(f"{step.name}, read back with OpenCascade ({len(tris)} triangles)", fontsize=9)
    fig.savefig(png, bbox_inches="tight")
    plt.close(fig)


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
        step_picture(work / "cylindrical-translating" / "cylindrical-translating.step", TOUR / "barrel-step.png")
        small = "cylindrical-translating-small-tool"
        shutil.copy(work / small / f"{small}-groove-map.png", TOUR / "groove-map.png")
        head = (disc / "disc-translating-roller.ngc").read_text().splitlines()[:16]
        (TOUR / "program-head.ngc").write_text("\n".join(head) + "\n")
        shoot(disc / "disc-translating-roller-report.html", TOUR / "report.png", work)
        sized = work / "size"
        assert main(["size", str(ROOT / "samples" / "size" / "translating-roller.toml"), "-o", str(sized), "--in-process"]) == 0
        shutil.copy(sized / "size-translating-roller-sizing.png", TOUR / "sizing.png")


def step_only() -> None:
    """Only the barrel cam's STEP picture (a run of its sample, then :func:`step_picture`)."""
    with tempfile.TemporaryDirectory() as d:
        out = Path(d) / "barrel"
        assert main(["run", str(ROOT / "samples" / "cylindrical-translating.toml"), "-o", str(out)]) == 0
        step_picture(out / "cylindrical-translating.step", TOUR / "barrel-step.png")


if __name__ == "__main__":
    step_only() if sys.argv[1:] == ["step"] else run()
