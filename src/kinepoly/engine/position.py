"""Execute the position plan over an array of inputs: the driver, then each group in order.

Each dyad is closed in its closed form (``engine.closures``), a group that is not a dyad by
Newton's method (``engine.newton``). Which assembly each row takes, where a Newton row starts,
and whether a row that does not close is an error (a solve) or a marked row (a sweep) is the
assembly policy's decision (``engine.assembly``): this module only executes.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from kinepoly.engine.cam_place import place_cam, place_floating_contacts
from kinepoly.engine.carry import drive_values, place_on
from kinepoly.engine.closures import Choice, Closure, close_dyad
from kinepoly.engine.gears import place_rolling
from kinepoly.engine.inputs import describe_input, input_values
from kinepoly.engine.placement import Failure, Placement, Positions
from kinepoly.engine.plan import CamGroup, DriveGroup, GearGroup, Group, NewtonGroup, PositionPlan
from kinepoly.engine.planet import place_planet
from kinepoly.engine.policy import Policy
from kinepoly.geom.arrays import Reals, turn
from kinepoly.model.array_pose import ArrayPose, pose_from_point, still_pose
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput

__all__ = ["Failure", "Placement", "Policy", "Positions", "describe_input", "driver_poses", "input_values", "place_groups", "solve_positions"]


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


def place_groups(mechanism: Mechanism, groups: tuple[Group, ...], placed: Placement, policy: Policy) -> Placement:
    """Place ``groups`` in order on top of ``placed``."""
    for index, group in enumerate(groups):
        if isinstance(group, NewtonGroup) and group.gears:
            placed = place_planet(mechanism, group, placed)
            continue
        if isinstance(group, NewtonGroup):
            placed = policy.newton(mechanism, group, placed)
            if group.cams:
                placed = place_floating_contacts(mechanism, group, placed, policy)
            continue
        if isinstance(group, GearGroup):
            pose, rolled = place_rolling(mechanism, group.gear, group.link, group.joint, group.carrier,
                                         placed.poses, placed.rolled, placed.values)
            turned = placed.rolled if rolled is None else {**placed.rolled, group.link: rolled}
            placed = replace(placed, poses={**placed.poses, group.link: pose}, rolled=turned)
            continue
        if isinstance(group, CamGroup):
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
