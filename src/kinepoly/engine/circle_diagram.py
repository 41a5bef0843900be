"""The circle (Kennedy) diagram, combinatorially: which instant centers to derive, in which order.

Each link is a point on a circle; a known instant center I_ij is the edge ij. The centers of the
joints are known from the start (a pin, or a slider's center at infinity). An unknown edge ij
can be drawn when it closes two triangles ijk and ijl whose other edges are known: I_ij is then
where the line I_ik I_jk crosses the line I_il I_jl (the Aronhold-Kennedy theorem). Repeating
this round by round finds every center the theorem can reach.

A higher pair (a cam and its follower) is a *line edge*: its center is not known at once as a
point but as a line, the common normal at the contact (the relative motion of the two links is a
turn about a point of it). One triangle ijk whose other edges are known points is then enough:
the Kennedy line I_ik I_jk crosses the common normal at I_ij.

``plan_kennedy`` keeps only the centers on the path to the asked ones: for each asked edge the
pair of triangles that needs the fewest derived centers, and recursively theirs. No geometry
here: the plan is made before any position is solved.
"""

from __future__ import annotations

import math
from itertools import combinations
from typing import Literal

from msgspec import Struct

from kinepoly.geom.vec import Vec

__all__ = [
    "CircleDiagram",
    "DiagramEdge",
    "Edge",
    "KennedyPlan",
    "center_label",
    "circle_positions",
    "edge",
    "pair_name",
    "plan_kennedy",
    "split_pair",
    "triangle_name",
]

Edge = tuple[str, str]
"""Two links, in the order of the scene's [links] table."""


def edge(first: str, second: str, links: tuple[str, ...]) -> Edge:
    """The edge of two links, ordered as the scene lists them."""
    return (first, second) if links.index(first) < links.index(second) else (second, first)


def pair_name(pair: Edge) -> str:
    """``"13"``, or ``"1-13"`` when a name is longer than one character (as the scene writes pairs)."""
    first, second = pair
    return first + second if len(first) == 1 and len(second) == 1 else f"{first}-{second}"


def split_pair(name: str, links: tuple[str, ...]) -> Edge:
    """The edge of a pair name (``"13"``, ``"31"``, ``"frame-rod"``); ValueError if it names no two links."""
    if len(name) == 2 and name[0] in links and name[1] in links and name[0] != name[1]:
        return edge(name[0], name[1], links)
    for index, char in enumerate(name):
        first, second = name[:index], name[index + 1:]
        if char == "-" and first in links and second in links and first != second:
            return edge(first, second, links)
    raise ValueError(f"{name!r} names no two links of {', '.join(links)}")


def center_label(name: str) -> str:
    """The textbook name of a center: ``I13``, or ``I(frame-rod)`` when a link's name is longer."""
    return f"I{name}" if "-" not in name else f"I({name})"


class KennedyPlan(Struct, frozen=True):
    """What the circle diagram will derive.

    ``known``: the edges known at once as points (joints); ``lines``: the line edges (higher pairs,
    known at once as their common normal); ``order``: the derived edges on the path to ``targets``,
    in the order the diagram finds them (round by round); ``options``: for each edge that the
    theorem can reach, the third links k whose triangles ijk close it in the round it is found;
    ``chosen``: the two third links of a point found by two triangles, the one of a line edge's;
    ``unreachable``: asked edges it cannot reach.
    """

    links: tuple[str, ...]
    known: frozenset[Edge]
    targets: tuple[Edge, ...]
    order: tuple[Edge, ...]
    options: dict[Edge, tuple[str, ...]]
    chosen: dict[Edge, tuple[str, ...]]
    unreachable: tuple[Edge, ...]
    lines: frozenset[Edge] = frozenset()

    def sides(self, e: Edge) -> tuple[Edge, ...]:
        """The other edges of the triangles chosen for ``e``: four for two triangles, two for a line edge's
        one (none for a joint)."""
        if e not in self.chosen:
            return ()
        i, j = e
        return tuple(edge(a, k, self.links) for k in self.chosen[e] for a in (i, j))


def _closure(links: tuple[str, ...], known: frozenset[Edge],
             lines: frozenset[Edge]) -> tuple[dict[Edge, int], dict[Edge, tuple[str, ...]]]:
    """Round of every reachable edge (0 for joints) and the triangles that close it in that round (two
    for a point, one for a line edge)."""
    round_of: dict[Edge, int] = {e: 0 for e in known}
    options: dict[Edge, tuple[str, ...]] = {}
    number = 0
    while True:
        number += 1
        found: dict[Edge, tuple[str, ...]] = {}
        for i, j in combinations(links, 2):
            if (i, j) in round_of:
                continue
            ks = tuple(k for k in links if k not in (i, j)
                       and edge(i, k, links) in round_of and edge(j, k, links) in round_of)
            if len(ks) >= (1 if (i, j) in lines else 2):
                found[(i, j)] = ks
        if not found:
            return round_of, options
        for e, ks in found.items():
            round_of[e] = number
            options[e] = ks


def plan_kennedy(links: tuple[str, ...], known: frozenset[Edge], targets: tuple[Edge, ...],
                 lines: frozenset[Edge] = frozenset()) -> KennedyPlan:
    """The derived edges on the path to ``targets``, each closed by the triangles needing least: two
    triangles for a point, one (crossed with its common normal) for a line edge of ``lines``."""
    lines = lines - known
    round_of, options = _closure(links, known, lines)
    needs: dict[Edge, frozenset[Edge]] = {}
    chosen: dict[Edge, tuple[str, ...]] = {}

    def needed(e: Edge) -> frozenset[Edge]:
        if e in known:
            return frozenset()
        if e not in needs:
            i, j = e
            best: frozenset[Edge] | None = None
            thirds = [(k,) for k in options[e]] if e in lines else list(combinations(options[e], 2))
            for ks in thirds:
                sides = tuple(edge(a, k, links) for k in ks for a in (i, j))
                union = frozenset().union(*(needed(s) for s in sides))
                if best is None or len(union) < len(best):
                    best, chosen[e] = union, ks
            assert best is not None
            needs[e] = best | {e}
        return needs[e]

    reachable = tuple(t for t in targets if t in round_of)
    path = frozenset().union(*(needed(t) for t in reachable)) if reachable else frozenset()
    every = list(combinations(links, 2))
    order = tuple(sorted(path, key=lambda e: (round_of[e], every.index(e))))
    unreachable = tuple(t for t in targets if t not in round_of)
    return KennedyPlan(links, known, targets, order, options, {e: chosen[e] for e in order}, unreachable, lines)


class DiagramEdge(Struct, frozen=True):
    """One edge of the circle diagram: a center known from a joint (solid), derived (dashed), or a
    higher pair's line edge (``"line"``: known at once as its common normal, drawn dash-dot).

    ``number`` is 0 for a joint's center (and a line edge whose point was not needed) and n for the
    n-th center derived; ``via`` says how: ``"pin A0"``, ``"slider 14"``, ``"triangles 124 and 234"``,
    ``"common normal of cam 23"`` or ``"common normal of cam 23 and triangle 123"``.
    """

    links: Edge
    kind: Literal["joint", "derived", "line"]
    number: int
    via: str

    @property
    def name(self) -> str:
        return pair_name(self.links)


class CircleDiagram(Struct, frozen=True):
    """The diagram as drawing data: links as points on a unit circle, edges in the order found.

    ``on_circle`` places the links on the unit circle in scene order, the first at the top and
    the rest clockwise; a sheet scales and places the circle beside the mechanism.
    """

    links: tuple[str, ...]
    on_circle: dict[str, Vec]
    edges: tuple[DiagramEdge, ...]


def triangle_name(links: tuple[str, ...], *members: str) -> str:
    """``"124"`` (or ``"1-2-14"`` with a long name): the links of a triangle in scene order."""
    ordered = sorted(members, key=links.index)
    return "".join(ordered) if all(len(m) == 1 for m in ordered) else "-".join(ordered)


def circle_positions(links: tuple[str, ...]) -> dict[str, Vec]:
    """Unit-circle points for the links: the first at the top (90 degrees), then clockwise."""
    n = len(links)
    out: dict[str, Vec] = {}
    for index, link in enumerate(links):
        angle = math.pi / 2.0 - 2.0 * math.pi * index / n
        out[link] = (math.cos(angle) + 0.0, math.sin(angle) + 0.0)
    return out
