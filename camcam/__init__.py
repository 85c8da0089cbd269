"""camcam: from a cam's motion requirement to a verified NC program.

The flow (see README): spec → motion → geometry → toolpath → post/export/report.
"""

__version__ = "0.1.0"
