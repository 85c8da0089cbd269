"""scipy's k-d tree (:class:`scipy.spatial.cKDTree`) without the import of the whole of scipy.spatial.

The material check (:mod:`camcam.verify.removal`) needs one thing of scipy.spatial: ``cKDTree``.  Importing
``scipy.spatial`` runs its package, which loads Qhull, the distance functions, Voronoi, the rotations and
scipy.sparse's linear algebra besides the tree: 0.35–0.53 CPU s in the drawing's child where numpy, ezdxf and
shapely are loaded (issue 49; best and worst of 3 on the 2-core machine).  The tree is one extension module,
``scipy/spatial/_ckdtree``, which needs only numpy, ``scipy._lib`` and scipy.sparse's containers: loaded on
its own from its file it costs 0.10–0.14 CPU s.  Importing this module loads it (the drawing's child does,
beside the NC step: :data:`camcam.flow.CHECK_MODULES`).

It is loaded under its own name, ``scipy.spatial._ckdtree``, so the class is the very one scipy.spatial
exports: a later ``import scipy.spatial`` in the same process finds the module loaded and re-exports it (the
package's ``from ._ckdtree import cKDTree``), and trees pickle by that name.  Where the file is not found
(a scipy that moved it) the package is imported as usual: the same class, only dearer.

Examples
--------
>>> import numpy as np
>>> tree = cKDTree(np.array([[0.0, 0.0], [3.0, 4.0]]))
>>> d, i = tree.query(np.array([[3.0, 3.0]]))
>>> float(d[0]), int(i[0])
(1.0, 1)
"""

from __future__ import annotations

import importlib.machinery
import importlib.util
import sys
from pathlib import Path

__all__ = ["cKDTree", "ckdtree_module"]

_NAME = "scipy.spatial._ckdtree"


def ckdtree_module():
    """The module ``scipy.spatial._ckdtree``: the one loaded, else loaded from its file alone, else through
    the scipy.spatial package (module notes)."""
    loaded = sys.modules.get(_NAME)
    if loaded is not None:
        return loaded
    import scipy

    folder = Path(scipy.__file__).parent / "spatial"
    for suffix in importlib.machinery.EXTENSION_SUFFIXES:
        path = folder / f"_ckdtree{suffix}"
        if path.is_file():
            spec = importlib.util.spec_from_file_location(_NAME, path)
            module = importlib.util.module_from_spec(spec)
            sys.modules[_NAME] = module
            try:
                spec.loader.exec_module(module)
            except BaseException:
                del sys.modules[_NAME]
                raise
            return module
    import scipy.spatial  # noqa: F401  (the file is elsewhere: the package finds it)

    return sys.modules[_NAME]


#: scipy.spatial's k-d tree class, loaded as the module notes say.
cKDTree = ckdtree_module().cKDTree
