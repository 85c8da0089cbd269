"""Worker processes: work done in forked children while the run goes on (the plot worker among them).

Two kinds, one module each:

* :mod:`camcam.workers.children`: one-off children (:func:`later`, collected
  with :func:`resolve`; :class:`ChildGroup` stops a group of them together)
  and :func:`parallel_map` (:class:`ProcessMap`, the map the NC stage hands the
  fitter);
* :mod:`camcam.workers.servers`: children that stay and take jobs over pipes,
  the plot worker (:class:`Server`, behind a :class:`Gate`) and the drawing's
  prepared child (:class:`Prepared`).

Every job is the very same call on the very same data as in process, so the
results are the same; without ``os.fork``, or within :func:`single_process` (a `camcam batch`
job on a Dask worker), every job runs at once, in process.
"""

from camcam.workers.children import (ChildError, ChildGroup, Pending, ProcessMap, call_target, freeze_start_up, later,
                                     parallel_map, preload, resolve, single_process)
from camcam.workers.servers import Gate, Prepared, Server

__all__ = ["ChildError", "Pending", "later", "resolve", "ChildGroup", "parallel_map", "call_target", "preload",
           "freeze_start_up", "single_process", "ProcessMap", "Server", "Prepared", "Gate"]
