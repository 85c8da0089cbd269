"""Spec files (TOML) validated into frozen values; see :mod:`camcam.spec.document`."""

from camcam.spec.document import Spec, load_spec, parse_spec

__all__ = ["Spec", "load_spec", "parse_spec"]
