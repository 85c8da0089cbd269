"""Post-processors: controller dialects as data (``post/*.toml``) and the G-code writer."""
