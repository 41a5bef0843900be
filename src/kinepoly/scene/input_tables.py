"""The motion a scene gives: an ``[input]`` driver (a link turning or a slider sliding) or ``[given.P]`` points.

A scene has exactly one of them. ``[input]`` names a link (angle, omega, alpha; turning on the
frame or, with ``relative_to``, on another link) or a slider (s, s_dot, s_ddot; on the frame or
between two moving links, a cylinder); ``[[input]]``, an array of such tables, gives one input per
degree of freedom. ``[given]`` gives the velocity (and acceleration) of two or more points of a
scene's single link.
"""

from __future__ import annotations

from kinepoly.scene.lines import KeyPath
from kinepoly.scene.problems import no_such, quoted
from kinepoly.scene.reader_state import ReaderState
from kinepoly.scene.source import Table
from kinepoly.scene.spec import GivenInput, GivenPoint, InputSpec, LinkInput, SliderInput
from kinepoly.scene.units import Kind, quantity, quantity_pair
from kinepoly.scene.values import Vector, check_keys, read_name, read_table, require

__all__ = ["InputTables"]

_LINK_INPUT_KEYS = ("link", "relative_to", "angle", "omega", "alpha")
_SLIDER_INPUT_KEYS = ("slider", "s", "s_dot", "s_ddot")
_GIVEN_KEYS = ("velocity", "acceleration")


class InputTables(ReaderState):
    """Reads ``[input]`` or ``[given]``, checking the names they use against the links and sliders."""

    def read_input(self, data: Table) -> tuple[InputSpec, ...] | None:
        """Every input, the first one first (a sweep varies it)."""
        has_input, has_given = "input" in data, "given" in data
        if has_input and has_given:
            self.report.add(("given",), "both [input] and [given]; expected exactly one of them")
            self.read_drivers(data["input"])
            return None
        if has_given:
            given = self.read_given(data["given"])
            return None if given is None else (given,)
        if has_input:
            return self.read_drivers(data["input"])
        self.report.add(
            ("input",),
            'missing; expected an [input] table (link = "2" or slider = "14") or [given.P] tables',
        )
        return None

    def read_drivers(self, value: object) -> tuple[LinkInput | SliderInput, ...] | None:
        """``[input]`` (one table) or ``[[input]]`` (an array of them, one per degree of freedom)."""
        if not isinstance(value, list):
            one = self.read_driver(("input",), value)
            return None if one is None else (one,)
        if not value:
            self.report.add(("input",), "an empty [[input]] array; expected one table per input")
            return None
        drivers = [self.read_driver(("input", str(k)), item) for k, item in enumerate(value, start=1)]
        found = tuple(d for d in drivers if d is not None)
        self.check_distinct_drivers(found)
        return found if len(found) == len(drivers) else None

    def check_distinct_drivers(self, drivers: tuple[LinkInput | SliderInput, ...]) -> None:
        seen: set[tuple[str, str]] = set()
        for k, driver in enumerate(drivers, start=1):
            key = ("slider", driver.slider) if isinstance(driver, SliderInput) else (
                "link", f"{driver.link}/{driver.relative_to or ''}")
            if key in seen:
                self.report.add(("input", str(k)), f"{key[0]} {key[1].rstrip('/')} is driven twice; expected "
                                "each input to drive a different joint")
            seen.add(key)

    def read_driver(self, path: KeyPath, value: object) -> LinkInput | SliderInput | None:
        table = read_table(self.report, path, value, 'an [input] table with link = "NAME" or slider = "NAME"')
        if table is None:
            return None
        check_keys(self.report, path, table, _LINK_INPUT_KEYS + _SLIDER_INPUT_KEYS)
        if "link" in table and "slider" in table:
            self.report.add(path + ("slider",), "both link and slider; expected one driver, a link or a slider")
            return None
        if "slider" in table:
            self.reject_keys(path, table, _LINK_INPUT_KEYS, "a slider input", _SLIDER_INPUT_KEYS)
            return self.read_slider_input(path, table)
        if "link" in table:
            self.reject_keys(path, table, _SLIDER_INPUT_KEYS, "a link input", _LINK_INPUT_KEYS)
            return self.read_link_input(path, table)
        self.report.add(path, 'no driver; expected link = "2" (a turning link) or slider = "14" (a driven slider)')
        return None

    def reject_keys(
        self, path: KeyPath, table: Table, wrong: tuple[str, ...], form: str, right: tuple[str, ...]
    ) -> None:
        for key in table:
            if key in wrong:
                self.report.add(path + (key,), f"not a key of {form}; expected {quoted(right)}")

    def read_link_input(self, path: KeyPath, table: Table) -> LinkInput | None:
        link = read_name(self.report, path + ("link",), table["link"], "a link name", "2")
        base = self.read_relative_to(path, table, link)
        if link is not None and not self.has_link(link):
            self.report.add(path + ("link",), no_such("link", link, self.links or {}))
        elif link is not None and link == self.ground:
            self.report.add(
                path + ("link",),
                f'link "{link}" is the ground; expected a moving link turning about a pin',
            )
        angle = self.required_quantity(path, table, "angle", self.kinds.angle)
        omega = self.required_quantity(path, table, "omega", self.kinds.omega)
        alpha = quantity(self.report, path + ("alpha",), table.get("alpha", 0.0), self.kinds.alpha)
        if link is None or angle is None or omega is None or alpha is None:
            return None
        return LinkInput(link, angle, omega, alpha, self.report.line(path), base)

    def read_relative_to(self, path: KeyPath, table: Table, link: str | None) -> str | None:
        """The link the input link turns on (None: the ground); it must share a pin with it."""
        if "relative_to" not in table:
            return None
        key = path + ("relative_to",)
        base = read_name(self.report, key, table["relative_to"], "a link name", "4")
        if base is None:
            return None
        if not self.has_link(base):
            self.report.add(key, lambda: no_such("link", base, self.links or {}))
            return None
        if base == link:
            self.report.add(key, f'link "{base}" cannot turn relative to itself; expected the link it turns on')
            return None
        if self.links is not None and link in self.links:
            shared = set(self.links[link].point_names) & set(self.links[base].point_names)
            if not shared:
                self.report.add(key, f'links "{link}" and "{base}" share no point; expected the link that '
                                f'"{link}" is pinned to (a relative rotation turns about their common pin)')
                return None
        return None if base == self.ground else base

    def read_slider_input(self, path: KeyPath, table: Table) -> SliderInput | None:
        slider = read_name(self.report, path + ("slider",), table["slider"], "a slider name", "14")
        if slider is not None and slider not in self.slider_names:
            self.report.add(path + ("slider",), no_such("slider", slider, self.slider_names))
        s = self.required_quantity(path, table, "s", self.kinds.length)
        s_dot = self.required_quantity(path, table, "s_dot", self.kinds.speed)
        s_ddot = quantity(self.report, path + ("s_ddot",), table.get("s_ddot", 0.0), self.kinds.accel)
        if slider is None or s is None or s_dot is None or s_ddot is None:
            return None
        return SliderInput(slider, s, s_dot, s_ddot, self.report.line(path))

    def required_quantity(self, path: KeyPath, table: Table, key: str, kind: Kind) -> float | None:
        value = require(self.report, path, table, key, f"{key} = {kind.expected()}")
        return None if value is None else quantity(self.report, path + (key,), value, kind)

    def read_given(self, value: object) -> GivenInput | None:
        path = ("given",)
        table = read_table(self.report, path, value, "[given.P] tables with velocity = [x, y]")
        if table is None:
            return None
        self.check_given_scene()
        points = [self.read_given_point(path + (name,), name, body) for name, body in table.items()]
        found = [point for point in points if point is not None]
        if len(table) < 2:
            self.report.add(path, f"{len(table)} given point; expected at least two, [given.A] and [given.B]")
        self.check_given_accelerations(found)
        if len(found) != len(points):
            return None
        return GivenInput(tuple(found), self.report.line(path))

    def check_given_scene(self) -> None:
        if self.links is not None and len(self.links) != 1:
            self.report.add(
                ("links",),
                f"a [given] scene has exactly one link, this has {len(self.links)}; expected one link",
            )
        if self.sliders:
            self.report.add(("sliders",), "a [given] scene has no sliders; expected no [[sliders]]")

    def read_given_point(self, path: KeyPath, name: str, value: object) -> GivenPoint | None:
        if name not in self.point_names and self.links is not None:
            self.report.add(path, lambda: no_such("point", name, self.point_names))
        table = read_table(self.report, path, value, "a table { velocity = [x, y], acceleration = [x, y] }")
        if table is None:
            return None
        check_keys(self.report, path, table, _GIVEN_KEYS)
        velocity_value = require(
            self.report, path, table, "velocity", "velocity = [x, y], " + self.kinds.speed.expected()
        )
        velocity = (
            None
            if velocity_value is None
            else quantity_pair(self.report, path + ("velocity",), velocity_value, self.kinds.speed)
        )
        acceleration: Vector | None = None
        if "acceleration" in table:
            acceleration = quantity_pair(self.report, path + ("acceleration",), table["acceleration"], self.kinds.accel)
            if acceleration is None:
                return None
        if velocity is None:
            return None
        return GivenPoint(name, velocity, acceleration, self.report.line(path))

    def check_given_accelerations(self, points: list[GivenPoint]) -> None:
        having = [point.name for point in points if point.acceleration is not None]
        if not having:
            return
        for point in points:
            if point.acceleration is None:
                self.report.add(
                    ("given", point.name, "acceleration"),
                    f"missing while given.{having[0]} has one; expected acceleration on every given point or on none",
                )
