"""The right answers: the scene solved, through the public API, for every key asked or answered.

A key the scene's own ``[find]`` does not ask for is answered by solving a copy of the scene whose
``[find]`` asks for it. The copy asks for every point and link too when it can (the diagnosis
compares a wrong answer with the values of the other points and links); when that wider copy
cannot be solved (a group the question never needed does not assemble) only what is asked or
answered is solved. The values are read off the :class:`~kinepoly.solution.Solution` itself.

A student's answers with a construction mistake (:func:`student_solution`) are the engine's
acceleration polygon constructed again with that mistake switched in (``engine.acceleration.Rules``)
on the reference's positions and velocity polygon: velocities are not affected by these mistakes.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Literal

from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.acceleration import Rules
from kinepoly.engine.construct import construct_row
from kinepoly.errors import KinepolyError
from kinepoly.geom.vec import Vec
from kinepoly.homework.answers import AnswerKey, Direction, Value
from kinepoly.present.clean import noise_of
from kinepoly.present.scales import A4, polygon_scales
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.spec import FindSpec, GivenInput, Scene
from kinepoly.solution import Solution, solve, wanted

__all__ = ["FLOOR_FRACTION", "Reference", "Values", "asked_keys", "fixed_angles", "prepare", "solve_for",
           "student_solution", "value_in", "values_of"]

FLOOR_FRACTION = 0.01
"""A value is judged against at least this fraction of the largest value of its kind in the mechanism."""

_RATES = ("omega", "alpha", "theta")
ScaleKind = Literal["omega", "alpha", "theta", "velocity", "acceleration", "length"]
Values = Mapping[AnswerKey, Value]
"""Answers by key, in internal units (angles in radians), in the order ``kinepoly solve`` reports them."""


class Reference(Struct, frozen=True):
    """The scene solved for the answers.

    ``solution`` is the scene solved for every key (and, when it could be, every point and link);
    ``values`` its answers (see :func:`values_of`) and those of the links that never turn; ``asked``
    the keys the scene's own ``[find]`` asks for (none when the scene has no ``[find]``); ``kv`` and
    ``ka`` the polygon scales ``kinepoly solve`` draws the scene at (None where there is no such
    polygon); ``scales`` the largest size of each kind.
    """

    scene: Scene
    solution: Solution
    values: Values
    asked: tuple[AnswerKey, ...]
    kv: float | None
    ka: float | None
    scales: Mapping[ScaleKind, float]
    has_centers: bool  # False: this kinepoly does not compute instant centers yet

    @property
    def warnings(self) -> list[str]:
        """kinepoly's own cross-check failing on the reference: its answers are then in doubt."""
        return [n.message for n in self.solution.notices if n.code == "check-failed"]

    def expected(self, key: AnswerKey) -> Value | None:
        return value_in(self.values, key)

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
# Values off the solution


def _pair(v: Vec) -> tuple[float, float]:
    return (float(v[0]) + 0.0, float(v[1]) + 0.0)  # + 0.0 turns -0.0 into 0.0


def values_of(solution: Solution) -> dict[AnswerKey, Value]:
    """Every value ``solution`` reports for its scene's [find], keyed, in the order ``kinepoly solve`` shows them:
    links (theta, omega, alpha), points (velocity, acceleration), sliders (s, s_dot, s_ddot), instant centers.

    By the number rule (``present.clean``): a value within its error estimate of 0 is 0, of a short decimal that
    decimal, and a driven value is the one given; the answer keys and the checking show them so."""
    asked, find = solution.asked, solution.scene.find
    velocity, acceleration = solution.velocity, solution.acceleration
    noise = noise_of(solution)
    out: dict[AnswerKey, Value] = {}
    for link in dict.fromkeys((*asked.omega, *asked.alpha)):
        driven = solution.driven_link(link)
        out[AnswerKey("theta", link)] = (solution.angle(link) if driven is not None
                                         else noise.value(solution.angle(link), "angle"))
        if link in asked.omega and velocity is not None:
            out[AnswerKey("omega", link)] = (driven.omega if driven
                                             else noise.value(float(velocity.omega[link]), "omega"))
        if link in asked.alpha and acceleration is not None:
            out[AnswerKey("alpha", link)] = (driven.alpha if driven
                                             else noise.value(float(acceleration.alpha[link]), "alpha"))
    for label in dict.fromkeys((*find.velocity, *find.acceleration)):
        if label in find.velocity and velocity is not None:
            out[AnswerKey("velocity", label)] = _pair(noise.pair(velocity.tips[label], "velocity"))
        if label in find.acceleration and acceleration is not None:
            out[AnswerKey("acceleration", label)] = _pair(noise.pair(acceleration.tips[label], "acceleration"))
    for name in asked.sliders:
        slider, given = solution.slider(name), solution.driven_slider(name) is not None
        out[AnswerKey("s", name)] = float(slider.s) if given else noise.value(float(slider.s), "position")
        if slider.s_dot is not None:
            out[AnswerKey("s_dot", name)] = (float(slider.s_dot) if given
                                             else noise.value(float(slider.s_dot), "velocity"))
        if slider.s_ddot is not None and slider.coriolis is not None:
            out[AnswerKey("s_ddot", name)] = (float(slider.s_ddot) if given
                                              else noise.value(float(slider.s_ddot), "acceleration"))
    centers = solution.centers.centers if solution.centers is not None else {}
    for key, name in solution.centers.asked if solution.centers is not None else ():
        center = centers[name]
        if center.position is not None:
            out[AnswerKey("center", key)] = _pair(noise.pair(center.position, "position"))
        elif center.direction is not None:
            out[AnswerKey("center", key)] = Direction(*_pair(noise.pair(center.direction, "direction")))
    return out


def _other_order(pair: str) -> str:
    if "-" in pair:
        first, _, second = pair.partition("-")
        return f"{second}-{first}"
    return pair[::-1]


def value_in(values: Values, key: AnswerKey) -> Value | None:
    """The value of ``key`` in ``values``, None if absent; an instant center under either order of its links."""
    found = values.get(key)
    if found is None and key.kind == "center":
        found = values.get(AnswerKey("center", _other_order(key.target)))
    return found


def asked_keys(values: Values) -> tuple[AnswerKey, ...]:
    """The keys a solved scene reports (its angles aside), in its order: what its [find] asks."""
    return tuple(key for key in values if key.kind != "theta")


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
        points += [LinkPoint(s.point, s.guide).text for s in scene.sliders]
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


def _solved_for(scene: Scene, keys: tuple[AnswerKey, ...], *, everything: bool) -> Solution:
    return solve(replace(scene, find=_find_for(scene, keys, everything=everything)))


def _with_fixed_links(scene: Scene, values: Values) -> dict[AnswerKey, Value]:
    """``values`` and, for each link that never turns, its angle and omega = alpha = 0."""
    out = dict(values)
    for link, angle in fixed_angles(scene).items():
        out.setdefault(AnswerKey("theta", link), math.remainder(angle, 2.0 * math.pi))
        out.setdefault(AnswerKey("omega", link), 0.0)
        out.setdefault(AnswerKey("alpha", link), 0.0)
    return out


def solve_for(scene: Scene, keys: Iterable[AnswerKey], *, everything: bool = True) -> dict[AnswerKey, Value]:
    """The values of ``scene`` solved with a [find] that asks for ``keys`` (and every point and link)."""
    return _with_fixed_links(scene, values_of(_solved_for(scene, tuple(keys), everything=everything)))


def student_solution(solution: Solution, rules: Rules) -> dict[AnswerKey, Value]:
    """The answers of a student who lays the acceleration polygon's known terms as ``rules`` say, at the
    positions and velocities of ``solution``: what :func:`values_of` gives, and the links that never turn."""
    inside = solution.inside
    if solution.acceleration is not None and inside is not None:  # the right construction went through at this row
        built = construct_row(inside.mechanism, solution.plan, wanted(solution.asked), origin=inside.frame.origin,
                              unit=solution.scene.units.length, strict=False, rules=rules)
        solution = replace(solution, acceleration=built.acceleration, sliders=built.sliders)
    return _with_fixed_links(solution.scene, values_of(solution))


def _scales(solution: Solution, values: Values) -> dict[ScaleKind, float]:
    find = solution.scene.find
    positions = [solution.position(label) for label in dict.fromkeys((*find.velocity, *find.acceleration))]
    size = max((math.dist(a, b) for a in positions for b in positions), default=0.0)

    def sizes(kind: str) -> list[float]:
        return [math.hypot(*v) if isinstance(v, tuple) else abs(v)
                for key, v in values.items() if key.kind == kind and not isinstance(v, Direction)]

    inp = solution.scene.input
    inputs = [abs(getattr(inp, "omega", 0.0)), abs(getattr(inp, "alpha", 0.0))]
    omega = max(sizes("omega") + inputs[:1])
    alpha = max(sizes("alpha") + inputs[1:] + [omega * omega])
    speed = max(sizes("velocity") + sizes("s_dot") + [size * omega])
    accel = max(sizes("acceleration") + sizes("s_ddot") + [size * alpha])
    return {"omega": omega, "alpha": alpha, "theta": math.pi, "velocity": speed, "acceleration": accel,
            "length": size}


def prepare(scene: Scene, keys: Iterable[AnswerKey] = (), paper: tuple[float, float] = A4) -> Reference:
    """Solve ``scene`` for what its [find] asks and for ``keys``; raises KinepolyError as ``solve`` does.

    kv and ka are those of the scene's drawing and handout on ``paper`` (``present.scales``).
    """
    keys = tuple(keys)
    original = solve(scene)
    try:
        solution = _solved_for(scene, keys, everything=True)
    except KinepolyError:
        solution = _solved_for(scene, keys, everything=False)
    values = _with_fixed_links(scene, values_of(solution))
    kv_ka = polygon_scales(original, paper)
    return Reference(
        scene=scene,
        solution=solution,
        values=values,
        asked=() if scene.find.is_default else asked_keys(values_of(original)),
        kv=kv_ka.get("velocity"),
        ka=kv_ka.get("acceleration"),
        scales=_scales(solution, values),
        has_centers=solution.centers is not None,
    )
