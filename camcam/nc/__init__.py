"""The NC stage: a built cam and its ``[machining]`` table → a machining job.

Owns the job: tool-size rules, the disc and rotary jobs, the pass records and
the result (:class:`MachiningResult`).  It takes fitted paths from
:mod:`camcam.toolpath` and prints them with a :mod:`camcam.post` dialect.
"""

from camcam.nc.job import MachiningResult, machine

__all__ = ["MachiningResult", "machine"]
