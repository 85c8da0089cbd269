"""Reports for the machinist and the inspector: self-contained HTML and JSON."""
