"""Plots rendered to PNG bytes (matplotlib, Agg, deterministic metadata)."""
