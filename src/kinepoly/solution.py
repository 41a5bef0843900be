"""Scene in, solution out: plan backwards from [find], solve the position, construct, check.

``solve`` is the whole pipeline for one scene; every stage's output is a frozen value.
"""

from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

import numpy as np
from msgspec import Struct, field

from kinepoly.check import (
    AccuracyReport,
    LocalFrame,
    assess,
    estimate_errors,
    localize,
    near_singular_notice,
    singular_position_error,
    transmission_notices,
)
from kinepoly.check.analytic import AnalyticSolution, solve_analytic
from kinepoly.check.compare import CheckReport, Quantity, compare
from kinepoly.engine.construct import Wanted, construct_row
from kinepoly.engine.contacts import Contact, contact_links
from kinepoly.engine.groups import PositionPlan
from kinepoly.engine.plan import make_plan
from kinepoly.engine.position import describe_input
from kinepoly.engine.row import AccelerationPolygon, SliderValues, VelocityPolygon
from kinepoly.engine.steps import Step
from kinepoly.engine.transmission import transmission_angles
from kinepoly.errors import SingularityError
from kinepoly.geom.hull import diameter
from kinepoly.geom.tolerances import LOUD_ERROR
from kinepoly.geom.vec import Vec
from kinepoly.model.mechanism import Mechanism, build_mechanism
from kinepoly.model.pose import Pose
from kinepoly.notice import Notice
from kinepoly.scene.link_point import LinkPoint
from kinepoly.scene.spec import LinkInput, Scene, SliderInput

if TYPE_CHECKING:  # Aronhold-Kennedy's modules are loaded only for a scene that asks for instant centers
    from kinepoly.engine.center_values import InstantCenters

__all__ = ["Asked", "Inside", "SliderValues", "Solution", "needed_links", "solve", "wanted", "what_is_asked"]


class Asked(Struct, frozen=True):
    """What the scene asks, as (link, point) pairs and link names, planned backwards."""

    velocity: tuple[tuple[str, str], ...]
    acceleration: tuple[tuple[str, str], ...]
    omega: tuple[str, ...]
    alpha: tuple[str, ...]
    sliders: tuple[str, ...]

    @property
    def needs_velocity(self) -> bool:
        return bool(self.velocity or self.omega or self.sliders or self.needs_acceleration)

    @property
    def needs_acceleration(self) -> bool:
        return bool(self.acceleration or self.alpha)


class Inside(Struct, frozen=True):
    """The solve's own frames (``kinepoly.check.frame``): the localized mechanism and its pose.

    Differences of positions (slider values, the cross-check) are taken here, where every
    coordinate is of the mechanism's size; ``Solution.pose`` is the same pose in the user's frames.
    """

    frame: LocalFrame
    mechanism: Mechanism
    pose: Pose


class Solution(Struct, frozen=True):
    """Everything ``kinepoly solve`` reports for one scene."""

    scene: Scene
    mechanism: Mechanism
    asked: Asked
    plan: PositionPlan
    pose: Pose
    velocity: VelocityPolygon | None
    acceleration: AccelerationPolygon | None
    check: CheckReport
    notices: tuple[Notice, ...]
    timing: dict[str, float] = field(default_factory=dict)
    inside: Inside | None = None
    accuracy: AccuracyReport | None = None
    centers: InstantCenters | None = None
    sliders: dict[str, SliderValues] = field(default_factory=dict)
    contacts: dict[str, Contact] = field(default_factory=dict)
    """Each higher pair's contact (``engine.contacts``), in the user's frame."""

    @property
    def steps(self) -> tuple[Step, ...]:
        v = self.velocity.steps if self.velocity else ()
        a = self.acceleration.steps if self.acceleration else ()
        return v + a

    def position(self, label: str) -> Vec:
        point = LinkPoint.parse(label).point
        if point in self.pose.marks:
            return self.pose.marks[point]
        owner = next(link for link in self.mechanism.links_of_point(point) if link in self.pose.links)
        return self.pose.links[owner].world(self.mechanism.local(owner, point))

    def angle(self, link: str) -> float:
        """theta_1k in radians, in (-pi, pi]; a link driven on the frame at an angle in that range: the angle given."""
        given = self.driven_link(link)
        if given is not None and -math.pi < given.angle_rad <= math.pi:
            return given.angle_rad
        theta = math.remainder(self.pose.links[link].theta, 2.0 * math.pi)
        return math.pi if theta == -math.pi else theta

    def driven_link(self, link: str) -> LinkInput | None:
        """The input that turns ``link`` on the frame (its theta, omega and alpha given), None if none does."""
        for drive in self.mechanism.drives:
            spec = drive.spec
            if isinstance(spec, LinkInput) and spec.relative_to is None and spec.link == link and drive.on_frame:
                return spec
        return None

    def slider(self, name: str) -> SliderValues:
        """An asked slider's s, s_dot, s_ddot and Coriolis term, as the engine constructed them; a driven
        slider's s, s_dot and s_ddot as the scene gives them (given, not recomputed: 50, not 49.99999999999999)."""
        values, spec = self.sliders[name], self.driven_slider(name)
        if spec is None:
            return values
        return SliderValues(spec.s, None if values.s_dot is None else spec.s_dot,
                            None if values.s_ddot is None else spec.s_ddot, values.coriolis)

    def driven_slider(self, name: str) -> SliderInput | None:
        """The input that drives slider ``name`` (its s, s_dot and s_ddot given), None if none does."""
        for drive in self.mechanism.drives:
            if isinstance(drive.spec, SliderInput) and drive.spec.slider == name:
                return drive.spec
        return None

    def __repr__(self) -> str:
        """One line: the scene, what was solved, the cross-check (the default repr printed every array)."""
        inputs = "; ".join(drive.name for drive in self.mechanism.drives) or "given motion"
        return (f"<Solution {self.scene.title!r}: {len(self.mechanism.scene.links)} links, input {inputs}, "
                f"{len(self.steps)} steps, max relative error {self.check.max_rel_error:.2g}>")


def _pair(mechanism: Mechanism, label: str) -> tuple[str, str]:
    named = LinkPoint.parse(label)
    return (named.link, named.point) if named.link else (mechanism.owner(named.point), named.point)


def what_is_asked(mechanism: Mechanism) -> Asked:
    find = mechanism.scene.find
    return Asked(
        velocity=tuple(_pair(mechanism, p) for p in find.velocity),
        acceleration=tuple(_pair(mechanism, p) for p in find.acceleration),
        omega=tuple(find.omega),
        alpha=tuple(find.alpha),
        sliders=tuple(find.sliders),
    )


def wanted(asked: Asked) -> Wanted:
    """What the engine is to construct for ``asked``."""
    return Wanted(asked.velocity, asked.acceleration, asked.needs_velocity, asked.needs_acceleration, asked.sliders)


def needed_links(mechanism: Mechanism, asked: Asked) -> set[str]:
    """The links whose poses the asked quantities need: asked links, owners of asked points, sliders' links."""
    links: set[str] = set(asked.omega) | set(asked.alpha)
    for link, point in (*asked.velocity, *asked.acceleration):
        links.add(link)
        links.add(mechanism.owner(point))
    for name in asked.sliders:
        spec = mechanism.slider(name)
        links.update((spec.block, spec.guide))
    return links | contact_links(mechanism)


def solve(scene: Scene, *, load_s: float = 0.0) -> Solution:
    """Solve one scene: position, velocity and acceleration polygons as asked, cross-checked."""
    t0 = time.perf_counter()
    mechanism = build_mechanism(scene)
    frame = localize(scene)  # every coordinate of the solve near the mechanism: translation costs nothing
    inner = mechanism if frame.is_identity else build_mechanism(frame.scene)
    asked = what_is_asked(inner)
    center_plan = None
    if scene.find.instant_centers:  # Aronhold-Kennedy's modules are loaded only for a scene that asks for centers
        from kinepoly.engine.centers import plan_instant_centers

        center_plan = plan_instant_centers(inner)
    plan = make_plan(inner, needed_links(inner, asked) | set(center_plan.links_needed if center_plan else ()))
    built = construct_row(inner, plan, wanted(asked), origin=frame.origin, unit=scene.units.length, record=True)
    positions, pose, velocity, acceleration = built.positions, built.pose, built.velocity, built.acceleration
    t1 = time.perf_counter()
    _finite(inner, velocity, acceleration)
    centers = None
    if center_plan:
        from kinepoly.engine.centers import find_instant_centers

        centers = find_instant_centers(inner, pose, center_plan, frame.origin)
    t2 = time.perf_counter()
    where = describe_input(inner)
    transmissions = transmission_angles(positions, plan)
    draft = Solution(frame.scene, inner, asked, plan, pose, velocity, acceleration, compare([], 1.0), (),
                     centers=centers, sliders=built.sliders)
    try:
        with np.errstate(all="ignore"):  # rates beyond double precision are reported by name just below
            analytic = solve_analytic(inner, dict(pose.links), with_acceleration=asked.needs_acceleration)
    except SingularityError as error:
        raise singular_position_error(where, transmissions, draft.steps, str(error)) from error
    rates = [*analytic.omega.values(), *(analytic.alpha.values() if analytic.alpha else ())]
    rates += [c.omega for c in centers.omegas] if centers else []
    if not all(math.isfinite(x) for x in rates):
        raise SingularityError(f"the velocities at {where} overflowed: they are beyond the range of double "
                               "precision (reduce the input's rates)")
    check = compare(_quantities(draft, analytic), analytic.condition_number, _natural_scales(draft))
    kennedy = {"instant_center": max((s.relative_error for s in centers.steps), default=0.0)} if centers else None
    estimate = estimate_errors(analytic.condition_number, draft.steps, check.relative, kennedy)
    accuracy = assess(check, estimate, frame)
    t3 = time.perf_counter()
    notices = list(positions.notices)
    notices += centers.notices if centers else ()
    notices += transmission_notices(transmissions, where)
    near = near_singular_notice(estimate, where)
    notices += [near] if near is not None else []
    if check.max_rel_error > LOUD_ERROR:
        worst = max(check.relative, key=lambda k: check.relative[k])
        notices.append(Notice("check-failed", f"the construction and the analytic solution disagree: "
                              f"{worst} differs by {check.relative[worst]:.3g} (relative), above {LOUD_ERROR:g} "
                              f"(the error estimate of {worst} is {estimate.of_kind(worst):.2g})"))
    timing = {"load_s": load_s, "position_s": t1 - t0, "construction_s": t2 - t1, "check_s": t3 - t2,
              "total_s": load_s + (t3 - t0)}
    contacts = {name: found.row(0, complex(*frame.origin)) for name, found in built.contacts.items()}
    return Solution(scene, mechanism, asked, plan, frame.pose_to_user(pose), velocity, acceleration, check,
                    tuple(notices), timing, Inside(frame, inner, pose), accuracy, centers, built.sliders, contacts)


def _finite(mechanism: Mechanism, velocity: VelocityPolygon | None, acceleration: AccelerationPolygon | None) -> None:
    """Raise where a polygon's values overflowed (rates so large that their squares are not numbers)."""
    for polygon, values in (("velocity", velocity), ("acceleration", acceleration)):
        if values is None:
            continue
        numbers = [x for tip in values.tips.values() for x in tip]
        numbers += list(values.omega.values() if isinstance(values, VelocityPolygon) else values.alpha.values())
        if not all(math.isfinite(x) for x in numbers):
            raise SingularityError(f"the {polygon} polygon at {describe_input(mechanism)} overflowed: its values are "
                                   "beyond the range of double precision (reduce the input's rates)")


def _label(mechanism: Mechanism, link: str, point: str) -> str:
    return point if mechanism.has_point(link, point) else LinkPoint(point, link).text


def _quantities(sol: Solution, analytic: AnalyticSolution) -> list[Quantity]:
    mech, asked = sol.mechanism, sol.asked
    out: list[Quantity] = []
    labels = {_label(mech, lk, p) for lk, p in (*asked.velocity, *asked.acceleration)}
    for label in sorted(labels):
        out.append(Quantity(f"points.{label}.position", "position", sol.position(label),
                            analytic.point_position(mech, label)))
    if sol.velocity:
        for link, point in asked.velocity:
            label = _label(mech, link, point)
            out.append(Quantity(f"points.{label}.velocity", "velocity", sol.velocity.tips[label],
                                analytic.point_velocity(mech, label)))
        for link in asked.omega:
            out.append(Quantity(f"links.{link}.omega", "omega", sol.velocity.omega[link], analytic.omega[link]))
    if sol.acceleration and analytic.alpha is not None:
        for link, point in asked.acceleration:
            label = _label(mech, link, point)
            out.append(Quantity(f"points.{label}.acceleration", "acceleration", sol.acceleration.tips[label],
                                analytic.point_acceleration(mech, label)))
        for link in asked.alpha:
            out.append(Quantity(f"links.{link}.alpha", "alpha", sol.acceleration.alpha[link], analytic.alpha[link]))
    for link in dict.fromkeys((*asked.omega, *asked.alpha)):
        out.append(Quantity(f"links.{link}.angle", "angle", sol.angle(link), analytic.poses[link].theta))
    for name in asked.sliders:
        got, ref = sol.sliders[name], analytic.slider_values(mech, name)  # as constructed, driven ones too
        out.append(Quantity(f"sliders.{name}.s", "position", got.s, ref["s"]))
        if got.s_dot is not None:
            out.append(Quantity(f"sliders.{name}.s_dot", "velocity", got.s_dot, ref["s_dot"]))
        if got.s_ddot is not None and got.coriolis is not None:
            out.append(Quantity(f"sliders.{name}.s_ddot", "acceleration", got.s_ddot, ref["s_ddot"]))
            out.append(Quantity(f"sliders.{name}.coriolis", "acceleration", got.coriolis, ref["coriolis"]))
    return out + _center_quantities(sol, analytic)


def _center_quantities(sol: Solution, analytic: AnalyticSolution) -> list[Quantity]:
    """omega_1j from the instant centers against the polygon's (where it has it) and the analytic one."""
    out: list[Quantity] = []
    for found in sol.centers.omegas if sol.centers else ():
        key = f"instant_centers.{found.symbol}"
        if sol.velocity is not None and found.link in sol.velocity.omega:
            out.append(Quantity(f"{key}.polygon", "instant_center", found.omega, sol.velocity.omega[found.link]))
        out.append(Quantity(f"{key}.analytic", "instant_center", found.omega, analytic.omega[found.link]))
    return out


def _natural_scales(sol: Solution) -> dict[str, float]:
    """Each kind's size in the whole solution: every tip and rate, and what the other kinds imply."""
    points = [sol.pose.links[k].world(p.local) for k in sol.pose.links for p in sol.scene.link(k).points]
    size = diameter(points)
    omega = max((abs(w) for w in sol.velocity.omega.values()), default=0.0) if sol.velocity else 0.0
    alpha = max((abs(a) for a in sol.acceleration.alpha.values()), default=0.0) if sol.acceleration else 0.0
    speed = max((math.hypot(*t) for t in sol.velocity.tips.values()), default=0.0) if sol.velocity else 0.0
    accel = max((math.hypot(*t) for t in sol.acceleration.tips.values()), default=0.0) if sol.acceleration else 0.0
    return {"position": size, "omega": omega, "alpha": max(alpha, omega * omega), "instant_center": omega,
            "velocity": max(speed, size * omega), "acceleration": max(accel, size * (omega * omega + alpha))}
