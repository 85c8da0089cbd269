"""matplotlib imported the cheap way (camcam.plots.mpl_import) draws the same pixels and behaves the same."""

import subprocess
import sys

#: Draws a figure with lines, markers, a patch, text, a legend and a colour mesh; prints a hash of its pixels.
DRAW = r"""
import hashlib, sys
if sys.argv[1] == "cheap":
    from camcam.plots.mpl_import import load_matplotlib
    load_matplotlib()
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from matplotlib.patches import Circle
fig = Figure(figsize=(5, 4))
FigureCanvasAgg(fig)
ax0, ax1 = fig.subplots(2, 1)
x = np.linspace(0, 6, 200)
ax0.plot(x, np.sin(x), lw=1.4, label="sin")
ax0.plot(x[::10], np.cos(x[::10]), "o", ms=3, label="cos")
ax0.add_patch(Circle((3, 0), 0.5, fill=False, color="C2"))
ax0.set_title("title ²³ −1", y=1.0)
ax0.legend(fontsize=7)
ax0.grid(True, alpha=0.3)
ax1.pcolormesh(np.arange(4.0), np.arange(3.0), np.arange(12.0).reshape(3, 4), cmap="RdBu_r", shading="nearest")
line = ax1.plot([0, 1], [0, 1])[0]
line.set(lw=3, c="r")  # aliases through Artist.set
fig.canvas.draw()
print(hashlib.sha256(bytes(fig.canvas.buffer_rgba())).hexdigest(), line.get_linewidth(), line.get_color(),
      "mpl_toolkits.mplot3d" in sys.modules)
"""


def run(mode: str) -> list[str]:
    out = subprocess.run([sys.executable, "-c", DRAW, mode], capture_output=True, text=True, check=True)
    return out.stdout.split()


def test_same_pixels_and_setters_as_the_ordinary_import():
    cheap, ordinary = run("cheap"), run("ordinary")
    assert cheap[:3] == ordinary[:3]
    assert cheap[1:3] == ["3.0", "r"]
    assert (cheap[3], ordinary[3]) == ("False", "True")  # the 3-D toolkit is what the cheap import skips


def test_the_skipped_work_is_skipped_and_undone():
    code = (
        "import inspect, sys\n"
        "from camcam.plots.mpl_import import load_matplotlib\n"
        "load_matplotlib()\n"
        "from matplotlib.lines import Line2D\n"
        "from matplotlib.artist import Artist\n"
        "print(Line2D.set.__doc__ is None, 'linewidth' in inspect.signature(Line2D.set).parameters)\n"
        "from matplotlib.axes import Axes\n"
        "print('agg_filter' in Axes.plot.__doc__)\n"
        "class Mine(Artist):\n"
        "    def set_speed(self, v): pass\n"
        "print('speed' in inspect.signature(Mine.set).parameters)\n"
        "import mpl_toolkits.mplot3d\n"
        "print('imported')\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout.split()
    # no generated docs or property lists (Axes.plot's lists Line2D's) during the import; an artist class made
    # afterwards gets them as usual; 3-D still imports
    assert out == ["True", "False", "False", "True", "imported"]
