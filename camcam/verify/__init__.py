"""Checks with programs nobody on the project wrote (LinuxCNC's rs274 interpreter)."""
