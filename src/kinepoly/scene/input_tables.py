"""The motion a scene gives: an ``[input]`` driver (a link turning or a slider sliding) or ``[given.P]`` points.

A scene has exactly one of them. ``[input]`` names a link (angle, omega, alpha) or a slider
(s, s_dot, s_ddot); ``[given]`` gives the velocity (and acceleration) of two or more points
of a scene's single link.
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

_LINK_INPUT_KEYS = ("link", "angle", "omega", "alpha")
_SLIDER_INPUT_KEYS = ("slider", "s", "s_dot", "s_ddot")
_GIVEN_KEYS = ("velocity", "acceleration")


class InputTables(ReaderState):
    """Reads ``[input]`` or ``[given]``, checking the names they use against the links and sliders."""

    def read_input(self, data: Table) -> InputSpec | None:
        has_input, has_given = "input" in data, "given" in data
        if has_input and has_given:
            self.report.add(("given",), "both [input] and [given]; expected exactly one of them")
            self.read_driver(data["input"])
            return None
        if has_given:
            return self.read_given(data["given"])
        if has_input:
            return self.read_driver(data["input"])
        self.report.add(
            ("input",),
            'missing; expected an [input] table (link = "2" or slider = "14") or [given.P] tables',
        )
        return None

    def read_driver(self, value: object) -> LinkInput | SliderInput | None:
        path = ("input",)
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
        if link is not None and not self.has_link(link):
            self.report.add(path + ("link",), no_such("link", link, self.links or {}))
        elif link is not None and link == self.ground:
            self.report.add(
                path + ("link",),
                f'link "{link}" is the ground; expected a moving link turning about its joint with the ground',
            )
        angle = self.required_quantity(path, table, "angle", self.kinds.angle)
        omega = self.required_quantity(path, table, "omega", self.kinds.omega)
        alpha = quantity(self.report, path + ("alpha",), table.get("alpha", 0.0), self.kinds.alpha)
        if link is None or angle is None or omega is None or alpha is None:
            return None
        return LinkInput(link, angle, omega, alpha, self.report.line(path))

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
            self.report.add(path, no_such("point", name, self.point_names))
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
