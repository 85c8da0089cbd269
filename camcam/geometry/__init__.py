"""Geometry stage: pitch curves, profiles and cams as exact parametric curves."""
