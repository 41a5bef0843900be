"""The names of the scenes a new file starts from (``kinepoly edit --template``)."""

from __future__ import annotations

__all__ = ["TEMPLATES"]

TEMPLATES = ("four-bar", "slider-crank", "slotted-lever", "six-bar", "cam", "gear-pair")
"""The scenes a new file starts from (package data in ``templates/``, copies of the project's examples)."""
