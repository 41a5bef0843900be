"""Read a scene file (TOML) into the frozen values of :mod:`kinepoly.scene.spec`.

The whole scene is checked in one pass and every problem is reported at once, as a
:class:`~kinepoly.errors.SceneError` whose ``problems`` each read
``FILE:LINE: key.path: what is wrong; what is expected`` (``FILE: key.path: ...`` when no
line can be found). tomllib gives no line numbers, so :func:`_scan` maps key paths to the
lines where they are written.

Conventions a caller may rely on:

* lengths stay in the scene's length unit (unit strings such as ``"4 cm"`` are converted to
  it); angles are stored in radians; angular velocity in rad/s, angular acceleration rad/s^2;
* ``[[sliders]]`` are numbered from 1 in key paths: ``sliders.1.line`` is the first slider;
* instant-center pairs keep the user's order and are normalised to ``"13"`` (both names one
  character) or ``"1-13"``; repeated entries of a ``[find]`` list are dropped, the first kept.
"""

from __future__ import annotations

import difflib
import json
import math
import os
import re
import tomllib
from collections.abc import Collection, Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Literal, NoReturn, cast

from kinepoly.errors import SceneError
from kinepoly.scene.spec import (
    DrawSpec,
    FindSpec,
    GivenInput,
    GivenPoint,
    InputSpec,
    LinkInput,
    LinkSpec,
    PointSpec,
    Scene,
    SliderInput,
    SliderSpec,
    Units,
)

__all__ = ["ProblemReport", "load_scene", "loads_scene", "parse_located", "read_quantity", "show_value", "suggest"]

KeyPath = tuple[str, ...]
Vector = tuple[float, float]
Table = Mapping[str, object]

_NOWHERE: Vector = (math.nan, math.nan)  # stands in for a value that failed; never returned

_TOP_KEYS = ("title", "units", "ground", "links", "sliders", "input", "given", "guess", "find", "draw", "vary")
_UNITS_KEYS = ("length", "angle")
_LINK_KEYS = ("points",)
_POLAR_KEYS = ("polar",)
_SLIDER_KEYS = ("block", "guide", "point", "line", "name")
_LINE_KEYS = ("through", "angle")
_LINK_INPUT_KEYS = ("link", "angle", "omega", "alpha")
_SLIDER_INPUT_KEYS = ("slider", "s", "s_dot", "s_ddot")
_GIVEN_KEYS = ("velocity", "acceleration")
_FIND_KEYS = ("velocity", "acceleration", "omega", "alpha", "sliders", "instant_centers")
_DRAW_KEYS = ("kv", "ka")

_LENGTH_UNITS = ("mm", "cm", "m", "in")
_ANGLE_UNITS = ("deg", "rad")
_MICROMETRES = {"mm": 1_000.0, "cm": 10_000.0, "m": 1_000_000.0, "in": 25_400.0}
_RADIANS = {"deg": math.pi / 180.0, "rad": 1.0}


# --------------------------------------------------------------------------------------------
# Public API


def load_scene(path: str | os.PathLike[str]) -> Scene:
    """Read and check the scene file at ``path``; problems name the path as given."""
    source = os.fspath(path)
    text = _decode(source, _read_bytes(source))
    return loads_scene(text, source)


def loads_scene(text: str, source: str = "<string>") -> Scene:
    """Check the scene written in ``text``; ``source`` names it in problems."""
    text = text.removeprefix("\ufeff")
    if not text.strip():
        _fail(source, None, "the file is empty; expected a scene with [links] and [input] or [given]")
    lines = _scan(text)
    data = _parse_toml(text, source, lines)
    if not data:
        _fail(source, None, "no keys, only comments; expected a scene with [links] and [input] or [given]")
    report = _Report(source, lines)
    scene = _SceneReader(report, _kinds(Units())).read(data)
    report.raise_if_any()
    if scene is None:  # pragma: no cover - every failure path reports a problem
        _fail(source, None, "the scene could not be read; expected a valid scene")
    return scene


# --------------------------------------------------------------------------------------------
# Bytes, text and TOML


def _fail(source: str, line: int | None, message: str, path: str = "(file)") -> NoReturn:
    where = source if line is None else f"{source}:{line}"
    raise SceneError([f"{where}: {path}: {message}"])


def _read_bytes(source: str) -> bytes:
    try:
        return Path(source).read_bytes()
    except FileNotFoundError:
        _fail(source, None, "no such file; expected the path of a scene .toml file")
    except IsADirectoryError:
        _fail(source, None, "is a directory; expected the path of a scene .toml file")
    except OSError as exc:
        _fail(source, None, f"cannot be read ({exc.strerror}); expected a readable scene .toml file")


def _decode(source: str, data: bytes) -> str:
    nul = data.find(b"\x00")
    if nul >= 0:
        line = data.count(b"\n", 0, nul) + 1
        _fail(source, line, "binary data (a NUL byte); expected a UTF-8 text TOML scene")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        bad = data[exc.start]
        _fail(
            source,
            line,
            f"not UTF-8 text (byte 0x{bad:02x} at offset {exc.start}); expected a UTF-8 TOML scene",
        )


_TOML_WHERE = re.compile(r"\s*\((?:at line (\d+), column (\d+)|at end of document)\)\s*$")


def _parse_toml(text: str, source: str, lines: _LineMap) -> Table:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise SceneError([_syntax_problem(str(exc), text, source, lines)]) from None
    except ValueError as exc:  # integers longer than Python converts
        raise SceneError([f"{source}: (file): {exc}; expected numbers of ordinary size"]) from None
    except RecursionError:
        raise SceneError([f"{source}: (file): arrays or tables nested too deeply; expected a flat scene"]) from None


def _syntax_problem(message: str, text: str, source: str, lines: _LineMap) -> str:
    match = _TOML_WHERE.search(message)
    what = message[: match.start()] if match else message
    if match and match.group(1):
        line, where = int(match.group(1)), f" at column {match.group(2)}"
    else:
        line, where = text.rstrip().count("\n") + 1, " at the end of the file"
    path = _dotted(lines.owner.get(line, ()))
    return f"{source}:{line}: {path}: TOML syntax error{where}: {what}; expected valid TOML"


def _dotted(path: KeyPath) -> str:
    return ".".join(path) if path else "(file)"


# --------------------------------------------------------------------------------------------
# Line scanner: which line each key path is written on


_BARE_KEY = re.compile(r"[A-Za-z0-9_-]+")


@dataclass
class _LineMap:
    """The first line of each key path, and the key path written or open on each line."""

    first: dict[KeyPath, int] = field(default_factory=dict)
    owner: dict[int, KeyPath] = field(default_factory=dict)

    def note(self, path: KeyPath, line: int) -> None:
        for end in range(1, len(path) + 1):
            self.first.setdefault(path[:end], line)
        self.owner.setdefault(line, path)

    def line_of(self, path: KeyPath) -> int | None:
        """The line of the most specific prefix of ``path`` that is written in the file."""
        for end in range(len(path), 0, -1):
            line = self.first.get(path[:end])
            if line is not None:
                return line
        return None


@dataclass
class _ScanState:
    lines: _LineMap = field(default_factory=_LineMap)
    table: KeyPath = ()
    last_key: KeyPath = ()
    arrays: dict[KeyPath, int] = field(default_factory=dict)
    depth: int = 0
    closer: str | None = None


def _scan(text: str) -> _LineMap:
    """Map key paths to lines. Tolerant: never raises, whatever the text."""
    state = _ScanState()
    for number, raw in enumerate(text.split("\n"), start=1):
        line = raw.removesuffix("\r")
        inside = state.closer is not None or state.depth > 0
        fallback = state.last_key if inside else state.table
        _scan_line(state, line, number)
        state.lines.owner.setdefault(number, fallback)
    return state.lines


def _scan_line(state: _ScanState, line: str, number: int) -> None:
    if state.closer is not None:
        start = _close_string(line, 0, state.closer)
        if start < 0:
            return
        state.closer = None
    elif state.depth == 0:
        start = _scan_line_start(state, line, number)
    else:
        start = 0
    _scan_rest(state, line, start)


def _scan_line_start(state: _ScanState, line: str, number: int) -> int:
    i = _skip_space(line, 0)
    if i >= len(line) or line[i] == "#":
        return len(line)
    if line.startswith("[[", i):
        return _scan_header(state, line, number, i + 2, array=True)
    if line[i] == "[":
        return _scan_header(state, line, number, i + 1, array=False)
    parts, end = _parse_key(line, i)
    if parts and end < len(line) and line[end] == "=":
        state.last_key = state.table + parts
        state.lines.note(state.last_key, number)
        return end + 1
    return i


def _scan_header(state: _ScanState, line: str, number: int, start: int, *, array: bool) -> int:
    parts, _ = _parse_key(line, start)
    if not parts:
        return len(line)
    if array:
        path = _resolve(state, parts[:-1]) + parts[-1:]
        count = state.arrays.get(path, 0) + 1
        state.arrays[path] = count
        state.table = path + (str(count),)
    else:
        state.table = _resolve(state, parts)
    state.last_key = state.table
    state.lines.note(state.table, number)
    return len(line)


def _resolve(state: _ScanState, parts: KeyPath) -> KeyPath:
    """Insert the running index after every prefix that is an array of tables."""
    out: KeyPath = ()
    for part in parts:
        out += (part,)
        count = state.arrays.get(out)
        if count is not None:
            out += (str(count),)
    return out


def _scan_rest(state: _ScanState, line: str, i: int) -> None:
    """Follow strings, comments and bracket depth to the end of the line."""
    while i < len(line):
        char = line[i]
        if char == "#":
            return
        if char in "\"'":
            i = _skip_string(state, line, i)
            continue
        if char in "[{":
            state.depth += 1
        elif char in "]}":
            state.depth = max(0, state.depth - 1)
        i += 1


def _skip_string(state: _ScanState, line: str, i: int) -> int:
    triple = line[i] * 3
    if line.startswith(triple, i):
        end = _close_string(line, i + 3, triple)
        if end < 0:
            state.closer = triple
            return len(line)
        return end
    return _string_end(line, i)


def _close_string(line: str, start: int, closer: str) -> int:
    """Index just after the multi-line string's closing delimiter, or -1 if not on this line."""
    i = start
    while i < len(line):
        if closer == '"""' and line[i] == "\\":
            i += 2
            continue
        if line.startswith(closer, i):
            end = i + 3
            while end < len(line) and end - i < 5 and line[end] == closer[0]:
                end += 1
            return end
        i += 1
    return -1


def _string_end(line: str, i: int) -> int:
    """Index just after the one-line string starting at ``i`` (or the end of the line)."""
    quote = line[i]
    j = i + 1
    while j < len(line):
        if quote == '"' and line[j] == "\\":
            j += 2
            continue
        if line[j] == quote:
            return j + 1
        j += 1
    return len(line)


def _skip_space(line: str, i: int) -> int:
    while i < len(line) and line[i] in " \t":
        i += 1
    return i


def _parse_key(line: str, i: int) -> tuple[KeyPath, int]:
    """A dotted key at ``i``: its parts and the index after it; no parts if there is none."""
    parts: list[str] = []
    while True:
        part, i = _parse_key_part(line, _skip_space(line, i))
        if part is None:
            return (), i
        parts.append(part)
        i = _skip_space(line, i)
        if i < len(line) and line[i] == ".":
            i += 1
            continue
        return tuple(parts), i


def _parse_key_part(line: str, i: int) -> tuple[str | None, int]:
    if i >= len(line):
        return None, i
    if line[i] in "\"'":
        end = _string_end(line, i)
        raw = line[i:end]
        if len(raw) < 2 or raw[-1] != line[i]:
            return None, i
        return _decode_key(raw), end
    match = _BARE_KEY.match(line, i)
    if match is None:
        return None, i
    return match.group(), match.end()


def _decode_key(raw: str) -> str:
    if raw.startswith("'"):
        return raw[1:-1]
    try:
        value = tomllib.loads(f"k = {raw}").get("k")
    except (tomllib.TOMLDecodeError, ValueError):
        return raw[1:-1]
    return value if isinstance(value, str) else raw[1:-1]


# --------------------------------------------------------------------------------------------
# Problems


@dataclass
class _Report:
    """Collects problems, each placed at the line of its key path."""

    source: str
    lines: _LineMap
    problems: list[tuple[int, str]] = field(default_factory=list)

    def add(self, path: KeyPath, message: str) -> None:
        line = self.lines.line_of(path)
        where = self.source if line is None else f"{self.source}:{line}"
        self.problems.append((line or 0, f"{where}: {_dotted(path)}: {message}"))

    def line(self, path: KeyPath) -> int:
        return self.lines.line_of(path) or 0

    def raise_if_any(self) -> None:
        if self.problems:
            ordered = sorted(dict.fromkeys(self.problems), key=lambda item: item[0])
            raise SceneError([text for _, text in ordered])


def _show(value: object, limit: int = 60) -> str:
    """A value as TOML would write it, cut short when long."""
    text = _toml_text(value)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _toml_text(value: object) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, list):
        return "[" + ", ".join(_toml_text(item) for item in value) + "]"
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{key} = {_toml_text(item)}" for key, item in value.items()) + " }"
    return str(value)


def _quoted(names: Iterable[str], limit: int = 12) -> str:
    names = list(names)
    shown = ", ".join(f'"{name}"' for name in names[:limit])
    return shown + (", …" if len(names) > limit else "")


def _suggest(word: str, options: Collection[str]) -> str:
    close = difflib.get_close_matches(word, list(options), n=1)
    if close:
        return f'did you mean "{close[0]}"?'
    if not options:
        return "expected none here"
    return f"expected one of {_quoted(sorted(options))}"


def _no_such(kind: str, name: str, known: Collection[str]) -> str:
    return f'no {kind} "{name}"; {_suggest(name, known)}'


# --------------------------------------------------------------------------------------------
# Quantities and plain values


@dataclass(frozen=True)
class _Kind:
    """A kind of quantity: how plain numbers and unit strings turn into the stored unit."""

    noun: str
    plain: str  # what a plain number means, e.g. "in mm"
    example: str
    units: Mapping[str, float]  # unit -> size in a base unit (µm, rad)
    per: float = 1.0  # base units per stored unit
    scale: float = 1.0  # stored units per plain number

    def expected(self) -> str:
        return f'{self.noun} (a number {self.plain}, or a string like "{self.example}")'


@dataclass(frozen=True)
class _Kinds:
    length: _Kind
    speed: _Kind
    accel: _Kind
    angle: _Kind
    omega: _Kind
    alpha: _Kind


def _kinds(units: Units) -> _Kinds:
    lu = units.length
    per = _MICROMETRES[lu]
    speeds = {f"{u}/s": size for u, size in _MICROMETRES.items()}
    accels = {f"{u}/s{sq}": size for u, size in _MICROMETRES.items() for sq in ("^2", "²")}
    turns = {"rad/s": 1.0, "deg/s": math.pi / 180.0, "rpm": math.pi / 30.0}
    spins = {f"{u}/s{sq}": size for u, size in _RADIANS.items() for sq in ("^2", "²")}
    return _Kinds(
        length=_Kind("a length", f"in {lu}", f"40 {lu}", _MICROMETRES, per),
        speed=_Kind("a velocity", f"in {lu}/s", f"-500 {lu}/s", speeds, per),
        accel=_Kind("an acceleration", f"in {lu}/s^2", f"0 {lu}/s^2", accels, per),
        angle=_Kind("an angle", f"in {units.angle}", "30 deg", _RADIANS, 1.0, _RADIANS[units.angle]),
        omega=_Kind("an angular velocity", "in rad/s", "300 rpm", turns),
        alpha=_Kind("an angular acceleration", "in rad/s^2", "2 rad/s^2", spins),
    )


_QUANTITY = re.compile(r"\s*(?P<number>[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*(?P<unit>\S+)?\s*", re.ASCII)


def _finite(report: _Report, path: KeyPath, value: object, expected: str) -> float | None:
    """A TOML number (int or float, not bool) as a finite float."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        report.add(path, f"expected {expected}, got {_show(value)}")
        return None
    try:
        number = float(value)
    except OverflowError:
        report.add(path, f"{_show(value)} is too large; expected {expected}")
        return None
    if not math.isfinite(number):
        report.add(path, f"{_show(value)} is not a finite number; expected {expected}")
        return None
    return number


def _quantity(report: _Report, path: KeyPath, value: object, kind: _Kind) -> float | None:
    """A number in the scene's unit, or a string with a unit; in the stored unit."""
    if isinstance(value, str):
        return _unit_string(report, path, value, kind)
    number = _finite(report, path, value, kind.expected())
    return None if number is None else number * kind.scale


def _unit_string(report: _Report, path: KeyPath, text: str, kind: _Kind) -> float | None:
    match = _QUANTITY.fullmatch(text)
    if match is None or match.group("unit") is None:
        report.add(path, f"expected {kind.expected()}, got {_show(text)}")
        return None
    unit = match.group("unit")
    size = kind.units.get(unit)
    if size is None:
        report.add(path, f'unknown unit "{unit}" for {kind.noun} in {_show(text)}; {_suggest(unit, kind.units)}')
        return None
    stored = float(match.group("number")) * size / kind.per
    if not math.isfinite(stored):
        report.add(path, f"{_show(text)} is too large; expected {kind.expected()}")
        return None
    return stored


def _pair(report: _Report, path: KeyPath, value: object, kind: _Kind) -> Vector | None:
    """``[x, y]``, each a quantity of ``kind``."""
    if not isinstance(value, list) or len(value) != 2:
        report.add(path, f"expected [x, y], each {kind.noun}, got {_show(value)}")
        return None
    x = _quantity(report, path + ("x",), value[0], kind)
    y = _quantity(report, path + ("y",), value[1], kind)
    return None if x is None or y is None else (x, y)


def _name(report: _Report, path: KeyPath, value: object, what: str, example: str) -> str | None:
    """A non-empty string naming something."""
    if isinstance(value, str) and value:
        return value
    report.add(path, f'expected {what} as a string like "{example}", got {_show(value)}')
    return None


def _table(report: _Report, path: KeyPath, value: object, expected: str) -> Table | None:
    if isinstance(value, dict):
        return cast(Table, value)
    report.add(path, f"expected {expected}, got {_show(value)}")
    return None


def _check_keys(report: _Report, path: KeyPath, table: Table, allowed: Collection[str]) -> None:
    for key in table:
        if key not in allowed:
            report.add(path + (key,), f"unknown key; {_suggest(key, allowed)}")


def _require(report: _Report, path: KeyPath, table: Table, key: str, expected: str) -> object | None:
    if key not in table:
        report.add(path + (key,), f"missing; expected {expected}")
        return None
    return table[key]


def _polar(r: float, angle: float) -> Vector:
    """The point at distance r and angle (rad); exact on the axes."""
    quarter = angle / (math.pi / 2.0)
    if abs(quarter - round(quarter)) < 1e-15 * max(1.0, abs(quarter)):
        cos, sin = ((1.0, 0.0), (0.0, 1.0), (-1.0, 0.0), (0.0, -1.0))[round(quarter) % 4]
        return (r * cos, r * sin)
    return (r * math.cos(angle), r * math.sin(angle))


def _default_title(source: str) -> str:
    if source.startswith("<") or not source:
        return "untitled"
    return Path(source).stem or "untitled"


def _pair_name(first: str, second: str) -> str:
    return first + second if len(first) == 1 and len(second) == 1 else f"{first}-{second}"


# --------------------------------------------------------------------------------------------
# The scene, section by section


@dataclass
class _SceneReader:
    """Reads one parsed scene; each method checks one section and reports what is wrong."""

    report: _Report
    kinds: _Kinds
    links: dict[str, LinkSpec] | None = None  # None: [links] could not be read at all
    sliders: list[SliderSpec] = field(default_factory=list)
    ground: str | None = None

    # -- names known so far

    def has_link(self, name: str) -> bool:
        return self.links is None or name in self.links

    @property
    def point_names(self) -> set[str]:
        return {p.name for link in (self.links or {}).values() for p in link.points}

    @property
    def slider_names(self) -> list[str]:
        return [slider.name for slider in self.sliders]

    # -- the whole

    def read(self, data: Table) -> Scene | None:
        _check_keys(self.report, (), data, _TOP_KEYS)
        units = self.read_units(data.get("units"))
        self.kinds = _kinds(units)
        title = self.read_title(data.get("title"))
        self.links = self.read_links(data.get("links"))
        self.sliders = self.read_sliders(data.get("sliders"))
        self.check_joints()
        given_scene = "given" in data and "input" not in data
        self.ground = self.read_ground(data.get("ground"), given_scene)
        spec_input = self.read_input(data)
        guess = self.read_guess(data.get("guess"))
        find = self.read_find(data.get("find"))
        draw = self.read_draw(data.get("draw"))
        if "vary" in data:  # read by `kinepoly variants` (kinepoly.homework.vary); only its shape here
            _table(self.report, ("vary",), data["vary"], "a [vary] table of ranges like angle = [30, 150]")
        if self.report.problems or spec_input is None or self.links is None:
            return None
        return Scene(
            title=title,
            units=units,
            ground=self.ground,
            links=tuple(self.links.values()),
            sliders=tuple(self.sliders),
            input=spec_input,
            guess=guess,
            find=find,
            draw=draw,
            source=self.report.source,
        )

    # -- title, units, ground

    def read_title(self, value: object) -> str:
        if value is None:
            return _default_title(self.report.source)
        if isinstance(value, str):
            return value
        self.report.add(("title",), f'expected a string like "Offset slider-crank", got {_show(value)}')
        return ""

    def read_units(self, value: object) -> Units:
        path = ("units",)
        if value is None:
            return Units()
        table = _table(self.report, path, value, '{ length = "mm", angle = "deg" }')
        if table is None:
            return Units()
        _check_keys(self.report, path, table, _UNITS_KEYS)
        length = self.read_unit_name(path + ("length",), table.get("length", "mm"), _LENGTH_UNITS, "mm")
        angle = self.read_unit_name(path + ("angle",), table.get("angle", "deg"), _ANGLE_UNITS, "deg")
        return Units(length=cast(Literal["mm", "cm", "m", "in"], length), angle=cast(Literal["deg", "rad"], angle))

    def read_unit_name(self, path: KeyPath, value: object, allowed: tuple[str, ...], default: str) -> str:
        if isinstance(value, str) and value in allowed:
            return value
        shown = _show(value)
        if isinstance(value, str):
            self.report.add(path, f"unknown unit {shown}; {_suggest(value, allowed)}")
        else:
            self.report.add(path, f"expected one of {_quoted(allowed)}, got {shown}")
        return default

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
                    f'no link "1" (the default ground); expected ground = "NAME" naming one of {_quoted(self.links)}',
                )
            return "1"
        name = _name(self.report, path, value, "a link name", "1")
        if name is not None and not self.has_link(name):
            self.report.add(path, _no_such("link", name, self.links or {}))
        return name

    # -- links and their points

    def read_links(self, value: object) -> dict[str, LinkSpec] | None:
        path = ("links",)
        if value is None:
            self.report.add(path, "missing; expected a [links] table like 1 = { points = { A0 = [0, 0] } }")
            return None
        table = _table(self.report, path, value, "a [links] table of link names")
        if table is None:
            return None
        if not table:
            self.report.add(path, "no links; expected at least one link")
        return {name: self.read_link(path + (name,), name, body) for name, body in table.items()}

    def read_link(self, path: KeyPath, name: str, body: object) -> LinkSpec:
        line = self.report.line(path)
        if not name:
            self.report.add(path, 'empty link name; expected a name like "2"')
        table = _table(self.report, path, body, "{ points = { NAME = [x, y], ... } }")
        if table is None:
            return LinkSpec(name, (), line)
        _check_keys(self.report, path, table, _LINK_KEYS)
        points = _require(self.report, path, table, "points", "points = { NAME = [x, y], ... }")
        if points is None:
            return LinkSpec(name, (), line)
        return LinkSpec(name, self.read_points(path + ("points",), points), line)

    def read_points(self, path: KeyPath, value: object) -> tuple[PointSpec, ...]:
        table = _table(self.report, path, value, "a table { NAME = [x, y], ... }")
        if table is None:
            return ()
        if not table:
            self.report.add(path, "no points; expected at least one named point")
        return tuple(self.read_point(path + (name,), name, spec) for name, spec in table.items())

    def read_point(self, path: KeyPath, name: str, value: object) -> PointSpec:
        line = self.report.line(path)
        if not name or "@" in name:
            self.report.add(path, 'bad point name; expected a name without "@" (kept for coincident points)')
        local = self.read_point_value(path, value)
        return PointSpec(name, _NOWHERE if local is None else local, line)

    def read_point_value(self, path: KeyPath, value: object) -> Vector | None:
        if isinstance(value, list) and len(value) == 2:
            return _pair(self.report, path, value, self.kinds.length)
        if not isinstance(value, dict):
            self.report.add(path, f"expected [x, y] or {{ polar = [r, angle] }}, got {_show(value)}")
            return None
        _check_keys(self.report, path, value, _POLAR_KEYS)
        polar = _require(self.report, path, value, "polar", "[x, y] or { polar = [r, angle] }")
        if polar is None:
            return None
        if not isinstance(polar, list) or len(polar) != 2:
            self.report.add(path + ("polar",), f"expected [r, angle], got {_show(polar)}")
            return None
        r = _quantity(self.report, path + ("polar", "r"), polar[0], self.kinds.length)
        angle = _quantity(self.report, path + ("polar", "angle"), polar[1], self.kinds.angle)
        return None if r is None or angle is None else _polar(r, angle)

    # -- joints implied by shared point names

    def check_joints(self) -> None:
        owners: dict[str, list[str]] = {}
        for link in (self.links or {}).values():
            for point in link.points:
                owners.setdefault(point.name, []).append(link.name)
        for point_name, names in owners.items():
            if len(names) > 2:
                self.report.add(
                    ("links", names[2], "points", point_name),
                    f'point "{point_name}" is in links {_quoted(names)}; a point name joins at most two links',
                )
        slider_points = {slider.point for slider in self.sliders}
        for link in (self.links or {}).values():
            joints = [p for p in link.points if len(owners[p.name]) > 1 or p.name in slider_points]
            self.check_distinct_joints(link.name, joints)

    def check_distinct_joints(self, link: str, joints: list[PointSpec]) -> None:
        for i, first in enumerate(joints):
            for second in joints[i + 1 :]:
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
            self.report.add(path, f"expected [[sliders]] tables, got {_show(value)}")
            return []
        sliders = [self.read_slider(path + (str(i),), item) for i, item in enumerate(value, start=1)]
        self.check_slider_names(sliders)
        return [slider for slider in sliders if slider is not None]

    def read_slider(self, path: KeyPath, table: Table) -> SliderSpec | None:
        _check_keys(self.report, path, table, _SLIDER_KEYS)
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
        value = _require(self.report, path[:-1], table, path[-1], f'{path[-1]} = "NAME", {role}')
        if value is None:
            return None
        name = _name(self.report, path, value, "a link name", "4")
        if name is not None and not self.has_link(name):
            self.report.add(path, _no_such("link", name, self.links or {}))
        return name

    def read_slider_point(self, path: KeyPath, table: Table, block: str | None) -> str | None:
        value = _require(self.report, path[:-1], table, "point", 'point = "NAME", the block\'s point on the line')
        if value is None:
            return None
        name = _name(self.report, path, value, "a point name", "B")
        links = self.links or {}
        if name is not None and block in links:
            known = links[block].point_names
            if name not in known:
                self.report.add(path, f'no point "{name}" in link "{block}" (the block); {_suggest(name, known)}')
        return name

    def read_slider_line(self, path: KeyPath, value: object) -> tuple[Vector, float]:
        if value is None:
            self.report.add(path, "missing; expected line = { through = [x, y], angle = a }")
            return _NOWHERE, math.nan
        table = _table(self.report, path, value, "{ through = [x, y], angle = a }")
        if table is None:
            return _NOWHERE, math.nan
        _check_keys(self.report, path, table, _LINE_KEYS)
        through_value = _require(self.report, path, table, "through", "through = [x, y], a point of the line")
        angle_value = _require(self.report, path, table, "angle", "angle = a, the line's direction")
        through = (
            None if through_value is None else _pair(self.report, path + ("through",), through_value, self.kinds.length)
        )
        angle = (
            None if angle_value is None else _quantity(self.report, path + ("angle",), angle_value, self.kinds.angle)
        )
        return (through or _NOWHERE), (math.nan if angle is None else angle)

    def read_slider_name(self, path: KeyPath, value: object, block: str | None, guide: str | None) -> str | None:
        if value is not None:
            return _name(self.report, path, value, "a slider name", "14")
        if block is None or guide is None:
            return None
        return _pair_name(guide, block)

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

    # -- input: [input] or [given]

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
        table = _table(self.report, path, value, 'an [input] table with link = "NAME" or slider = "NAME"')
        if table is None:
            return None
        _check_keys(self.report, path, table, _LINK_INPUT_KEYS + _SLIDER_INPUT_KEYS)
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
                self.report.add(path + (key,), f"not a key of {form}; expected {_quoted(right)}")

    def read_link_input(self, path: KeyPath, table: Table) -> LinkInput | None:
        link = _name(self.report, path + ("link",), table["link"], "a link name", "2")
        if link is not None and not self.has_link(link):
            self.report.add(path + ("link",), _no_such("link", link, self.links or {}))
        elif link is not None and link == self.ground:
            self.report.add(
                path + ("link",),
                f'link "{link}" is the ground; expected a moving link turning about its joint with the ground',
            )
        angle = self.required_quantity(path, table, "angle", self.kinds.angle)
        omega = self.required_quantity(path, table, "omega", self.kinds.omega)
        alpha = _quantity(self.report, path + ("alpha",), table.get("alpha", 0.0), self.kinds.alpha)
        if link is None or angle is None or omega is None or alpha is None:
            return None
        return LinkInput(link, angle, omega, alpha, self.report.line(path))

    def read_slider_input(self, path: KeyPath, table: Table) -> SliderInput | None:
        slider = _name(self.report, path + ("slider",), table["slider"], "a slider name", "14")
        if slider is not None and slider not in self.slider_names:
            self.report.add(path + ("slider",), _no_such("slider", slider, self.slider_names))
        s = self.required_quantity(path, table, "s", self.kinds.length)
        s_dot = self.required_quantity(path, table, "s_dot", self.kinds.speed)
        s_ddot = _quantity(self.report, path + ("s_ddot",), table.get("s_ddot", 0.0), self.kinds.accel)
        if slider is None or s is None or s_dot is None or s_ddot is None:
            return None
        return SliderInput(slider, s, s_dot, s_ddot, self.report.line(path))

    def required_quantity(self, path: KeyPath, table: Table, key: str, kind: _Kind) -> float | None:
        value = _require(self.report, path, table, key, f"{key} = {kind.expected()}")
        return None if value is None else _quantity(self.report, path + (key,), value, kind)

    def read_given(self, value: object) -> GivenInput | None:
        path = ("given",)
        table = _table(self.report, path, value, "[given.P] tables with velocity = [x, y]")
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
            self.report.add(path, _no_such("point", name, self.point_names))
        table = _table(self.report, path, value, "a table { velocity = [x, y], acceleration = [x, y] }")
        if table is None:
            return None
        _check_keys(self.report, path, table, _GIVEN_KEYS)
        velocity_value = _require(
            self.report, path, table, "velocity", "velocity = [x, y], " + self.kinds.speed.expected()
        )
        velocity = (
            None
            if velocity_value is None
            else _pair(self.report, path + ("velocity",), velocity_value, self.kinds.speed)
        )
        acceleration: Vector | None = None
        if "acceleration" in table:
            acceleration = _pair(self.report, path + ("acceleration",), table["acceleration"], self.kinds.accel)
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

    # -- guess, find, draw

    def read_guess(self, value: object) -> tuple[tuple[str, Vector], ...]:
        path = ("guess",)
        if value is None:
            return ()
        table = _table(self.report, path, value, "a [guess] table of NAME = [x, y]")
        if table is None:
            return ()
        guesses: list[tuple[str, Vector]] = []
        for name, spot in table.items():
            if self.links is not None and name not in self.point_names:
                self.report.add(path + (name,), _no_such("point", name, self.point_names))
            position = _pair(self.report, path + (name,), spot, self.kinds.length)
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
        table = _table(self.report, path, value, "a [find] table")
        if table is None:
            return FindSpec()
        _check_keys(self.report, path, table, _FIND_KEYS)
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
            self.report.add(path, f"expected a list of {what}s like {example}, got {_show(value)}")
            return []
        names: list[str] = []
        for index, item in enumerate(value, start=1):
            if isinstance(item, str) and item:
                names.append(item)
            else:
                self.report.add(path, f"item {index} is {_show(item)}; expected {what}s as strings, like {example}")
        return list(dict.fromkeys(names))

    def find_points(self, path: KeyPath, value: object) -> tuple[str, ...]:
        names = self.string_list(path, value, "point name", '["B", "A@4"]')
        return tuple(name for name in names if self.check_find_point(path, name))

    def check_find_point(self, path: KeyPath, name: str) -> bool:
        if self.links is None:
            return True
        point, at, link = name.partition("@")
        ok = True
        if point not in self.point_names:
            self.report.add(path, _no_such("point", point, self.point_names))
            ok = False
        if at and link not in self.links:
            self.report.add(path, f'in "{name}": {_no_such("link", link, self.links)}')
            ok = False
        return ok

    def find_links(self, path: KeyPath, value: object) -> tuple[str, ...]:
        names = self.string_list(path, value, "link name", '["3", "4"]')
        kept: list[str] = []
        for name in names:
            if not self.has_link(name):
                self.report.add(path, _no_such("link", name, self.links or {}))
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
                self.report.add(path, _no_such("slider", name, known))
        return tuple(name for name in names if name in known)

    def find_centers(self, path: KeyPath, value: object) -> tuple[str, ...] | Literal["all"]:
        if value == "all":
            return "all"
        if isinstance(value, str):
            self.report.add(path, f'expected "all" or a list of pairs like ["13", "2-14"], got {_show(value)}')
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
                self.report.add(path, f'in "{text}": {_no_such("link", name, self.links or {})}')
                return None
        if first == second:
            self.report.add(path, f'"{text}" names link "{first}" twice; expected two different links')
            return None
        return _pair_name(first, second)

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
        table = _table(self.report, path, value, "a [draw] table")
        if table is None:
            return DrawSpec()
        _check_keys(self.report, path, table, _DRAW_KEYS)
        return DrawSpec(
            kv=self.read_scale(path + ("kv",), table.get("kv")),
            ka=self.read_scale(path + ("ka",), table.get("ka")),
        )

    def read_scale(self, path: KeyPath, value: object) -> float | None:
        if value is None or value == "auto":
            return None
        expected = 'a positive number (drawing mm per unit) or "auto"'
        number = _finite(self.report, path, value, expected)
        if number is not None and number <= 0:
            self.report.add(path, f"{_show(value)} is not positive; expected {expected}")
            return None
        return number


def _same_place(first: Vector, second: Vector) -> bool:
    size = max(1.0, abs(first[0]), abs(first[1]), abs(second[0]), abs(second[1]))
    return math.hypot(first[0] - second[0], first[1] - second[1]) <= 1e-12 * size


# --------------------------------------------------------------------------------------------
# For kinepoly's other TOML files (answers files, [vary]): the same parsing, lines and problems

ProblemReport = _Report
"""Collects ``FILE:LINE: key.path: what; expected`` problems; ``raise_if_any`` raises a SceneError."""

show_value = _show
suggest = _suggest


def parse_located(text: str, source: str) -> tuple[Table, _Report]:
    """Parse ``text`` as a scene is parsed (same syntax errors); the data and a report placing each key path."""
    text = text.removeprefix("\ufeff")
    lines = _scan(text)
    return _parse_toml(text, source, lines), _Report(source, lines)


def read_quantity(
    report: _Report,
    path: KeyPath,
    value: object,
    kind: Literal["length", "speed", "accel", "angle", "omega", "alpha"],
    units: Units,
) -> float | None:
    """A number or unit string (``"4 cm"``, ``"300 rpm"``) as a scene's value of ``kind`` is read; None if wrong."""
    return _quantity(report, path, value, getattr(_kinds(units), kind))
