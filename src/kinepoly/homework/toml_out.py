"""Canonical TOML text of a scene and of an answer key, as ``kinepoly variants`` writes them.

Numbers are written as the shortest text that reads back to the same float (answers: six
significant digits), whole numbers without a point; keys bare where TOML allows it; every vector
as ``[x, y]``.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable, Sequence

from kinepoly.geom.tolerances import NOISE_REL
from kinepoly.homework.answers import AnswerKey, Direction, Value
from kinepoly.homework.higher_pairs import as_written
from kinepoly.present.clean import given_angle
from kinepoly.scene.spec import (
    CamSpec,
    GearSpec,
    LinkInput,
    PitchCircle,
    PitchLine,
    PointSpec,
    Scene,
    SliderInput,
    Units,
)

__all__ = ["answers_toml", "scene_toml", "toml_key", "toml_number"]

_BARE = re.compile(r"[A-Za-z0-9_-]+")


def toml_key(name: str) -> str:
    return name if _BARE.fullmatch(name) else json.dumps(name, ensure_ascii=False)


def toml_number(x: float, digits: int | None = None) -> str:
    """``x`` exactly (the shortest text that reads back to it) or to ``digits`` significant digits;
    whole numbers without a point; never -0."""
    if not math.isfinite(x):
        raise ValueError(f"{x!r} has no TOML form here; expected a finite number")
    x = float(format(x, f".{digits}g")) if digits is not None else float(x)
    if x == 0.0:
        return "0"
    if x.is_integer() and abs(x) < 1e15:
        return str(int(x))
    return repr(x)


def _pair(v: Sequence[float], digits: int | None = None) -> str:
    return f"[{toml_number(v[0], digits)}, {toml_number(v[1], digits)}]"


def _point(scene: Scene, point: PointSpec) -> str:
    """``[x, y]``, or ``{ polar = [r, angle] }`` where the scene wrote it so."""
    if point.polar is None:
        return _pair(point.local)
    return f"{{ polar = [{toml_number(point.polar[0])}, {_angle(scene, point.polar[1])}] }}"


def _strings(names: Iterable[str]) -> str:
    return "[" + ", ".join(json.dumps(name, ensure_ascii=False) for name in names) + "]"


def _angle(scene: Scene, radians: float) -> str:
    """An angle as the scene writes it (``present.clean.given_angle``: 210, not 210.00000000000003)."""
    return toml_number(given_angle(radians, scene.units.angle))


def _name_line(name: str, first: str, second: str) -> list[str]:
    """``name = ...`` when a slider's or pair's name is not the one the loader gives it (``pair_name``)."""
    default = first + second if len(first) == 1 and len(second) == 1 else f"{first}-{second}"
    return [] if name == default else [f"name = {json.dumps(name, ensure_ascii=False)}"]


def _profile_toml(cam: CamSpec) -> str:
    """``profile = ...``: the circle, or the points the spline runs through, four to a line."""
    if not cam.is_spline:
        return f"profile = {{ circle = {{ center = {_pair(cam.center)}, radius = {toml_number(cam.radius)} }} }}"
    pairs = [_pair(p) for p in cam.profile_points]
    rows = [", ".join(pairs[k:k + 4]) + "," for k in range(0, len(pairs), 4)]
    return "profile = { points = [\n" + "\n".join(f"  {row}" for row in rows) + "\n] }"


def _cam_toml(scene: Scene, cam: CamSpec) -> list[str]:
    out = ["", "[[cams]]", f"cam = {json.dumps(cam.cam)}", f"follower = {json.dumps(cam.follower)}",
           _profile_toml(cam)]
    if cam.kind == "roller" and cam.follower_profile:
        out.append(f"follower_profile = {{ circle = {{ center = {json.dumps(cam.point)}, "
                   f"radius = {toml_number(cam.roller_radius)} }} }}")
    elif cam.follower_points:
        pairs = [_pair(p) for p in cam.follower_points]
        rows = [", ".join(pairs[k:k + 4]) + "," for k in range(0, len(pairs), 4)]
        out.append("follower_profile = { points = [\n" + "\n".join(f"  {row}" for row in rows) + "\n] }")
    elif cam.kind == "roller":
        out.append(f"roller = {{ center = {json.dumps(cam.point)}, radius = {toml_number(cam.roller_radius)} }}")
    elif cam.kind == "knife":
        out.append(f"knife = {json.dumps(cam.point)}")
    else:
        assert cam.flat is not None
        out.append(f"flat = {{ through = {_pair(cam.flat[0])}, angle = {_angle(scene, cam.flat[1])} }}")
    if cam.inside:
        out.append('contact = "inside"')
    return out + _name_line(cam.name, cam.cam, cam.follower)


def _pitch(curve: PitchCircle | PitchLine, scene: Scene) -> str:
    if isinstance(curve, PitchCircle):
        return f"{{ center = {json.dumps(curve.center)}, radius = {toml_number(curve.radius)} }}"
    return f"{{ line = {{ through = {_pair(curve.through)}, angle = {_angle(scene, curve.angle_rad)} }} }}"


def _gear_toml(scene: Scene, gear: GearSpec) -> list[str]:
    phase = [toml_number(p) if isinstance(c, PitchLine) else _angle(scene, p)
             for c, p in zip(gear.pitch, gear.phase, strict=True)]
    out = ["", "[[gears]]", f"links = {_strings(gear.links)}",
           f"pitch = [{_pitch(gear.pitch[0], scene)}, {_pitch(gear.pitch[1], scene)}]"]
    if gear.internal:
        out.append("internal = true")
    return out + [f"phase = [{phase[0]}, {phase[1]}]"] + _name_line(gear.name, *gear.links)


def _higher_pairs(scene: Scene) -> list[str]:
    """The scene's ``[[gears]]`` and ``[[cams]]`` as the user writes them."""
    return [line for gear in scene.gears for line in _gear_toml(scene, gear)] + [
        line for cam in scene.cams for line in _cam_toml(scene, cam)]


def scene_toml(scene: Scene, header: str = "") -> str:
    """The scene as TOML (a link or slider input); ``header`` becomes comment lines at the top. Cams are
    written as ``[[cams]]``, never as their equivalent links."""
    scene = as_written(scene)
    out = [f"# {line}" for line in header.splitlines()]
    out += [f"title = {json.dumps(scene.title, ensure_ascii=False)}",
            f'units = {{ length = "{scene.units.length}", angle = "{scene.units.angle}" }}']
    if scene.ground is not None and scene.ground != "1":
        out.append(f"ground = {json.dumps(scene.ground)}")
    out += ["", "[links]"]
    for link in scene.links:
        points = ", ".join(f"{toml_key(p.name)} = {_point(scene, p)}" for p in link.points)
        out.append(f"{toml_key(link.name)} = {{ points = {{ {points} }} }}")
    for slider in scene.sliders:
        out += ["", "[[sliders]]", f"block = {json.dumps(slider.block)}", f"guide = {json.dumps(slider.guide)}",
                f"point = {json.dumps(slider.point)}",
                f"line = {{ through = {_pair(slider.through)}, angle = {_angle(scene, slider.angle_rad)} }}"]
        out += _name_line(slider.name, slider.guide, slider.block)
    out += _higher_pairs(scene)
    for inp in scene.inputs:
        out += ["", "[[input]]" if scene.more_inputs else "[input]"]
        if isinstance(inp, LinkInput):
            base = [f"relative_to = {json.dumps(inp.relative_to)}"] if inp.relative_to else []
            out += [f"link = {json.dumps(inp.link)}", *base, f"angle = {_angle(scene, inp.angle_rad)}",
                    f"omega = {toml_number(inp.omega)}", f"alpha = {toml_number(inp.alpha)}"]
        else:
            assert isinstance(inp, SliderInput), "a [given] scene is not written here"
            out += [f"slider = {json.dumps(inp.slider)}", f"s = {toml_number(inp.s)}",
                    f"s_dot = {toml_number(inp.s_dot)}", f"s_ddot = {toml_number(inp.s_ddot)}"]
    if scene.guess:
        out += ["", "[guess]"] + [f"{toml_key(name)} = {_pair(spot)}" for name, spot in scene.guess]
    find = scene.find
    if not find.is_default:
        out += ["", "[find]"]
        for key in ("velocity", "acceleration", "omega", "alpha", "sliders"):
            names = getattr(find, key)
            if names:
                out.append(f"{key} = {_strings(names)}")
        if find.instant_centers:
            centers = find.instant_centers
            out.append(f"instant_centers = {json.dumps(centers) if centers == 'all' else _strings(centers)}")
    if scene.draw.kv is not None or scene.draw.ka is not None:
        out += ["", "[draw]"]
        out += [f"{key} = {toml_number(value)}" for key, value in (("kv", scene.draw.kv), ("ka", scene.draw.ka))
                if value is not None]
    return "\n".join(out) + "\n"


def _answer(value: Value) -> str:
    if isinstance(value, Direction):
        return f"{{ direction = {_pair((value.x, value.y), 6)} }}"
    if isinstance(value, tuple):
        size = math.hypot(*value)
        tidy = [0.0 if abs(c) <= NOISE_REL * size else c for c in value]  # round-off beside a large component
        return _pair(tidy, 6)
    return toml_number(value, 6)


def answers_toml(answers: Iterable[tuple[AnswerKey, Value]], units: Units, header: str = "") -> str:
    """An answer key in the canonical forms, six significant digits (values as stored: theta in radians)."""
    out = [f"# {line}" for line in header.splitlines()]
    for key, value in answers:
        if key.kind == "theta" and units.angle == "deg" and isinstance(value, float):
            value = math.degrees(value)
        out.append(f"{toml_key(key.text)} = {_answer(value)}")
    return "\n".join(out) + "\n"
