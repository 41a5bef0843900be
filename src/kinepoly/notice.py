"""Warnings kinepoly reports in its results (not Python warnings): a stable code and a message."""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["Notice"]


@dataclass(frozen=True)
class Notice:
    """A warning with a stable ``code`` (``default-assembly``, ``near-singular``, ...)."""

    code: str
    message: str
