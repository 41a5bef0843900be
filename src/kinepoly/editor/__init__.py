"""``kinepoly edit``: a local web page that edits a scene by hand and redraws its polygons as it changes.

The editor holds no geometry of its own: every change is an edit of the scene's TOML text
(``edits``, through tomlkit, which keeps the user's comments, order and formatting), and every
answer is the engine's solve and the drawing code's sheet of that text (``evaluate``), as
``kinepoly solve --json`` and ``kinepoly draw`` make them. ``document`` holds the text, its undo
history and what is on disk; ``server`` is the ASGI app (starlette) behind the page, bound to
127.0.0.1 and guarded by a token (docs/editor.md describes its JSON API).
"""

from __future__ import annotations

from kinepoly.editor.template_names import TEMPLATES

__all__ = ["TEMPLATES"]
