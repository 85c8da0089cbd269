"""Tool paths: the NC second fitting (arcs and lines with a guaranteed deviation),
two-sided deviation measurement, and the neutral :class:`Toolpath` the posts print."""
