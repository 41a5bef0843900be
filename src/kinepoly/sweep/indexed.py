"""The mechanism with its name lookups indexed once.

``Mechanism.local``, ``has_point`` and ``links_of_point`` scan the scene's links on every call;
a sweep asks them a few hundred times while the numpy work for thousands of rows takes about a
millisecond, so the scans would cost as much as the sweep. ``IndexedMechanism`` answers the
same questions from dictionaries built on first use; it is a ``Mechanism`` in every other way.
"""

from __future__ import annotations

from functools import cached_property

from kinepoly.model.mechanism import Mechanism

__all__ = ["IndexedMechanism", "indexed"]

Vec = tuple[float, float]


class IndexedMechanism(Mechanism):
    """A ``Mechanism`` whose point lookups are dictionary lookups."""

    @cached_property
    def _locals(self) -> dict[tuple[str, str], Vec]:
        return {(link.name, p.name): p.local for link in self.scene.links for p in link.points}

    @cached_property
    def _links_of(self) -> dict[str, tuple[str, ...]]:
        out: dict[str, list[str]] = {}
        for link in self.scene.links:
            for p in link.points:
                out.setdefault(p.name, []).append(link.name)
        return {point: tuple(links) for point, links in out.items()}

    def local(self, link: str, point: str) -> Vec:
        try:
            return self._locals[(link, point)]
        except KeyError:
            return super().local(link, point)  # raises as the mechanism does

    def has_point(self, link: str, point: str) -> bool:
        return (link, point) in self._locals

    def links_of_point(self, point: str) -> tuple[str, ...]:
        return self._links_of.get(point, ())


def indexed(mechanism: Mechanism) -> IndexedMechanism:
    """The same mechanism, indexed."""
    if isinstance(mechanism, IndexedMechanism):
        return mechanism
    return IndexedMechanism(scene=mechanism.scene, revolutes=mechanism.revolutes)
