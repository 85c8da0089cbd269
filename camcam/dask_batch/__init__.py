"""The Dask batch engine: the independent tasks of `camcam size` and `camcam batch`, run in this process
or on a Dask cluster (``pip install 'camcam[scale]'``); the command-line options are :mod:`camcam.cli.dask_options`.

The public names load their module on first use (:mod:`camcam.lazy`).
"""

from camcam.lazy import lazy_exports

__getattr__, __dir__, __all__ = lazy_exports(__name__, {
    **dict.fromkeys(("Executor", "InProcess", "DaskExecutor", "open_executor", "dask_available", "SCALE_HINT"),
                    "camcam.dask_batch.engine"),
})
