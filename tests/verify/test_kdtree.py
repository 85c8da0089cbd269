"""camcam.verify.kdtree: scipy's own k-d tree, loaded without the rest of scipy.spatial (issue 49)."""

import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[2]


def _python(code: str) -> str:
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                         env={**os.environ, "PYTHONPATH": str(ROOT)})
    assert run.returncode == 0, run.stderr[-2000:]
    return run.stdout.strip()


def test_the_tree_loads_without_scipy_spatials_package_and_is_its_class_afterwards():
    # in a fresh interpreter: the tree needs neither scipy.spatial's package nor scipy.interpolate; a later
    # import of the package re-exports the very class (the same module object), and trees pickle by its name
    out = _python(
        "import sys\n"
        "from camcam.verify.kdtree import cKDTree\n"
        "print('scipy.spatial' in sys.modules, 'scipy.interpolate' in sys.modules)\n"
        "import scipy.spatial\n"
        "print(scipy.spatial.cKDTree is cKDTree, cKDTree.__module__)\n")
    assert out.split("\n") == ["False False", "True scipy.spatial._ckdtree"]


def test_the_tree_answers_as_scipys_and_pickles():
    from scipy.spatial import cKDTree as scipy_tree

    from camcam.verify.kdtree import cKDTree

    # in this process scipy.spatial may be loaded first: then it is the same class
    assert cKDTree is scipy_tree
    rng = np.random.default_rng(7)
    pts, q = rng.normal(size=(500, 2)), rng.normal(size=(50, 2))
    tree = pickle.loads(pickle.dumps(cKDTree(pts, leafsize=64, balanced_tree=False, compact_nodes=False)))
    d, i = tree.query(q)
    brute = np.hypot(*(q[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
    # exact nearest distances both ways (one subtraction and hypot each: equal to the last bits)
    assert np.allclose(d, brute.min(axis=1), rtol=0, atol=1e-15)
    assert np.array_equal(i, brute.argmin(axis=1))


def test_a_disc_run_imports_no_scipy_interpolate_optimize_or_spatial_package():
    """A disc run (no STEP) needs of scipy only the material check's k-d tree: the DXF's splines are numpy's
    Hermite cubics and the tree is loaded alone; scipy.interpolate's and scipy.spatial's imports were 0.35–0.53
    CPU s of the drawing's child (issue 49).  Run in one process (--single-process) so sys.modules has all."""
    spec = ROOT / "samples" / "disc-translating-roller.toml"
    out = _python(
        "import sys, tempfile, pathlib, re\n"
        "from camcam.cli import main\n"
        f"text = pathlib.Path({str(spec)!r}).read_text()\n"
        "text = re.sub(r'(?m)^\\[report\\]\\s*$', '[report]\\nstep_file = false', text)\n"
        "text += '' if 'step_file' in text else '\\n[report]\\nstep_file = false\\n'\n"
        "d = pathlib.Path(tempfile.mkdtemp())\n"
        "(d / 's.toml').write_text(text)\n"
        "code = main(['run', str(d / 's.toml'), '-o', str(d / 'out'), '--single-process'])\n"
        "print(code, sorted(m for m in ('scipy.interpolate', 'scipy.optimize', 'scipy.spatial', 'trimesh', 'OCP')"
        " if m in sys.modules), 'scipy.spatial._ckdtree' in sys.modules)\n")
    assert out.splitlines()[-1] == "0 [] True"
