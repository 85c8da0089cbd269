"""Shared test helpers: ``tests/`` on sys.path so test modules can import ``nc_curves``."""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
