"""The methods the bench compares, each able to give the scene's quantities at an array of inputs.

Every method runs in the solve's own frame (``kinepoly.check.frame``) and reports positions in
the user's frame. Methods that work one position at a time (the construction, the analytic
solve, finite differences, the construction with GEOS crossings) are timed per call; the closed
forms and the series run over a whole batch of inputs in one numpy call.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.bench.closed_forms import closed_form
from kinepoly.bench.motion import LinkMotion, Trig, evaluate
from kinepoly.check.analytic import solve_analytic
from kinepoly.check.compare import compare
from kinepoly.check.series import slider_crank_series
from kinepoly.engine.assembly import position_at_input
from kinepoly.engine.construct import construct_row
from kinepoly.engine.policy import Continuity
from kinepoly.engine.polygon import CrossLines
from kinepoly.engine.position import input_values, solve_positions
from kinepoly.engine.row import pose_row
from kinepoly.geom.arrays import Crossing, Points, PointsLike, Reals, cross_lines
from kinepoly.geom.tolerances import TINY_POSITIVE
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import LinkInput, SliderInput
from kinepoly.solution import Solution, wanted

__all__ = ["FD_STEPS", "Guess", "Method", "Setting", "construct_at", "construction_values", "geos_crossing",
           "methods_for", "with_input"]

FD_STEPS = (1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
"""Central-difference steps: radians for a turning input, times the mechanism's size for a slider."""

Values = dict[str, Any]
Guess = tuple[tuple[str, tuple[float, float]], ...]


class Setting(Struct, frozen=True):
    """What every method needs: the solved scene, its frame, the quantity keys and the input's size."""

    solution: Solution
    keys: tuple[str, ...]

    @property
    def mechanism(self) -> Mechanism:
        assert self.solution.inside is not None
        return self.solution.inside.mechanism

    @property
    def origin(self) -> tuple[float, float]:
        assert self.solution.inside is not None
        return self.solution.inside.frame.origin

    @property
    def pose(self) -> Pose:
        assert self.solution.inside is not None
        return self.solution.inside.pose

    @property
    def input_unit(self) -> float:
        """1 rad for a turning input; the mechanism's size for a slider (FD steps scale with it)."""
        if isinstance(self.mechanism.scene.input, SliderInput):
            points = [p.local for link in self.mechanism.scene.links for p in link.points]
            return max((math.hypot(a[0] - b[0], a[1] - b[1]) for a in points for b in points), default=1.0)
        return 1.0


class Method(Struct, frozen=True):
    """One method: ``compute`` does the timed work for an array of inputs; ``values`` reads position i.

    ``compute(ts, guesses)`` takes, for the methods that solve a position, one ``[guess]`` per input
    (a sweep follows its assembly that way); the batched closed forms keep the scene's assembly.
    """

    name: str
    family: str
    batched: bool
    compute: Callable[[np.ndarray, Sequence[Guess] | None], Any]
    values: Callable[[Any, int], Values]
    step: float | None = None


def with_input(mechanism: Mechanism, t: float, guess: Guess | None = None) -> Mechanism:
    """The mechanism with its input at ``t`` (theta in rad or s), and optionally another [guess]."""
    scene = mechanism.scene.at_input(float(t))
    return replace(mechanism, scene=scene if guess is None else replace(scene, guess=guess))


def _moved(spec: LinkInput | SliderInput, tau: float) -> LinkInput | SliderInput:
    """An input ``tau`` seconds on, moving at its rate and acceleration."""
    if isinstance(spec, LinkInput):
        return replace(spec, angle_rad=spec.angle_rad + spec.omega * tau + 0.5 * spec.alpha * tau * tau)
    return replace(spec, s=spec.s + spec.s_dot * tau + 0.5 * spec.s_ddot * tau * tau)


def at_time(mechanism: Mechanism, tau: float) -> Mechanism:
    """The mechanism ``tau`` seconds on, every input moving at its own rate and acceleration."""
    scene = mechanism.scene
    moved = [_moved(spec, tau) for spec in scene.inputs if isinstance(spec, LinkInput | SliderInput)]
    return replace(mechanism, scene=replace(scene, input=moved[0], more_inputs=tuple(moved[1:])))


def _label_and_what(key: str) -> tuple[str, str, str]:
    family, rest = key.split(".", 1)
    name, what = rest.rsplit(".", 1)
    return family, name, what


def construction_values(draft: Solution, keys: tuple[str, ...], origin: tuple[float, float]) -> Values:
    """The construction's value of every key (``draft`` in the solve's frame)."""
    out: Values = {}
    for key in keys:
        family, name, what = _label_and_what(key)
        if family == "points":
            if what == "position":
                at = draft.position(name)
                out[key] = (at[0] + origin[0], at[1] + origin[1])
            else:
                polygon = draft.velocity if what == "velocity" else draft.acceleration
                assert polygon is not None
                out[key] = polygon.tips[name]
        elif family == "links":
            if what == "angle":
                out[key] = draft.angle(name)
            elif what == "omega":
                assert draft.velocity is not None
                out[key] = draft.velocity.omega[name]
            else:
                assert draft.acceleration is not None
                out[key] = draft.acceleration.alpha[name]
        else:
            values = draft.slider(name)
            out[key] = {"s": values.s, "s_dot": values.s_dot, "s_ddot": values.s_ddot,
                        "coriolis": values.coriolis}[what]
    return out


def construct_at(setting: Setting, mechanism: Mechanism, crossing: CrossLines = cross_lines) -> Solution:
    """Position and polygons at ``mechanism``'s input: the construction without the check."""
    sol = setting.solution
    built = construct_row(mechanism, sol.plan, wanted(sol.asked), unit=mechanism.scene.units.length, crossing=crossing)
    return Solution(mechanism.scene, mechanism, sol.asked, sol.plan, built.pose, built.velocity, built.acceleration,
                    compare([], 1.0), (), sliders=built.sliders)


def geos_crossing(through1: PointsLike, direction1: PointsLike, through2: PointsLike, direction2: PointsLike,
                  length1: float | None = None, length2: float | None = None) -> Crossing:
    """Two families of direction lines crossed by GEOS (shapely): each drawn as a segment long enough
    to meet the other, all rows at once.

    The segments reach 2 |p2 - p1| / |sin eps| + |p2 - p1| either side of their points, past the
    crossing; GEOS intersects them in doubles. Where they do not meet (parallel lines) the sine is 0.
    """
    import shapely

    t1, d1, t2, d2 = np.broadcast_arrays(*(np.atleast_1d(np.asarray(x, np.complex128))
                                           for x in (through1, direction1, through2, direction2)))
    n1, n2 = np.abs(d1), np.abs(d2)
    w = (d1.conjugate() * d2).imag
    sin_angle = w / (n1 * n2)
    gap = np.abs(t2 - t1)
    reach = 2.0 * gap / np.abs(sin_angle) + gap + TINY_POSITIVE

    def segments(through: Points, direction: Points, size: Reals) -> Any:
        u = direction / size
        ends = np.stack([through - reach * u, through + reach * u], axis=1)
        return shapely.linestrings(np.stack([ends.real, ends.imag], axis=2))

    found = shapely.intersection(segments(t1, d1, n1), segments(t2, d2, n2))
    is_point = shapely.get_type_id(found) == 0
    point = np.where(is_point, shapely.get_x(found) + 1j * shapely.get_y(found), 0.0)
    sin_angle = np.where(is_point, sin_angle, 0.0)
    along = ((point - t1) * d1.conjugate()).real / (n1 * n1)
    return Crossing(np.asarray(point), np.asarray(sin_angle), np.asarray(along), np.asarray(t2 - t1), d1, w)


def _per_position(setting: Setting, run: Callable[[Mechanism], Values]
                  ) -> Callable[[np.ndarray, Sequence[Guess] | None], Any]:
    def compute(ts: np.ndarray, guesses: Sequence[Guess] | None = None) -> list[Values]:
        return [run(with_input(setting.mechanism, float(t), guesses[n] if guesses else None))
                for n, t in enumerate(ts)]
    return compute


def _list_values(raw: Any, i: int) -> Values:
    return dict(raw[i])


def _construction(setting: Setting, name: str, family: str, crossing: CrossLines) -> Method:
    def run(mechanism: Mechanism) -> Values:
        return construction_values(construct_at(setting, mechanism, crossing), setting.keys, setting.origin)
    return Method(name, family, False, _per_position(setting, run), _list_values)


def _analytic(setting: Setting) -> Method:
    sol = setting.solution

    def run(mechanism: Mechanism) -> Values:
        start = pose_row(position_at_input(mechanism, sol.plan))
        analytic = solve_analytic(mechanism, dict(start.links), with_acceleration=sol.asked.needs_acceleration)
        motion = {k: LinkMotion(p.x, p.y, p.theta, *analytic.linear_velocity[k], analytic.omega[k],
                                *(analytic.linear_acceleration or {}).get(k, (0.0, 0.0)),
                                (analytic.alpha or {}).get(k, 0.0)) for k, p in analytic.poses.items()}
        return evaluate(mechanism, motion, list(setting.keys), Trig(math.cos, math.sin), setting.origin)
    return Method("analytic Jacobian solve", "analytic", False, _per_position(setting, run), _list_values)


def _wrap(d: float) -> float:
    return math.remainder(d, 2.0 * math.pi)


def _three_poses(mechanism: Mechanism, sol: Solution, h: float) -> list[Pose]:
    """The positions ``h`` seconds before, at and after ``mechanism``'s input.

    Each alone, every input moving at its own rate; but a scene with gears and one input as one batch
    of three rows, its assembly and the gears' phase followed from the middle one: alone, each would
    roll the shorter way to its own input, a turn apart where the input gear's rolled angle passes
    half a turn."""
    if not mechanism.scene.gears or len(mechanism.drives) != 1:
        return [pose_row(position_at_input(at_time(mechanism, d), sol.plan)) for d in (-h, 0.0, h)]
    middle = pose_row(position_at_input(mechanism, sol.plan))
    inputs = np.array([float(input_values(at_time(mechanism, d))[0]) for d in (-h, 0.0, h)])
    with np.errstate(all="ignore"):
        rows = solve_positions(mechanism, sol.plan, inputs, Continuity(1, dict(middle.links), False))
    return [pose_row(rows, k) for k in range(3)]


def _finite_differences(setting: Setting, step: float) -> Method:
    """Positions a time step before and after, every input moving at its own rate: central differences.

    The time step is the input step ``step`` (in the input's unit) over the first input's rate."""
    sol = setting.solution
    inp = setting.mechanism.scene.input
    rate = inp.omega if isinstance(inp, LinkInput) else inp.s_dot  # type: ignore[union-attr]
    h = step * setting.input_unit / (abs(rate) if rate else 1.0)

    def run(mechanism: Mechanism) -> Values:
        poses = _three_poses(mechanism, sol, h)
        motion = {}
        for link, mid in poses[1].links.items():
            lo, hi = poses[0].links[link], poses[2].links[link]
            v = [(hi.x - lo.x) / (2 * h), (hi.y - lo.y) / (2 * h), _wrap(hi.theta - lo.theta) / (2 * h)]
            a = [(hi.x - 2 * mid.x + lo.x) / (h * h), (hi.y - 2 * mid.y + lo.y) / (h * h),
                 (_wrap(hi.theta - mid.theta) - _wrap(mid.theta - lo.theta)) / (h * h)]
            motion[link] = LinkMotion(mid.x, mid.y, mid.theta, v[0], v[1], v[2], a[0], a[1], a[2])
        return evaluate(mechanism, motion, list(setting.keys), Trig(math.cos, math.sin), setting.origin)
    return Method(f"finite differences h={step:g}", "finite differences", False, _per_position(setting, run),
                  _list_values, step)


def _batched_values(raw: Any, i: int) -> Values:
    def pick(v: Any) -> Any:
        return tuple(float(x[i]) for x in v) if isinstance(v, tuple) else float(v[i])
    return {key: pick(v) for key, v in raw.items()}


def methods_for(setting: Setting, steps: tuple[float, ...] = FD_STEPS) -> list[Method]:
    """Every method that applies to the scene: the construction first."""
    out = [_construction(setting, "construction (polygons, homogeneous crossings)", "construction", cross_lines),
           _analytic(setting)]
    form = closed_form(setting.mechanism, setting.pose)
    if form is not None:
        keys, mech, origin = list(setting.keys), setting.mechanism, setting.origin

        def closed(ts: np.ndarray, guesses: Sequence[Guess] | None = None) -> Values:
            return evaluate(mech, form.motion(ts), keys, Trig(np.cos, np.sin), origin)
        out.append(Method(form.name, "closed form", True, closed, _batched_values))
    series = slider_crank_series(setting.mechanism, setting.pose, list(setting.keys))
    if series is not None:
        expand = series.values

        def approximate(ts: np.ndarray, guesses: Sequence[Guess] | None = None) -> Values:
            return expand(ts)
        out.append(Method(series.name, "series", True, approximate, _batched_values))
    out.append(_construction(setting, "construction with GEOS crossings (shapely)", "GEOS", geos_crossing))
    out += [_finite_differences(setting, h) for h in steps]
    return out
