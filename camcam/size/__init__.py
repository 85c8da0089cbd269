"""Sizing sweeps: thousands of disc-cam designs evaluated with closed forms, the best one checked exactly."""
