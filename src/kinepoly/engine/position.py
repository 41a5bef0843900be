"""Execute the position plan over an array of inputs: the driver, then each group in order.

Each dyad is closed in its closed form (``engine.closures``), a group that is not a dyad by
Newton's method (``engine.newton``). Which assembly each row takes, where a Newton row starts,
and whether a row that does not close is an error (a solve) or a marked row (a sweep) is the
assembly policy's decision (``engine.assembly``): this module only executes.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Protocol

import numpy as np

from kinepoly.engine.carry import drive_values, place_on
from kinepoly.engine.closures import Choice, Closure, close_dyad
from kinepoly.engine.gears import Rolled, place_rolling
from kinepoly.engine.plan import CamGroup, DriveGroup, GearGroup, Group, NewtonGroup, PositionPlan
from kinepoly.geom.arrays import Bools, Points, Reals, turn
from kinepoly.model.array_pose import ArrayPose, pose_from_point, still_pose
from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput

if TYPE_CHECKING:
    from kinepoly.engine.cam_contact import Candidates, Ints

__all__ = ["Failure", "Placement", "Policy", "Positions", "describe_input", "driver_poses", "input_values", "place_groups", "solve_positions"]


@dataclass(frozen=True)
class Failure:
    """Rows where one group cannot be assembled (rows where an earlier group failed are not among them)."""

    group: str
    joint: str
    rows: Bools
    why: Callable[[int], str]


@dataclass(frozen=True)
class Placement:
    """What placing some groups gave: poses, the rows that closed, failures, rough rows, warnings."""

    poses: dict[str, ArrayPose]
    ok: Bools
    failures: tuple[Failure, ...] = ()
    near: tuple[Failure, ...] = ()
    notices: tuple[Notice, ...] = ()
    values: tuple[Reals, ...] = ()
    """Each input's value at every row (``engine.carry.drive_values``)."""
    rolled: dict[str, Rolled] = field(default_factory=dict)
    """The gears placed by rolling, with how far each has rolled (``engine.gears``)."""
    marks: dict[str, Points] = field(default_factory=dict)
    """Points found while placing (a spline cam's contact and centre of curvature), by name."""
    contact_parameters: dict[str, Reals] = field(default_factory=dict)
    """Each spline cam's contact parameter on its profile at every row (``engine.cam_place``)."""

    def row_poses(self, links: Iterable[str], row: int) -> dict[str, LinkPose]:
        """The poses of ``links`` at ``row`` as scalar values (for the one-row solvers)."""
        return {link: LinkPose(*self.poses[link].row(row)) for link in links}

    def row_values(self, row: int) -> dict[int, float]:
        """Each input's value at ``row``, by input index."""
        return {index: float(values[row]) for index, values in enumerate(self.values)}


@dataclass
class Positions:
    """Poses of every link of the plan at every row; ``ok`` where all of them could be placed."""

    mechanism: Mechanism
    poses: dict[str, ArrayPose]
    ok: Bools
    failures: tuple[Failure, ...] = ()
    near: tuple[Failure, ...] = ()
    notices: tuple[Notice, ...] = ()
    values: tuple[Reals, ...] = ()
    """Each input's value at every row: theta (rad) or s (length)."""
    marks: dict[str, Points] = field(default_factory=dict)
    """Points the construction found on the mechanism (a triad's Assur point), by name."""
    contact_parameters: dict[str, Reals] = field(default_factory=dict)
    """Each spline cam's contact parameter on its profile at every row."""
    _points: dict[str, Points] = field(default_factory=dict)
    _turned: dict[tuple[str, str], tuple[Points, Points]] = field(default_factory=dict)

    @property
    def n(self) -> int:
        return len(self.ok)

    def point(self, name: str) -> Points:
        """World position of a named point (through the first solved link that has it)."""
        found = self._points.get(name)
        if found is None:
            owner = next(link for link in self.mechanism.links_of_point(name) if link in self.poses)
            found = self.poses[owner].world(self.mechanism.local(owner, name))
            self._points[name] = found
        return found

    def chord(self, start: str, end: str) -> tuple[Points, Points]:
        """The vector from point ``start`` to point ``end`` at every row, and that vector turned a quarter
        counter-clockwise: the direction of the relative velocity of ``end`` about ``start`` on their link.
        Made once, for the velocity and acceleration polygons alike (do not change them in place)."""
        found = self._turned.get((start, end))
        if found is None:
            r = np.asarray(self.point(end) - self.point(start))
            found = self._turned[start, end] = (r, np.asarray(1j * r))
        return found

    def world(self, link: str, point: str) -> Points:
        return self.poses[link].world(self.mechanism.local(link, point))

    def add_point(self, name: str, at: Points) -> None:
        """A point the construction finds on the mechanism (a triad's Assur point), by name."""
        self._points[name] = at
        self.marks[name] = at

    def row(self, k: int) -> dict[str, LinkPose]:
        """The poses of row k as scalar values."""
        return {link: LinkPose(*pose.row(k)) for link, pose in self.poses.items()}


def describe_input(mechanism: Mechanism) -> str:
    """The inputs as a textbook names them: ``theta12 = 60 deg``, ``s14 = 130 mm``, ``theta32 = -50 deg``."""
    scene = mechanism.scene
    if isinstance(scene.input, GivenInput):
        return "the given motion"
    out = []
    for drive in mechanism.drives:
        inp = drive.spec
        if isinstance(inp, LinkInput):
            value = math.degrees(inp.angle_rad) if scene.units.angle == "deg" else inp.angle_rad
            out.append(f"{drive.name} = {value:.15g} {scene.units.angle}")
        else:
            out.append(f"{drive.name} = {inp.s:.15g} {scene.units.length}")
    return ", ".join(out)


def input_values(mechanism: Mechanism) -> Reals:
    """The scene's own input as a batch of one row: theta (rad) or s (length); 0 for a [given] body."""
    inp = mechanism.scene.input
    value = inp.angle_rad if isinstance(inp, LinkInput) else inp.s if isinstance(inp, SliderInput) else 0.0
    return np.array([value], np.float64)


def driver_poses(mechanism: Mechanism, values: tuple[Reals, ...]) -> dict[str, ArrayPose]:
    """The frame and the links the inputs on the frame drive, at every row; ``values`` are each input's
    theta (rad) or s (length)."""
    n = len(values[0])
    ground = mechanism.ground
    if ground is None:  # a [given] body: its own frame is the frame
        return {mechanism.link_names[0]: still_pose(n)}
    poses = {ground: still_pose(n)}
    for drive in mechanism.drives:
        if drive.on_frame:
            _place_frame_drive(mechanism, drive.spec, values[drive.index], poses)
    return poses


def _place_frame_drive(mechanism: Mechanism, inp: LinkInput | SliderInput, inputs: Reals,
                       poses: dict[str, ArrayPose]) -> None:
    n = len(inputs)
    ground = mechanism.ground
    assert ground is not None
    if isinstance(inp, LinkInput):
        pivot = mechanism.input_pivot(inp).point
        x, y = mechanism.local(ground, pivot)
        rotation = np.empty(n, np.complex128)  # e^(i theta), its parts written in place: the same bits as
        np.cos(inputs, out=rotation.real)       # np.exp(1j * theta), without its complex temporaries
        np.sin(inputs, out=rotation.imag)
        poses[inp.link] = pose_from_point(mechanism.local(inp.link, pivot), np.full(n, complex(x, y)), rotation)
    else:
        slider = mechanism.slider(inp.slider)
        direction = turn(slider.angle_rad)
        along = np.asarray(complex(*slider.through) + inputs * direction, np.complex128)
        if slider.guide == ground:
            poses[slider.block] = pose_from_point(mechanism.local(slider.block, slider.point), along,
                                                  np.full(n, direction))
        else:  # the block is the frame: place the guide so that the frame's point sits at s
            block_point = np.full(n, complex(*mechanism.local(ground, slider.point)))
            poses[slider.guide] = ArrayPose(block_point - np.conjugate(direction) * along,
                                            np.full(n, np.conjugate(direction)))


class Policy(Protocol):
    """What the executor asks an assembly policy (``engine.assembly`` has the two policies)."""

    def choose(self, mechanism: Mechanism, closure: Closure, placed: Placement,
               later: Callable[[int], Placement]) -> Choice | Placement:
        """The assembly each row takes, or, having carried the assemblies through the later groups
        with ``later``, the whole placement."""

    def newton(self, mechanism: Mechanism, group: NewtonGroup, placed: Placement) -> Placement:
        """Place a group that is not a dyad, starting each row where the policy says."""

    def failed(self, mechanism: Mechanism, closure: Closure, rows: Bools) -> None:
        """Rows where a dyad does not close: a solve raises here, a sweep marks them."""

    def contact(self, mechanism: Mechanism, group: CamGroup, candidates: Candidates,
                placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """The contact of a spline cam each row keeps (-1 where it has none), with any warning."""

    def unreachable(self, message: str) -> None:
        """Rows where a spline cam's follower cannot touch its profile: a solve raises, a sweep marks them."""


def place_groups(mechanism: Mechanism, groups: tuple[Group, ...], placed: Placement, policy: Policy) -> Placement:
    """Place ``groups`` in order on top of ``placed``."""
    for index, group in enumerate(groups):
        if isinstance(group, NewtonGroup) and group.gears:
            from kinepoly.engine.planet import place_planet

            placed = place_planet(mechanism, group, placed)
            continue
        if isinstance(group, NewtonGroup):
            placed = policy.newton(mechanism, group, placed)
            if group.cams:
                from kinepoly.engine.cam_place import place_floating_contacts

                placed = place_floating_contacts(mechanism, group, placed, policy)
            continue
        if isinstance(group, GearGroup):
            pose, rolled = place_rolling(mechanism, group.gear, group.link, group.joint, group.carrier,
                                         placed.poses, placed.rolled, placed.values)
            turned = placed.rolled if rolled is None else {**placed.rolled, group.link: rolled}
            placed = replace(placed, poses={**placed.poses, group.link: pose}, rolled=turned)
            continue
        if isinstance(group, CamGroup):
            from kinepoly.engine.cam_place import place_cam

            placed = place_cam(mechanism, group, placed, policy)
            continue
        if isinstance(group, DriveGroup):
            pose = place_on(mechanism, group.drive, group.link, placed.poses[group.known],
                            placed.values[group.drive.index])
            placed = replace(placed, poses={**placed.poses, group.link: pose})
            continue
        closure = close_dyad(mechanism, placed.poses, group, placed.values)
        if closure.near is not None:
            placed = replace(placed, near=(*placed.near, Failure(group.name, closure.joint, closure.near[0],
                                                                 closure.near[1])))
        if not closure.ok.all():
            bad = placed.ok & ~closure.ok
            policy.failed(mechanism, closure, bad)
            placed = replace(placed, ok=placed.ok & closure.ok,
                             failures=(*placed.failures, Failure(group.name, closure.joint, bad, closure.why)))
        choice: Choice = 0
        if len(closure.telling) == 2:
            rest = groups[index + 1:]
            base = placed

            def later(label: int, base: Placement = base, rest: tuple[Group, ...] = rest,
                      closure: Closure = closure) -> Placement:
                step = replace(base, poses={**base.poses, **closure.place(label)})
                return place_groups(mechanism, rest, step, policy)

            chosen = policy.choose(mechanism, closure, placed, later)
            if isinstance(chosen, Placement):
                return chosen
            choice = chosen
        placed = replace(placed, poses={**placed.poses, **closure.place(choice)})
    return placed


def solve_positions(mechanism: Mechanism, plan: PositionPlan, inputs: Reals, policy: Policy) -> Positions:
    """Poses of the driven links and of every group in the plan at each input, as ``policy`` chooses."""
    values = drive_values(mechanism, inputs)
    start = Placement(driver_poses(mechanism, values or (inputs,)), np.ones(len(inputs), np.bool_), values=values)
    if isinstance(mechanism.scene.input, GivenInput):
        return Positions(mechanism, start.poses, start.ok)
    placed = place_groups(mechanism, plan.groups, start, policy)
    positions = Positions(mechanism, placed.poses, placed.ok, placed.failures, placed.near, placed.notices, values,
                          contact_parameters=placed.contact_parameters)
    for name, at in placed.marks.items():
        positions.add_point(name, at)
    return positions
