"""A point of a link as the textbook names it: ``B``, or ``B@4``, the point of link 4 that is under B.

``B@4`` is how a scene's ``[find]``, the JSON and the construction name the material point of a link at a
place another link's point B marks (a slider's block over its guide, a cam's contact, a planet at its pitch
point). ``LinkPoint`` makes that text and reads it, here only.
"""

from __future__ import annotations

from msgspec import Struct

__all__ = ["SEPARATOR", "LinkPoint", "point_of"]

SEPARATOR = "@"
"""Between the point's name and the link's: no point or link name holds it."""


class LinkPoint(Struct, frozen=True):
    """``point`` (a point's name), as a point of ``link``; ``link`` None for the point itself (``B``), a link's
    name for the point of that link under it (``B@4``)."""

    point: str
    link: str | None = None

    @classmethod
    def parse(cls, text: str) -> LinkPoint:
        """``"B"`` or ``"B@4"`` as a value (``"B@"`` keeps an empty link name, which a check can refuse)."""
        point, at, link = text.partition(SEPARATOR)
        return cls(point, link if at else None)

    @property
    def text(self) -> str:
        """The textbook's name: ``B`` or ``B@4``."""
        return self.point if self.link is None else f"{self.point}{SEPARATOR}{self.link}"

    @property
    def at_link(self) -> str:
        """What the name adds to the point's: ``@4``, or nothing for the point itself."""
        return "" if self.link is None else f"{SEPARATOR}{self.link}"

    def __str__(self) -> str:
        return self.text


def point_of(text: str) -> str:
    """The point's name in ``"B"`` or ``"B@4"``: ``B``."""
    return LinkPoint.parse(text).point
