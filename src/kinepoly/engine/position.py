"""Execute the position plan over an array of inputs: the driver, then each group in order, placed by its
kind (``engine.table``, ``engine.kinds``).

Each dyad is closed in its closed form (``engine.closures``), a group that is not a dyad by
Newton's method (``engine.newton``). Which assembly each row takes, where a Newton row starts,
and whether a row that does not close is an error (a solve) or a marked row (a sweep) is the
assembly policy's decision (``engine.assembly``): this module only executes.
"""

from __future__ import annotations

import numpy as np

from kinepoly.engine.carry import drive_values
from kinepoly.engine.groups import Group, PositionPlan
from kinepoly.engine.inputs import describe_input, input_values
from kinepoly.engine.placement import Failure, Placement, Positions
from kinepoly.engine.policy import Policy
from kinepoly.engine.table import kind_of
from kinepoly.geom.arrays import Points, Reals, trues, turn
from kinepoly.model.array_pose import ArrayPose, local_point, pose_at, pose_from_point, still_pose
from kinepoly.model.family import FamilyMechanism
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput

__all__ = ["Failure", "Placement", "Policy", "Positions", "describe_input", "driver_poses", "input_values",
           "place_groups", "solve_positions"]


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
        rotation = _unit_turns(mechanism, inputs)
        poses[inp.link] = pose_at(mechanism.local_at(inp.link, pivot), poses[ground].world_at(
            mechanism.local_at(ground, pivot)), rotation)
    else:
        slider = mechanism.slider(inp.slider)
        direction = turn(slider.angle_rad)
        along = np.asarray(local_point(mechanism.slide_through(slider)) + inputs * direction, np.complex128)
        if slider.guide == ground:
            poses[slider.block] = pose_from_point(mechanism.local(slider.block, slider.point), along,
                                                  np.full(n, direction))
        else:  # the block is the frame: place the guide so that the frame's point sits at s
            block_point = np.full(n, local_point(mechanism.local(ground, slider.point)))
            poses[slider.guide] = ArrayPose(block_point - np.conjugate(direction) * along,
                                            np.full(n, np.conjugate(direction)))


def _unit_turns(mechanism: Mechanism, inputs: Reals) -> Points:
    """e^(i theta) at every row, its parts written in place: the same bits as np.exp(1j * theta), without its
    complex temporaries. A family's members that share their inputs (``model.family``): one member's are worked out
    and repeated."""
    each = mechanism.rows_each if isinstance(mechanism, FamilyMechanism) and mechanism.shared_inputs else len(inputs)
    one = inputs[:each]
    rotation = np.empty(len(one), np.complex128)
    np.cos(one, out=rotation.real)
    np.sin(one, out=rotation.imag)
    return rotation if each == len(inputs) else np.tile(rotation, len(inputs) // each)


def place_groups(mechanism: Mechanism, groups: tuple[Group, ...], placed: Placement, policy: Policy) -> Placement:
    """Place ``groups`` in order on top of ``placed``, each by its kind (``engine.table``)."""
    for index, group in enumerate(groups):
        rest = groups[index + 1:]

        def later(step: Placement, rest: tuple[Group, ...] = rest) -> Placement:
            return place_groups(mechanism, rest, step, policy)

        placed, done = kind_of(group).place(mechanism, group, placed, policy, later)
        if done:
            return placed
    return placed


def solve_positions(mechanism: Mechanism, plan: PositionPlan, inputs: Reals, policy: Policy) -> Positions:
    """Poses of the driven links and of every group in the plan at each input, as ``policy`` chooses."""
    values = drive_values(mechanism, inputs)
    start = Placement(driver_poses(mechanism, values or (inputs,)), trues(len(inputs)), values=values)
    if isinstance(mechanism.scene.input, GivenInput):
        return Positions(mechanism, start.poses, start.ok)
    placed = place_groups(mechanism, plan.groups, start, policy)
    positions = Positions(mechanism, placed.poses, placed.ok, placed.failures, placed.near, placed.notices, values,
                          contact_parameters=placed.contact_parameters)
    for name, at in placed.marks.items():
        positions.add_point(name, at)
    return positions
