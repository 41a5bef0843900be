"""A solve's values replaced by the loop method's, and the ``loops`` list of ``solve --json``."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from msgspec.structs import replace

from kinepoly.engine.assembly import position_at_input
from kinepoly.engine.plan import make_plan
from kinepoly.engine.row import SliderValues, pose_row
from kinepoly.loops.contours import LoopMethodError, uncovered
from kinepoly.loops.rates import LoopSolution, solve_loops
from kinepoly.model.pose import Pose
from kinepoly.scene.link_point import LinkPoint
from kinepoly.solution import Solution

__all__ = ["full_pose", "loop_method_solution", "loops_json"]

Vec = tuple[float, float]


def full_pose(solution: Solution) -> Pose:
    """Every link placed by the engine's position solve (the solve itself places only what is asked)."""
    why = uncovered(solution.mechanism)
    if why is not None:
        raise LoopMethodError(f"{solution.scene.source}: --method loops: the loop-closure method does not cover "
                              f"this scene: {why}; solve it without --method (the polygon method)")
    inside = solution.inside
    assert inside is not None
    positions = position_at_input(inside.mechanism, make_plan(inside.mechanism), inside.frame.origin)
    return inside.frame.pose_to_user(pose_row(positions))


def _vec(z: complex) -> Vec:
    return (float(z.real) + 0.0, float(z.imag) + 0.0)


def _resolve(solution: Solution, label: str) -> tuple[str, complex] | None:
    """The link a polygon's tip label is a point of, and where it is; None for a construction's own mark."""
    named = LinkPoint.parse(label)
    point, on = named.point, named.link or ""
    mech = solution.mechanism
    if on:
        link = on
    elif mech.links_of_point(point):
        link = mech.owner(point)
    else:
        return None
    x, y = solution.position(label)
    return link, complex(x, y)


def _tips(solution: Solution, labels: Iterable[str], motion: Callable[[str, complex], complex]) -> dict[str, Vec]:
    """Each tip of ``labels`` that is a point of a link, moved as the loops move that link's point there."""
    return {label: _vec(motion(*found)) for label in labels if (found := _resolve(solution, label)) is not None}


def loop_method_solution(solution: Solution) -> tuple[Solution, LoopSolution]:
    """The solve with every omega, alpha, tip and slider rate taken from the loop equations."""
    asked = solution.asked
    loops = solve_loops(solution.mechanism, full_pose(solution), with_acceleration=asked.needs_acceleration)
    velocity, acceleration = solution.velocity, solution.acceleration
    if velocity is not None:
        velocity = replace(velocity, tips=_tips(solution, velocity.tips, loops.velocity),
                           omega={k: loops.omega[k] for k in velocity.omega})
    if acceleration is not None and loops.alpha is not None:
        acceleration = replace(acceleration, tips=_tips(solution, acceleration.tips, loops.acceleration),
                               alpha={k: loops.alpha[k] for k in acceleration.alpha})
    sliders = {}
    for name, old in solution.sliders.items():
        sliders[name] = SliderValues(loops.s[name], loops.s_dot[name] if old.s_dot is not None else None,
                                     loops.s_ddot[name] if old.s_ddot is not None and loops.s_ddot else None,
                                     _vec(loops.coriolis(name)) if old.coriolis is not None else None)
    return replace(solution, velocity=velocity, acceleration=acceleration, sliders=sliders), loops


def loops_json(loops: LoopSolution) -> list[dict[str, Any]]:
    """Each loop's members (the links it goes round), its equation and its unknowns, as ``solve --json`` gives them."""
    from kinepoly.loops.text import loop_equation, loop_unknowns

    return [{"members": list(loop.members), "closing_joint": loop.closing, "equation": loop_equation(loops, loop),
             "unknowns": loop_unknowns(loops, loop)} for loop in loops.loops]
