"""The right answers: the scene solved, through the public API, for every key asked or answered.

A key the scene's own ``[find]`` does not ask for is answered by solving a copy of the scene whose
``[find]`` asks for it. The copy asks for every point and link too when it can (the diagnosis
compares a wrong answer with the values of the other points and links); when that wider copy
cannot be solved (a group the question never needed does not assemble) only what is asked or
answered is solved.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any, Literal

from kinepoly.errors import KinepolyError
from kinepoly.homework.answers import AnswerKey, Direction, Value
from kinepoly.report import to_json
from kinepoly.scene.spec import FindSpec, GivenInput, Scene, Units
from kinepoly.solution import solve

__all__ = ["FLOOR_FRACTION", "Reference", "asked_keys", "fixed_angles", "prepare", "solve_for", "value_of"]

FLOOR_FRACTION = 0.01
"""A value is judged against at least this fraction of the largest value of its kind in the mechanism."""

_RATES = ("omega", "alpha", "theta")
ScaleKind = Literal["omega", "alpha", "theta", "velocity", "acceleration", "length"]


@dataclass(frozen=True)
class Reference:
    """The scene solved for the answers.

    ``data`` is ``kinepoly.to_json`` of the scene solved for every key (and, when it could be,
    every point and link); ``asked`` the keys the scene's own ``[find]`` asks for (none when the
    scene has no ``[find]``); ``kv`` and ``ka`` the polygon scales ``kinepoly solve`` draws the
    scene at (None where there is no such polygon); ``scales`` the largest size of each kind.
    """

    scene: Scene
    data: Mapping[str, Any]
    asked: tuple[AnswerKey, ...]
    kv: float | None
    ka: float | None
    scales: Mapping[ScaleKind, float]
    has_centers: bool  # False: this kinepoly does not compute instant centers yet

    @property
    def warnings(self) -> list[str]:
        """kinepoly's own cross-check failing on the reference: its answers are then in doubt."""
        return [w["message"] for w in self.data.get("warnings", []) if w.get("code") == "check-failed"]

    def expected(self, key: AnswerKey) -> Value | None:
        return value_of(self.data, key, self.scene.units)

    def floor(self, key: AnswerKey) -> float:
        """The least size a value of this key is judged against (see ``FLOOR_FRACTION``); for an
        instant center, the mechanism's size (see kinepoly.homework.compare)."""
        if key.kind == "center":
            return self.scales["length"]
        return FLOOR_FRACTION * self.scales[_scale_kind(key)]


def _scale_kind(key: AnswerKey) -> ScaleKind:
    kind = key.kind
    if kind in ("omega", "alpha", "theta", "velocity", "acceleration"):
        return kind
    return {"s": "length", "center": "length", "s_dot": "velocity", "s_ddot": "acceleration"}[kind]  # type: ignore[return-value]


# --------------------------------------------------------------------------------------------
# Values out of the contract's JSON


def _other_order(pair: str) -> str:
    if "-" in pair:
        first, _, second = pair.partition("-")
        return f"{second}-{first}"
    return pair[::-1]


def value_of(data: Mapping[str, Any], key: AnswerKey, units: Units) -> Value | None:
    """The value of ``key`` in a ``kinepoly solve --json`` object (internal units), None if absent."""
    kind, target = key.kind, key.target
    if kind in ("omega", "alpha", "theta"):
        link = data.get("links", {}).get(target, {})
        if kind == "theta":
            angle = link.get("angle")
            return None if angle is None else (math.radians(angle) if units.angle == "deg" else float(angle))
        rate = link.get(kind)
        return None if rate is None else float(rate)
    if kind in ("velocity", "acceleration"):
        vector = data.get("points", {}).get(target, {}).get(kind)
        return None if vector is None else (float(vector[0]), float(vector[1]))
    if kind == "center":
        centers = data.get("instant_centers", {})
        entry = centers.get(target) or centers.get(_other_order(target))
        if entry is None:
            return None
        if "position" in entry:
            return (float(entry["position"][0]), float(entry["position"][1]))
        return Direction(float(entry["direction"][0]), float(entry["direction"][1]))
    number = data.get("sliders", {}).get(target, {}).get(kind)
    return None if number is None else float(number)


def asked_keys(data: Mapping[str, Any]) -> tuple[AnswerKey, ...]:
    """The keys a solved scene's JSON reports, in its order: what its [find] asks."""
    keys: list[AnswerKey] = []
    for link, entry in data.get("links", {}).items():
        keys += [AnswerKey(kind, link) for kind in ("omega", "alpha") if kind in entry]
    for label, entry in data.get("points", {}).items():
        keys += [AnswerKey(kind, label) for kind in ("velocity", "acceleration") if kind in entry]
    for name, entry in data.get("sliders", {}).items():
        keys += [AnswerKey(kind, name) for kind in ("s", "s_dot", "s_ddot") if kind in entry]
    keys += [AnswerKey("center", pair) for pair in data.get("instant_centers", {})]
    return tuple(keys)


# --------------------------------------------------------------------------------------------
# Solving for the keys


def _with_accelerations(scene: Scene) -> bool:
    inp = scene.input
    return not isinstance(inp, GivenInput) or all(p.acceleration is not None for p in inp.points)


def fixed_angles(scene: Scene) -> dict[str, float]:
    """The links that can never turn (the frame, blocks sliding on it, ...) and their angles in radians.

    ``kinepoly solve`` reports no omega for them (asking raises), so they are answered here:
    omega = alpha = 0, and a block's angle is its guide's plus the slide's.
    """
    if scene.ground is None:
        return {}
    fixed = {scene.ground: 0.0}
    grown = True
    while grown:
        grown = False
        for s in scene.sliders:
            if s.guide in fixed and s.block not in fixed:
                fixed[s.block], grown = fixed[s.guide] + s.angle_rad, True
            elif s.block in fixed and s.guide not in fixed:
                fixed[s.guide], grown = fixed[s.block] - s.angle_rad, True
    del fixed[scene.ground]
    return fixed


def _find_for(scene: Scene, keys: Iterable[AnswerKey], *, everything: bool) -> FindSpec:
    base = scene.find
    fixed = fixed_angles(scene)
    of = {kind: [k.target for k in keys if k.kind == kind and not (kind in _RATES and k.target in fixed)]
          for kind in ("omega", "alpha", "theta", "velocity", "acceleration", "s", "s_dot", "s_ddot", "center")}
    velocity = [*base.velocity, *of["velocity"], *of["acceleration"]]
    acceleration = [*base.acceleration, *of["acceleration"]]
    omega = [*base.omega, *of["omega"], *of["theta"]]
    alpha = [*base.alpha, *of["alpha"]]
    sliders = [*base.sliders, *of["s"], *of["s_dot"], *of["s_ddot"]]
    wants_acceleration = bool(acceleration or alpha or of["s_ddot"])
    if everything:
        points = [p.name for link in scene.links for p in link.points]
        points += [f"{s.point}@{s.guide}" for s in scene.sliders]
        moving = [link.name for link in scene.links if link.name not in (scene.ground, *fixed)]
        velocity += points
        omega += moving
        sliders += [s.name for s in scene.sliders]
        if wants_acceleration and _with_accelerations(scene):
            acceleration += velocity
            alpha += moving
    centers: tuple[str, ...] | Literal["all"] = "all" if base.instant_centers == "all" else tuple(
        dict.fromkeys([*base.instant_centers, *of["center"]]))
    return FindSpec(velocity=tuple(dict.fromkeys(velocity)), acceleration=tuple(dict.fromkeys(acceleration)),
                    omega=tuple(dict.fromkeys(omega)), alpha=tuple(dict.fromkeys(alpha)),
                    sliders=tuple(dict.fromkeys(sliders)), instant_centers=centers)


def solve_for(scene: Scene, keys: Iterable[AnswerKey], *, everything: bool = True) -> dict[str, Any]:
    """``to_json`` of ``scene`` solved with a [find] that asks for ``keys`` (and every point and link)."""
    keys = tuple(keys)
    data = to_json(solve(dataclasses.replace(scene, find=_find_for(scene, keys, everything=everything))))
    links = data.setdefault("links", {})
    for link, angle in fixed_angles(scene).items():
        angle = math.remainder(angle, 2.0 * math.pi)
        shown = math.degrees(angle) if scene.units.angle == "deg" else angle
        links.setdefault(link, {"angle": shown, "omega": 0.0, "alpha": 0.0})
    return data


def _scales(data: Mapping[str, Any], scene: Scene) -> dict[ScaleKind, float]:
    links = data.get("links", {}).values()
    points = data.get("points", {}).values()
    sliders = data.get("sliders", {}).values()
    positions = [p["position"] for p in points]
    size = max((math.dist(a, b) for a in positions for b in positions), default=0.0)
    inp = scene.input
    inputs = [abs(getattr(inp, "omega", 0.0)), abs(getattr(inp, "alpha", 0.0))]
    omega = max([abs(x.get("omega", 0.0)) for x in links] + inputs[:1])
    alpha = max([abs(x.get("alpha", 0.0)) for x in links] + inputs[1:] + [omega * omega])
    speed = max([math.hypot(*p["velocity"]) for p in points if "velocity" in p]
                + [abs(s.get("s_dot", 0.0)) for s in sliders] + [size * omega])
    accel = max([math.hypot(*p["acceleration"]) for p in points if "acceleration" in p]
                + [abs(s.get("s_ddot", 0.0)) for s in sliders] + [size * alpha])
    return {"omega": omega, "alpha": alpha, "theta": math.pi, "velocity": speed, "acceleration": accel,
            "length": size}


def prepare(scene: Scene, keys: Iterable[AnswerKey] = ()) -> Reference:
    """Solve ``scene`` for what its [find] asks and for ``keys``; raises KinepolyError as ``solve`` does."""
    keys = tuple(keys)
    original = to_json(solve(scene))
    try:
        data = solve_for(scene, keys, everything=True)
    except KinepolyError:
        data = solve_for(scene, keys, everything=False)
    polygons = original.get("polygons", {})
    return Reference(
        scene=scene,
        data=data,
        asked=() if scene.find.is_default else asked_keys(original),
        kv=polygons.get("velocity", {}).get("scale"),
        ka=polygons.get("acceleration", {}).get("scale"),
        scales=_scales(data, scene),
        has_centers="instant_centers" in data,
    )
