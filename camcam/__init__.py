"""camcam: from a cam's motion requirement to a verified NC program.

The flow (see README): spec → motion → geometry → toolpath → post/export/report.
From Python, :func:`camcam.run_job` runs it for one spec and returns a :class:`camcam.Job`
(:mod:`camcam.flow`); nothing is written until ``job.write(folder)``.
"""

__version__ = "0.1.0"

__all__ = ["run_job", "Job", "__version__"]


def __getattr__(name: str):
    # the flow is loaded on first use: `import camcam` stays as light as the version string
    if name in ("run_job", "Job"):
        from camcam import flow

        return getattr(flow, name)
    raise AttributeError(f"module 'camcam' has no attribute {name!r}")
