"""Post-processors: controller dialects as data (``post/*.toml``) and the G-code writer."""

from camcam.post.post import Post, load_post, known_posts, parse_post
from camcam.post.gcode import write_program, format_number

__all__ = ["Post", "load_post", "known_posts", "parse_post", "write_program", "format_number"]
