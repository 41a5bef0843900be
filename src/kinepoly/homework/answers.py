"""The answers file: a student's answers to a scene, read with the scene loader's error quality.

Canonical keys and forms (more is accepted where it helps students)::

    omega_3 = -1.70                # rad/s, ccw positive; or "1.70 cw", "1.70 rad/s ccw", "16.3 rpm cw"
    alpha_4 = 42.6                 # rad/s^2, the same forms
    theta_3 = 168.2                # a link's angle in the scene's angle unit, or "2.94 rad"
    v_B = [-388.4, 0]              # components in the scene's length unit per second
    v_C = { magnitude = 376.8, angle = 150.7 }      # polar: the angle in degrees from +x
    "v_A@4" = [-44.4, -76.8]       # a coincident point (TOML needs the quotes for "@")
    a_C = [-3367, -2316]
    s_14 = 137.4                   # and s_dot_14, s_ddot_14
    I_13 = [249.6, 931.4]          # an instant center; { direction = [0, 1] } when it is at infinity
    student = "Ana Pop"            # optional: names the row of a class report
    [tolerance]                    # optional
    relative = 0.02
    angle_deg = 2

Every problem is reported at once as ``FILE:LINE: key: what is wrong; what is expected``
(a :class:`~kinepoly.errors.SceneError`, exit status 2). Values are stored in the scene's
length unit, angles in radians, omega in rad/s and alpha in rad/s^2.
"""

from __future__ import annotations

import difflib
import math
import os
import re
from collections.abc import Mapping
from functools import partial
from typing import Literal, NoReturn

from msgspec import Struct, field

from kinepoly.errors import SceneError
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.loader import ProblemReport, parse_located, read_quantity, show_value, suggest
from kinepoly.scene.problems import unknown_key
from kinepoly.scene.source import read_text
from kinepoly.scene.spec import GivenInput, Scene, Units
from kinepoly.scene.values import read_finite

__all__ = [
    "DEFAULT_TOLERANCE",
    "Answer",
    "AnswerKey",
    "Answers",
    "Direction",
    "Kind",
    "Tolerance",
    "Value",
    "key_names",
    "load_answers",
    "loads_answers",
    "parse_key",
]

Kind = Literal["omega", "alpha", "theta", "velocity", "acceleration", "s", "s_dot", "s_ddot", "center"]
KeyPath = tuple[str, ...]

# longest prefix first: "s_ddot_14" is not "s_" + "ddot_14"
_PREFIXES: tuple[tuple[str, Kind], ...] = (
    ("s_ddot_", "s_ddot"), ("s_dot_", "s_dot"), ("omega_", "omega"), ("alpha_", "alpha"), ("theta_", "theta"),
    ("v_", "velocity"), ("a_", "acceleration"), ("s_", "s"), ("I_", "center"),
)
_PREFIX_OF: dict[Kind, str] = {kind: prefix for prefix, kind in _PREFIXES}
_META_KEYS = ("student", "tolerance")
_TOLERANCE_KEYS = ("relative", "angle_deg")
_POLAR_KEYS = ("magnitude", "angle")
_CENTER_KEYS = ("direction",)
_SENSES = r"(?:cw|ccw|clockwise|counterclockwise|counter-clockwise|anticlockwise|anti-clockwise)"
_SENSE = re.compile(
    r"\s*(?P<number>[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?)\s*"
    rf"(?:(?P<unit>(?!{_SENSES}\b)\S+)\s*)?(?P<sense>{_SENSES})?\s*",
    re.ASCII | re.IGNORECASE,
)
_CLOCKWISE = ("cw", "clockwise")
_SENSE_WORDS = ("cw", "ccw")


class Direction(Struct, frozen=True):
    """A direction without a point: an instant center at infinity. Its sense does not matter."""

    x: float
    y: float


Value = float | tuple[float, float] | Direction


class AnswerKey(Struct, frozen=True):
    """What an answer is about: ``kind`` of ``target`` (a link, point label, slider or link pair)."""

    kind: Kind
    target: str

    @property
    def text(self) -> str:
        """The canonical key: ``omega_3``, ``v_A@4``, ``s_dot_14``, ``I_13``."""
        return _PREFIX_OF[self.kind] + self.target

    @property
    def is_vector(self) -> bool:
        return self.kind in ("velocity", "acceleration", "center")

    @property
    def question(self) -> tuple[str, str | frozenset[str]]:
        """What is asked: the same for ``I_13`` and ``I_31``."""
        if self.kind == "center":
            return (self.kind, frozenset(self.target.split("-") if "-" in self.target else self.target))
        return (self.kind, self.target)


class Answer(Struct, frozen=True):
    key: AnswerKey
    value: Value
    line: int = 0


class Tolerance(Struct, frozen=True):
    """How close an answer must be. ``relative``: of the expected size (see kinepoly.homework.compare);
    ``angle_deg``: of a vector's direction or a link's angle."""

    relative: float = 0.02
    angle_deg: float = 2.0


DEFAULT_TOLERANCE = Tolerance()


class Answers(Struct, frozen=True):
    """One answers file: its answers in file order, the tolerance, and the student's name if given."""

    answers: tuple[Answer, ...]
    tolerance: Tolerance = field(default_factory=Tolerance)
    student: str | None = None
    source: str = "<answers>"


# --------------------------------------------------------------------------------------------
# Keys


def _moving_links(scene: Scene) -> list[str]:
    return [link.name for link in scene.links if link.name != scene.ground]


def _points(scene: Scene) -> list[str]:
    return list(dict.fromkeys(p.name for link in scene.links for p in link.points))


def _split_pair(text: str, links: list[str]) -> tuple[str, str] | None:
    if "-" not in text:
        return (text[0], text[1]) if len(text) == 2 else None
    splits = [(text[:i], text[i + 1 :]) for i, char in enumerate(text) if char == "-"]
    known = [(a, b) for a, b in splits if a in links and b in links]
    return known[0] if len(known) == 1 else None


def _pair_name(first: str, second: str) -> str:
    return first + second if len(first) == 1 and len(second) == 1 else f"{first}-{second}"


def key_names(scene: Scene) -> list[str]:
    """Every canonical key this scene can answer (instant centers: each pair in one order)."""
    moving = _moving_links(scene)
    links = [link.name for link in scene.links]
    names = [f"{prefix}{link}" for prefix in ("omega_", "alpha_", "theta_") for link in moving]
    names += [f"{prefix}{point}" for prefix in ("v_", "a_") for point in _points(scene)]
    names += [f"{prefix}{LinkPoint(s.point, s.guide).text}" for prefix in ("v_", "a_") for s in scene.sliders]
    names += [f"{prefix}{s.name}" for prefix in ("s_", "s_dot_", "s_ddot_") for s in scene.sliders]
    names += [f"I_{_pair_name(a, b)}" for i, a in enumerate(links) for b in links[i + 1 :]]
    return names


def parse_key(text: str, scene: Scene) -> AnswerKey | str:
    """The key ``text`` names, or what is wrong with it (a message without the key path)."""
    for prefix, kind in _PREFIXES:
        if text.startswith(prefix):
            target = text[len(prefix) :]
            problem = _target_problem(kind, target, scene)
            if problem is None:
                pair = _split_pair(target, [link.name for link in scene.links]) if kind == "center" else None
                return AnswerKey(kind, _pair_name(*pair) if pair else target)
            return problem
    return f"unknown answer key; {suggest(text, key_names(scene))}"


def _no_such(kind: str, name: str, known: list[str]) -> str:
    return f'no {kind} "{name}"; {suggest(name, known)}'


def _target_problem(kind: Kind, target: str, scene: Scene) -> str | None:
    links = [link.name for link in scene.links]
    if kind in ("omega", "alpha", "theta"):
        if target == scene.ground:
            return f'link "{target}" is the frame, it does not move; expected a moving link'
        return None if target in links else _no_such("link", target, _moving_links(scene))
    if kind in ("velocity", "acceleration"):
        named = LinkPoint.parse(target)
        point, link = named.point, named.link
        if point not in _points(scene):
            return _no_such("point", point, _points(scene))
        if link is not None and link not in links:
            return f'in "{target}": {_no_such("link", link, links)}'
        return None
    if kind in ("s", "s_dot", "s_ddot"):
        names = [s.name for s in scene.sliders]
        return None if target in names else _no_such("slider", target, names)
    pair = _split_pair(target, links)
    if pair is None:
        return (f'"{target}" is not a pair of links; expected two link names like "13" or "1-3" '
                '("-" when a name is longer than one character)')
    for name in pair:
        if name not in links:
            return f'in "{target}": {_no_such("link", name, links)}'
    if pair[0] == pair[1]:
        return f'"{target}" names link "{pair[0]}" twice; expected two different links'
    return None


# --------------------------------------------------------------------------------------------
# Values


def _rate(report: ProblemReport, path: KeyPath, value: object, kind: Literal["omega", "alpha"],
          units: Units) -> float | None:
    """omega or alpha: a number (ccw positive) or "1.70 cw", "1.70 rad/s ccw", "-1.70 rad/s"."""
    unit = "rad/s" if kind == "omega" else "rad/s^2"
    expected = f'a number in {unit} (ccw positive) or a string like "1.70 cw" or "1.70 {unit} ccw"'
    if not isinstance(value, str):
        return read_finite(report, path, value, expected)
    match = _SENSE.fullmatch(value)
    if match is None:
        report.add(path, f"expected {expected}, got {show_value(value)}")
        return None
    number, written_unit, sense = match.group("number", "unit", "sense")
    if sense and number.startswith("-"):
        report.add(path, f"{show_value(value)} has both a sign and a sense; expected a magnitude with cw or ccw "
                         f'("{number[1:]} {sense}") or a signed number without one')
        return None
    if written_unit and not sense and difflib.get_close_matches(written_unit.lower(), _SENSE_WORDS, n=1):
        report.add(path, f'"{written_unit}" in {show_value(value)} is not a sense; '
                         f'{suggest(written_unit, _SENSE_WORDS)}'
                         " (cw: clockwise, ccw: counter-clockwise)")
        return None
    size = read_quantity(report, path, f"{number} {written_unit}" if written_unit else float(number), kind, units)
    if size is None:
        return None
    return -size if sense and sense.lower() in _CLOCKWISE else size


def _vector(report: ProblemReport, path: KeyPath, value: object, kind: Literal["speed", "accel"],
            units: Units) -> tuple[float, float] | None:
    if isinstance(value, list) and len(value) == 2:
        x = read_quantity(report, path + ("x",), value[0], kind, units)
        y = read_quantity(report, path + ("y",), value[1], kind, units)
        return None if x is None or y is None else (x, y)
    if not isinstance(value, dict):
        report.add(path, f"expected [x, y] or {{ magnitude = m, angle = degrees from +x }}, got {show_value(value)}")
        return None
    if not _known_keys(report, path, value, _POLAR_KEYS):
        return None
    if "magnitude" not in value or "angle" not in value:
        missing = "magnitude" if "magnitude" not in value else "angle"
        report.add(path + (missing,), "missing; expected { magnitude = m, angle = degrees from +x }")
        return None
    size = read_quantity(report, path + ("magnitude",), value["magnitude"], kind, units)
    angle = read_quantity(report, path + ("angle",), value["angle"], "angle", Units(units.length, "deg"))
    if size is None or angle is None:
        return None
    if size < 0:
        report.add(path + ("magnitude",), f"{show_value(value['magnitude'])} is negative; expected a magnitude "
                                          "of at least 0, the direction given by angle")
        return None
    return (size * math.cos(angle), size * math.sin(angle))


def _center(report: ProblemReport, path: KeyPath, value: object, units: Units) -> Value | None:
    if isinstance(value, list) and len(value) == 2:
        x = read_quantity(report, path + ("x",), value[0], "length", units)
        y = read_quantity(report, path + ("y",), value[1], "length", units)
        return None if x is None or y is None else (x, y)
    if not isinstance(value, dict) or "direction" not in value:
        report.add(path, f"expected [x, y] or {{ direction = [x, y] }} (a center at infinity), got {show_value(value)}")
        return None
    if not _known_keys(report, path, value, _CENTER_KEYS):
        return None
    direction = value["direction"]
    if not isinstance(direction, list) or len(direction) != 2:
        report.add(path + ("direction",), f"expected [x, y], got {show_value(direction)}")
        return None
    x = read_finite(report, path + ("direction", "x"), direction[0], "a number")
    y = read_finite(report, path + ("direction", "y"), direction[1], "a number")
    if x is None or y is None:
        return None
    length = math.hypot(x, y)
    if length == 0.0:
        report.add(path + ("direction",), "is [0, 0]; expected a direction, a vector that is not zero")
        return None
    return Direction(x / length, y / length)


def _known_keys(report: ProblemReport, path: KeyPath, table: Mapping[str, object], allowed: tuple[str, ...]) -> bool:
    unknown = [key for key in table if key not in allowed]
    for key in unknown:
        report.add(path + (key,), partial(unknown_key, key, allowed))
    return not unknown


def _value(report: ProblemReport, path: KeyPath, key: AnswerKey, value: object, units: Units) -> Value | None:
    kind = key.kind
    if kind in ("omega", "alpha"):
        return _rate(report, path, value, "omega" if kind == "omega" else "alpha", units)
    if kind == "theta":
        return read_quantity(report, path, value, "angle", units)
    if kind == "velocity":
        return _vector(report, path, value, "speed", units)
    if kind == "acceleration":
        return _vector(report, path, value, "accel", units)
    if kind == "center":
        return _center(report, path, value, units)
    quantities: dict[str, Literal["length", "speed", "accel"]] = {"s": "length", "s_dot": "speed", "s_ddot": "accel"}
    return read_quantity(report, path, value, quantities[kind], units)


def _tolerance(report: ProblemReport, value: object) -> Tolerance:
    path = ("tolerance",)
    if not isinstance(value, dict):
        report.add(path, f"expected a [tolerance] table with relative = 0.02, angle_deg = 2, got {show_value(value)}")
        return DEFAULT_TOLERANCE
    _known_keys(report, path, value, _TOLERANCE_KEYS)
    relative = _bounded(report, path + ("relative",), value.get("relative", DEFAULT_TOLERANCE.relative),
                        1.0, "a fraction above 0 and below 1, like 0.02 for 2 %")
    angle = _bounded(report, path + ("angle_deg",), value.get("angle_deg", DEFAULT_TOLERANCE.angle_deg),
                     90.0, "degrees above 0 and below 90, like 2")
    return Tolerance(relative if relative is not None else DEFAULT_TOLERANCE.relative,
                     angle if angle is not None else DEFAULT_TOLERANCE.angle_deg)


def _bounded(report: ProblemReport, path: KeyPath, value: object, upper: float, expected: str) -> float | None:
    number = read_finite(report, path, value, expected)
    if number is not None and not 0.0 < number < upper:
        report.add(path, f"{show_value(value)} is out of range; expected {expected}")
        return None
    return number


# --------------------------------------------------------------------------------------------
# The file


def _fail(source: str, line: int | None, message: str) -> NoReturn:
    where = source if line is None else f"{source}:{line}"
    raise SceneError([f"{where}: (file): {message}"])


def load_answers(path: str | os.PathLike[str], scene: Scene) -> Answers:
    """Read and check the answers file at ``path`` against ``scene``; problems name the path as given."""
    source = os.fspath(path)
    return loads_answers(read_text(source, "an answers"), scene, source)


def loads_answers(text: str, scene: Scene, source: str = "<answers>") -> Answers:
    """Check the answers written in ``text`` against ``scene``; raises SceneError listing every problem."""
    if not text.strip():
        _fail(source, None, "the file is empty; expected answers like omega_3 = -1.70 or v_B = [-388.4, 0]")
    data, report = parse_located(text, source)
    answers: list[Answer] = []
    seen: dict[tuple[str, str | frozenset[str]], str] = {}
    for name, value in data.items():
        if name in _META_KEYS:
            continue
        key = parse_key(name, scene)
        if isinstance(key, str):
            report.add((name,), key)
            continue
        if key.question in seen:
            report.add((name,), f"answers the same question as {seen[key.question]}; expected each answer once")
            continue
        seen[key.question] = name
        given = _value(report, (name,), key, value, scene.units)
        if given is not None:
            answers.append(Answer(key, given, report.line((name,))))
    _check_accelerations_given(report, scene, answers)
    tolerance = _tolerance(report, data["tolerance"]) if "tolerance" in data else DEFAULT_TOLERANCE
    student = _student(report, data.get("student"))
    if not seen and not report.problems:
        report.add((), "no answers; expected keys like omega_3 = -1.70, v_B = [-388.4, 0] or a_C = [-3367, -2316]")
    report.raise_if_any()
    return Answers(tuple(answers), tolerance, student, source)


def _check_accelerations_given(report: ProblemReport, scene: Scene, answers: list[Answer]) -> None:
    """A [given] scene without accelerations cannot answer acceleration questions."""
    inp = scene.input
    if not isinstance(inp, GivenInput) or all(p.acceleration is not None for p in inp.points):
        return
    for answer in answers:
        if answer.key.kind in ("acceleration", "alpha"):
            report.add((answer.key.text,), "the scene's [given] points have no accelerations, so this cannot be "
                                           "checked; expected velocity answers only, or accelerations in [given]")


def _student(report: ProblemReport, value: object) -> str | None:
    if value is None:
        return None
    if isinstance(value, str) and value.strip():
        return value.strip()
    report.add(("student",), f'expected the student\'s name as a string like "Ana Pop", got {show_value(value)}')
    return None
