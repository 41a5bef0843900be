"""The mechanism's sections of a scene: ``[links]`` and their points, the joints, ``[[sliders]]``, ``ground``.

Points are ``[x, y]`` or ``{ polar = [r, angle] }`` in their link's frame; a point name shared
by two links is a revolute joint; a slider's line is ``{ through = [x, y], angle = a }`` in
the guide's frame, and its name defaults to the guide's and the block's names (``"14"``).
"""

from __future__ import annotations

import math

from kinepoly.geom.tolerances import COINCIDENT_REL
from kinepoly.scene.lines import KeyPath
from kinepoly.scene.link_point import SEPARATOR
from kinepoly.scene.problems import no_such, quoted, show_value, suggest
from kinepoly.scene.reader_state import ReaderState
from kinepoly.scene.source import Table
from kinepoly.scene.spec import LinkSpec, PointSpec, SliderSpec
from kinepoly.scene.units import quantity, quantity_pair
from kinepoly.scene.values import Vector, check_keys, check_showable, pair_name, read_name, read_table, require

__all__ = ["MechanismTables"]

_NOWHERE: Vector = (math.nan, math.nan)  # stands in for a value that failed; never returned

_LINK_KEYS = ("points",)
_SLIDER_KEYS = ("block", "guide", "point", "line", "name")
_LINE_KEYS = ("through", "angle")


class MechanismTables(ReaderState):
    """Reads ``ground``, ``[links]`` (with the joints their shared point names make) and ``[[sliders]]``."""

    def read_ground(self, value: object, given_scene: bool) -> str | None:
        path = ("ground",)
        if given_scene:
            if value is not None:
                self.report.add(path, "a [given] scene has no frame link; expected no ground key")
            return None
        if value is None:
            if self.links is not None and "1" not in self.links:
                self.report.add(
                    path,
                    f'no link "1" (the default ground); expected ground = "NAME" naming one of {quoted(self.links)}',
                )
            return "1"
        name = read_name(self.report, path, value, "a link name", "1")
        if name is not None and not self.has_link(name):
            self.report.add(path, lambda: no_such("link", name, self.links or {}))
        return name

    # -- links and their points

    def read_links(self, value: object) -> dict[str, LinkSpec] | None:
        path = ("links",)
        if value is None:
            self.report.add(path, "missing; expected a [links] table like 1 = { points = { A0 = [0, 0] } }")
            return None
        table = read_table(self.report, path, value, "a [links] table of link names")
        if table is None:
            return None
        if not table:
            self.report.add(path, "no links; expected at least one link")
        return {name: self.read_link(path + (name,), name, body) for name, body in table.items()}

    def read_link(self, path: KeyPath, name: str, body: object) -> LinkSpec:
        line = self.report.line(path)
        if not name:
            self.report.add(path, 'empty link name; expected a name like "2"')
        elif SEPARATOR in name:
            self.report.add(path, 'bad link name; expected a name without "@" (A@4 names the point of link 4 under A)')
        else:
            check_showable(self.report, path, name, "the link name")
        table = read_table(self.report, path, body, "{ points = { NAME = [x, y], ... } }")
        if table is None:
            return LinkSpec(name, (), line)
        check_keys(self.report, path, table, _LINK_KEYS)
        points = require(self.report, path, table, "points", "points = { NAME = [x, y], ... }")
        if points is None:
            return LinkSpec(name, (), line)
        return LinkSpec(name, self.read_points(path + ("points",), points), line)

    def read_points(self, path: KeyPath, value: object) -> tuple[PointSpec, ...]:
        table = read_table(self.report, path, value, "a table { NAME = [x, y], ... }")
        if table is None:
            return ()
        if not table:
            self.report.add(path, "no points; expected at least one named point")
        return tuple(self.read_point(path + (name,), name, spec) for name, spec in table.items())

    def read_point(self, path: KeyPath, name: str, value: object) -> PointSpec:
        line = self.report.line(path)
        if not name or SEPARATOR in name:
            self.report.add(path, 'bad point name; expected a name without "@" (kept for coincident points)')
        elif "/" in name:
            self.report.add(path, 'bad point name; expected a name without "/" (v_B/A names the velocity of B '
                            'relative to A)')
        else:
            check_showable(self.report, path, name, "the point name")
        local, polar = self.read_point_value(path, value)
        return PointSpec(name, _NOWHERE if local is None else local, line, polar)

    # -- joints implied by shared point names

    def check_joints(self) -> None:
        owners: dict[str, list[str]] = {}
        for link in (self.links or {}).values():
            for point in link.points:
                owners.setdefault(point.name, []).append(link.name)
        slider_points = {slider.point for slider in self.sliders}
        for link in (self.links or {}).values():
            joints = [p for p in link.points if len(owners[p.name]) > 1 or p.name in slider_points]
            self.check_distinct_joints(link.name, joints)

    def check_distinct_joints(self, link: str, joints: list[PointSpec]) -> None:
        for i, j in _close_pairs([joint.local for joint in joints]):
            first, second = joints[i], joints[j]
            if _same_place(first.local, second.local):
                x, y = first.local
                self.report.add(
                    ("links", link, "points", second.name),
                    f'joints "{first.name}" and "{second.name}" of link "{link}" are both at ({x:g}, {y:g}), '
                    "a zero-length link; expected joints at distinct places",
                )

    # -- sliders

    def read_sliders(self, value: object) -> list[SliderSpec]:
        path = ("sliders",)
        if value is None:
            return []
        if not isinstance(value, list) or not all(isinstance(item, dict) for item in value):
            self.report.add(path, f"expected [[sliders]] tables, got {show_value(value)}")
            return []
        sliders = [self.read_slider(path + (str(i),), item) for i, item in enumerate(value, start=1)]
        self.check_slider_names(sliders)
        return [slider for slider in sliders if slider is not None]

    def read_slider(self, path: KeyPath, table: Table) -> SliderSpec | None:
        check_keys(self.report, path, table, _SLIDER_KEYS)
        block = self.read_link_ref(path + ("block",), table, "the link that slides")
        guide = self.read_link_ref(path + ("guide",), table, "the link that carries the line")
        if block is not None and block == guide:
            self.report.add(path + ("guide",), f'block and guide are both link "{block}"; expected two different links')
        point = self.read_slider_point(path + ("point",), table, block)
        through, angle = self.read_slider_line(path + ("line",), table.get("line"))
        name = self.read_slider_name(path + ("name",), table.get("name"), block, guide)
        if name is None:
            return None
        return SliderSpec(name, block or "", guide or "", point or "", through, angle, self.report.line(path))

    def read_link_ref(self, path: KeyPath, table: Table, role: str) -> str | None:
        value = require(self.report, path[:-1], table, path[-1], f'{path[-1]} = "NAME", {role}')
        if value is None:
            return None
        name = read_name(self.report, path, value, "a link name", "4")
        if name is not None and not self.has_link(name):
            self.report.add(path, lambda: no_such("link", name, self.links or {}))
        return name

    def read_slider_point(self, path: KeyPath, table: Table, block: str | None) -> str | None:
        value = require(self.report, path[:-1], table, "point", 'point = "NAME", the block\'s point on the line')
        if value is None:
            return None
        name = read_name(self.report, path, value, "a point name", "B")
        links = self.links or {}
        if name is not None and block in links:
            known = links[block].point_names
            if name not in known:
                self.report.add(path, lambda: f'no point "{name}" in link "{block}" (the block); '
                                              f'{suggest(name, known)}')
        return name

    def read_slider_line(self, path: KeyPath, value: object) -> tuple[Vector, float]:
        if value is None:
            self.report.add(path, "missing; expected line = { through = [x, y], angle = a }")
            return _NOWHERE, math.nan
        table = read_table(self.report, path, value, "{ through = [x, y], angle = a }")
        if table is None:
            return _NOWHERE, math.nan
        check_keys(self.report, path, table, _LINE_KEYS)
        through_value = require(self.report, path, table, "through", "through = [x, y], a point of the line")
        angle_value = require(self.report, path, table, "angle", "angle = a, the line's direction")
        through = (
            None if through_value is None
            else quantity_pair(self.report, path + ("through",), through_value, self.kinds.length)
        )
        angle = (
            None if angle_value is None else quantity(self.report, path + ("angle",), angle_value, self.kinds.angle)
        )
        return (through or _NOWHERE), (math.nan if angle is None else angle)

    def read_slider_name(self, path: KeyPath, value: object, block: str | None, guide: str | None) -> str | None:
        if value is not None:
            return read_name(self.report, path, value, "a slider name", "14")
        if block is None or guide is None:
            return None
        return pair_name(guide, block)

    def check_slider_names(self, sliders: list[SliderSpec | None]) -> None:
        seen: dict[str, int] = {}
        for index, slider in enumerate(sliders, start=1):
            if slider is None:
                continue
            if slider.name in seen:
                self.report.add(
                    ("sliders", str(index)),
                    f'duplicate slider name "{slider.name}" (also sliders.{seen[slider.name]}); '
                    'expected a different name = "..."',
                )
            seen.setdefault(slider.name, index)


def _close_pairs(places: list[Vector]) -> list[tuple[int, int]]:
    """The pairs (i, j), i < j, in the order of a double loop, whose x differ by at most the widest tolerance of
    ``_same_place`` among ``places``: every pair at the same place is among them. Sorted by x and scanned, so that a
    link with many joints is checked in n log n, not by comparing every pair."""
    if len(places) < 2:
        return []
    reach = 1e-12 * max(1.0, *(max(abs(x), abs(y)) for x, y in places))
    order = sorted(range(len(places)), key=lambda k: places[k][0])
    pairs = []
    for at, i in enumerate(order):
        x = places[i][0]
        for j in order[at + 1:]:
            if places[j][0] - x > reach:
                break
            pairs.append((min(i, j), max(i, j)))
    return sorted(pairs)


def _same_place(first: Vector, second: Vector) -> bool:
    size = max(1.0, abs(first[0]), abs(first[1]), abs(second[0]), abs(second[1]))
    return math.hypot(first[0] - second[0], first[1] - second[1]) <= COINCIDENT_REL * size
