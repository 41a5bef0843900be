"""Read a scene file (TOML) into the frozen values of :mod:`kinepoly.scene.spec`.

The whole scene is checked in one pass and every problem is reported at once, as a
:class:`~kinepoly.errors.SceneError` whose ``problems`` each read
``FILE:LINE: key.path: what is wrong; what is expected`` (``FILE: key.path: ...`` when no
line can be found). tomllib gives no line numbers, so :func:`kinepoly.scene.lines.scan_lines`
maps key paths to the lines where they are written.

Conventions a caller may rely on:

* lengths stay in the scene's length unit (unit strings such as ``"4 cm"`` are converted to
  it); angles are stored in radians; angular velocity in rad/s, angular acceleration rad/s^2;
* ``[[sliders]]`` are numbered from 1 in key paths: ``sliders.1.line`` is the first slider;
* instant-center pairs keep the user's order and are normalised to ``"13"`` (both names one
  character) or ``"1-13"``; repeated entries of a ``[find]`` list are dropped, the first kept.

The work is shared out: :mod:`~kinepoly.scene.source` (bytes to TOML data),
:mod:`~kinepoly.scene.lines` (the line map), :mod:`~kinepoly.scene.problems` (the report),
:mod:`~kinepoly.scene.values` and :mod:`~kinepoly.scene.units` (plain values and quantities),
and one reader per group of sections (:mod:`~kinepoly.scene.mechanism_tables`,
:mod:`~kinepoly.scene.input_tables`, :mod:`~kinepoly.scene.request_tables`). This module
reads the whole scene, and offers the same parsing to kinepoly's other TOML files.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Literal, cast

from kinepoly.scene.equivalent import with_equivalent_links
from kinepoly.scene.higher_pair_tables import HigherPairTables
from kinepoly.scene.input_tables import InputTables
from kinepoly.scene.lines import KeyPath, scan_lines
from kinepoly.scene.mechanism_tables import MechanismTables
from kinepoly.scene.problems import ProblemReport, quoted, show_value, suggest
from kinepoly.scene.request_tables import RequestTables
from kinepoly.scene.source import Table, fail, parse_toml, read_text
from kinepoly.scene.spec import GivenInput, Scene, Units
from kinepoly.scene.units import ANGLE_UNITS, LENGTH_UNITS, kinds_for, quantity
from kinepoly.scene.values import check_keys, check_showable, read_table

__all__ = ["ProblemReport", "load_scene", "loads_scene", "parse_located", "read_quantity", "show_value", "suggest"]

_TOP_KEYS = ("title", "units", "ground", "links", "sliders", "gears", "cams", "input", "given", "guess", "find", "draw",
             "vary")
_UNITS_KEYS = ("length", "angle")


# --------------------------------------------------------------------------------------------
# Public API


def load_scene(path: str | os.PathLike[str]) -> Scene:
    """Read and check the scene file at ``path``; problems name the path as given."""
    source = os.fspath(path)
    return loads_scene(read_text(source), source)


def loads_scene(text: str, source: str = "<string>") -> Scene:
    """Check the scene written in ``text``; ``source`` names it in problems."""
    text = text.removeprefix("\ufeff")
    if not text.strip():
        fail(source, None, "the file is empty; expected a scene with [links] and [input] or [given]")
    lines = scan_lines(text)
    data = parse_toml(text, source, lines)
    if not data:
        fail(source, None, "no keys, only comments; expected a scene with [links] and [input] or [given]")
    report = ProblemReport(source, lines)
    scene = _SceneReader(report, kinds_for(Units())).read(data)
    report.raise_if_any()
    if scene is None:  # pragma: no cover - every failure path reports a problem
        fail(source, None, "the scene could not be read; expected a valid scene")
    return scene


# --------------------------------------------------------------------------------------------
# The scene, section by section


class _SceneReader(MechanismTables, HigherPairTables, InputTables, RequestTables):
    """Reads one parsed scene; each method checks one section and reports what is wrong."""

    # -- the whole

    def read(self, data: Table) -> Scene | None:
        check_keys(self.report, (), data, _TOP_KEYS)
        units = self.read_units(data.get("units"))
        self.kinds = kinds_for(units)
        title = self.read_title(data.get("title"))
        self.links = self.read_links(data.get("links"))
        self.sliders = self.read_sliders(data.get("sliders"))
        self.check_joints()
        gears = self.read_gears(data.get("gears"))
        cams = self.read_cams(data.get("cams"))
        given_scene = "given" in data and "input" not in data
        self.ground = self.read_ground(data.get("ground"), given_scene)
        spec_inputs = self.read_input(data)
        guess = self.read_guess(data.get("guess"))
        find = self.read_find(data.get("find"))
        draw = self.read_draw(data.get("draw"))
        if "vary" in data:  # read by `kinepoly variants` (kinepoly.homework.vary); only its shape here
            read_table(self.report, ("vary",), data["vary"], "a [vary] table of ranges like angle = [30, 150]")
        if self.report.problems or spec_inputs is None or self.links is None:
            return None
        return with_equivalent_links(Scene(
            title=title,
            units=units,
            ground=self.ground,
            links=tuple(self.links.values()),
            sliders=tuple(self.sliders),
            input=spec_inputs[0],
            guess=guess,
            find=find,
            draw=draw,
            source=self.report.source,
            more_inputs=tuple(i for i in spec_inputs[1:] if not isinstance(i, GivenInput)),
            gears=tuple(gears),
            cams=tuple(cams),
        ))

    # -- title, units

    def read_title(self, value: object) -> str:
        if value is None:
            return _default_title(self.report.source)
        if isinstance(value, str):
            return value if check_showable(self.report, ("title",), value, "the title") else ""
        self.report.add(("title",), f'expected a string like "Offset slider-crank", got {show_value(value)}')
        return ""

    def read_units(self, value: object) -> Units:
        path = ("units",)
        if value is None:
            return Units()
        table = read_table(self.report, path, value, '{ length = "mm", angle = "deg" }')
        if table is None:
            return Units()
        check_keys(self.report, path, table, _UNITS_KEYS)
        length = self.read_unit_name(path + ("length",), table.get("length", "mm"), LENGTH_UNITS, "mm")
        angle = self.read_unit_name(path + ("angle",), table.get("angle", "deg"), ANGLE_UNITS, "deg")
        return Units(length=cast(Literal["mm", "cm", "m", "in"], length), angle=cast(Literal["deg", "rad"], angle))

    def read_unit_name(self, path: KeyPath, value: object, allowed: tuple[str, ...], default: str) -> str:
        if isinstance(value, str) and value in allowed:
            return value
        shown = show_value(value)
        if isinstance(value, str):
            self.report.add(path, lambda: f"unknown unit {shown}; {suggest(value, allowed)}")
        else:
            self.report.add(path, f"expected one of {quoted(allowed)}, got {shown}")
        return default


def _default_title(source: str) -> str:
    if source.startswith("<") or not source:
        return "untitled"
    return Path(source).stem or "untitled"


# --------------------------------------------------------------------------------------------
# For kinepoly's other TOML files (answers files, [vary]): the same parsing, lines and problems


def parse_located(text: str, source: str) -> tuple[Table, ProblemReport]:
    """Parse ``text`` as a scene is parsed (same syntax errors); the data and a report placing each key path."""
    text = text.removeprefix("\ufeff")
    lines = scan_lines(text)
    return parse_toml(text, source, lines), ProblemReport(source, lines)


def read_quantity(
    report: ProblemReport,
    path: KeyPath,
    value: object,
    kind: Literal["length", "speed", "accel", "angle", "omega", "alpha"],
    units: Units,
) -> float | None:
    """A number or unit string (``"4 cm"``, ``"300 rpm"``) as a scene's value of ``kind`` is read; None if wrong."""
    return quantity(report, path, value, getattr(kinds_for(units), kind))
