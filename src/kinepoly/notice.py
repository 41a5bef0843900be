"""Warnings kinepoly reports in its results (not Python warnings): a stable code and a message."""

from __future__ import annotations

from msgspec import Struct

__all__ = ["Notice"]


class Notice(Struct, frozen=True):
    """A warning with a stable ``code`` (``default-assembly``, ``near-singular``, ...)."""

    code: str
    message: str
