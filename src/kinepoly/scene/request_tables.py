"""What a scene asks for and how: ``[guess]`` start positions, ``[find]`` quantities, ``[draw]`` scales.

Without ``[find]`` every point, moving link and slider is asked for; repeated entries of a
``[find]`` list are dropped (the first kept); instant-center pairs are normalised to ``"13"``
or ``"1-13"``.
"""

from __future__ import annotations

from functools import partial
from typing import Literal

from kinepoly.scene.lines import KeyPath
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.problems import no_such, show_value
from kinepoly.scene.reader_state import ReaderState
from kinepoly.scene.spec import DrawSpec, FindSpec
from kinepoly.scene.units import quantity_pair
from kinepoly.scene.values import Vector, check_keys, pair_name, read_finite, read_table

__all__ = ["RequestTables"]

_FIND_KEYS = ("velocity", "acceleration", "omega", "alpha", "sliders", "instant_centers")
_DRAW_KEYS = ("kv", "ka")
_SCALE_RANGE = (1e-30, 1e30)
"""kv and ka a drawing can use: a polygon drawn smaller than an atom or larger than the sky is a typing error."""


class RequestTables(ReaderState):
    """Reads ``[guess]``, ``[find]`` and ``[draw]``, checking the names they use."""

    def read_guess(self, value: object) -> tuple[tuple[str, Vector], ...]:
        path = ("guess",)
        if value is None:
            return ()
        table = read_table(self.report, path, value, "a [guess] table of NAME = [x, y]")
        if table is None:
            return ()
        guesses: list[tuple[str, Vector]] = []
        for name, spot in table.items():
            if self.links is not None and name not in self.point_names:
                self.report.add(path + (name,), partial(no_such, "point", name, self.point_names))
            position = quantity_pair(self.report, path + (name,), spot, self.kinds.length)
            if position is not None:
                guesses.append((name, position))
        return tuple(guesses)

    def default_find(self) -> FindSpec:
        points = tuple(sorted(self.point_names))
        moving = tuple(sorted(name for name in (self.links or {}) if name != self.ground))
        return FindSpec(points, points, moving, moving, tuple(self.slider_names), (), is_default=True)

    def read_find(self, value: object) -> FindSpec:
        path = ("find",)
        if value is None:
            return self.default_find()
        table = read_table(self.report, path, value, "a [find] table")
        if table is None:
            return FindSpec()
        check_keys(self.report, path, table, _FIND_KEYS)
        return FindSpec(
            velocity=self.find_points(path + ("velocity",), table.get("velocity")),
            acceleration=self.find_points(path + ("acceleration",), table.get("acceleration")),
            omega=self.find_links(path + ("omega",), table.get("omega")),
            alpha=self.find_links(path + ("alpha",), table.get("alpha")),
            sliders=self.find_sliders(path + ("sliders",), table.get("sliders")),
            instant_centers=self.find_centers(path + ("instant_centers",), table.get("instant_centers")),
        )

    def string_list(self, path: KeyPath, value: object, what: str, example: str) -> list[str]:
        if value is None:
            return []
        if not isinstance(value, list):
            self.report.add(path, f"expected a list of {what}s like {example}, got {show_value(value)}")
            return []
        names: list[str] = []
        for index, item in enumerate(value, start=1):
            if isinstance(item, str) and item:
                names.append(item)
            else:
                self.report.add(path, f"item {index} is {show_value(item)}; expected {what}s as "
                                      f"strings, like {example}")
        return list(dict.fromkeys(names))

    def find_points(self, path: KeyPath, value: object) -> tuple[str, ...]:
        names = self.string_list(path, value, "point name", '["B", "A@4"]')
        return tuple(name for name in names if self.check_find_point(path, name))

    def check_find_point(self, path: KeyPath, name: str) -> bool:
        if self.links is None:
            return True
        named = LinkPoint.parse(name)
        point, link = named.point, named.link
        ok = True
        if point not in self.point_names:
            self.report.add(path, lambda: no_such("point", point, self.point_names))
            ok = False
        if link is not None and link not in self.links:
            self.report.add(path, f'in "{name}": {no_such("link", link, self.links)}')
            ok = False
        elif link is not None and point in self.links[link].point_names:
            self.report.add(path, f'"{name}": {point} is a point of link "{link}" itself; expected "{point}" (a name '
                            'like "A@4" is the point of link 4 that is at A, for a point of another link)')
            ok = False
        return ok

    def find_links(self, path: KeyPath, value: object) -> tuple[str, ...]:
        names = self.string_list(path, value, "link name", '["3", "4"]')
        kept: list[str] = []
        for name in names:
            if not self.has_link(name):
                self.report.add(path, partial(no_such, "link", name, self.links or {}))
            elif name == self.ground:
                self.report.add(path, f'link "{name}" is the ground, it does not move; expected moving links only')
            else:
                kept.append(name)
        return tuple(kept)

    def find_sliders(self, path: KeyPath, value: object) -> tuple[str, ...]:
        names = self.string_list(path, value, "slider name", '["14"]')
        known = self.slider_names
        for name in names:
            if name not in known:
                self.report.add(path, partial(no_such, "slider", name, known))
        return tuple(name for name in names if name in known)

    def find_centers(self, path: KeyPath, value: object) -> tuple[str, ...] | Literal["all"]:
        if value == "all":
            return "all"
        if isinstance(value, str):
            self.report.add(path, f'expected "all" or a list of pairs like ["13", "2-14"], got {show_value(value)}')
            return ()
        names = self.string_list(path, value, "link pair", '["13", "2-14"]')
        pairs = [self.read_center_pair(path, name) for name in names]
        return tuple(dict.fromkeys(pair for pair in pairs if pair is not None))

    def read_center_pair(self, path: KeyPath, text: str) -> str | None:
        pair = self.split_pair(text)
        if pair is None:
            self.report.add(
                path,
                f'"{text}" is not a pair of links; expected two link names like "13" or "1-3" '
                '("-" when a name is longer than one character)',
            )
            return None
        first, second = pair
        for name in pair:
            if not self.has_link(name):
                self.report.add(path, f'in "{text}": {no_such("link", name, self.links or {})}')
                return None
        if first == second:
            self.report.add(path, f'"{text}" names link "{first}" twice; expected two different links')
            return None
        return pair_name(first, second)

    def split_pair(self, text: str) -> tuple[str, str] | None:
        if "-" not in text:
            return (text[0], text[1]) if len(text) == 2 else None
        splits = [(text[:i], text[i + 1 :]) for i, char in enumerate(text) if char == "-"]
        splits = [(a, b) for a, b in splits if a and b]
        known = [(a, b) for a, b in splits if self.has_link(a) and self.has_link(b)]
        if len(known) == 1:
            return known[0]
        return splits[0] if len(splits) == 1 else None

    def read_draw(self, value: object) -> DrawSpec:
        path = ("draw",)
        if value is None:
            return DrawSpec()
        table = read_table(self.report, path, value, "a [draw] table")
        if table is None:
            return DrawSpec()
        check_keys(self.report, path, table, _DRAW_KEYS)
        return DrawSpec(
            kv=self.read_scale(path + ("kv",), table.get("kv")),
            ka=self.read_scale(path + ("ka",), table.get("ka")),
        )

    def read_scale(self, path: KeyPath, value: object) -> float | None:
        if value is None or value == "auto":
            return None
        expected = 'a positive number (drawing mm per unit) or "auto"'
        number = read_finite(self.report, path, value, expected)
        if number is not None and number <= 0:
            self.report.add(path, f"{show_value(value)} is not positive; expected {expected}")
            return None
        if number is not None and not _SCALE_RANGE[0] <= number <= _SCALE_RANGE[1]:
            self.report.add(path, f"{show_value(value)} is out of range; expected a scale between "
                            f"{_SCALE_RANGE[0]:g} and {_SCALE_RANGE[1]:g} (drawing mm per unit) or \"auto\"")
            return None
        return number
