"""JSON that can sit inside a web page's ``<script>`` element: the one rule every page kinepoly writes follows.

Inside ``<script>`` the browser does not decode entities; it only looks for ``</script``, and after
``<!--`` also for ``<script``, which changes how the rest of the page is read. ``script_json`` writes
``<``, ``>`` and ``&`` as the JSON escapes ``\\u003c``, ``\\u003e`` and ``\\u0026`` (the rule template
engines use), so no title, name or text in the data can end the element or open a comment;
``JSON.parse`` reads the same value back.
"""

from __future__ import annotations

import json
from typing import Any

__all__ = ["script_json"]

_ESCAPES = str.maketrans({"<": "\\u003c", ">": "\\u003e", "&": "\\u0026"})


def script_json(value: Any) -> str:
    """``value`` as compact ASCII JSON (NaN or infinity: ValueError) that is safe inside ``<script>``."""
    return json.dumps(value, separators=(",", ":"), allow_nan=False).translate(_ESCAPES)
