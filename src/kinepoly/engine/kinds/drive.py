"""Drive kind: one link placed on a known one by a driven joint between them (a motor on a link, a cylinder)
(``engine.carry``); in the polygons a motor adds its rate, a cylinder its relative term along the slide."""

from __future__ import annotations

import numpy as np

from kinepoly.engine.carry import place_on
from kinepoly.engine.groups import DriveGroup
from kinepoly.engine.kind import Kind, Later, Placed
from kinepoly.engine.lines import add_motor_rate, lay_driven_slider
from kinepoly.engine.placement import Placement
from kinepoly.engine.policy import Policy
from kinepoly.engine.results import AccelerationContext, VelocityContext
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import SliderSpec

__all__ = ["KIND", "acceleration", "find", "place", "velocity"]


def find(mechanism: Mechanism, known: set[str]) -> DriveGroup | None:
    """A driven joint between a known link and an unknown one."""
    for drive in mechanism.drives:
        if drive.on_frame:
            continue
        if drive.base in known and drive.moving not in known:
            return DriveGroup(drive, drive.moving, drive.base)
        if drive.moving in known and drive.base not in known:
            return DriveGroup(drive, drive.base, drive.moving)
    return None


def velocity(state: VelocityContext, group: DriveGroup) -> None:
    """A link placed on a known one by a driven joint: a motor adds its omega, a cylinder its s_dot."""
    polygon, sliding = state.polygon, state.sliding
    drive = group.drive
    if isinstance(drive.joint, SliderSpec):
        slider = drive.joint
        start = polygon.tip(group.known, slider.point)
        sliding[slider.name] = lay_driven_slider(polygon, slider, drive.rate(1), group.known, start)
        return
    polygon.tip(group.known, drive.joint.point)
    known_rate = polygon.rate_of(group.known)
    assert known_rate is not None
    add_motor_rate(polygon, drive, group.link, group.known, known_rate)


def acceleration(ctx: AccelerationContext, group: DriveGroup) -> None:
    """A link placed on a known one by a driven joint: a motor adds its alpha; a cylinder's block point
    gets the Coriolis term 2 omega x s_dot e, then s_ddot along the slide."""
    b, drive = ctx.b, group.drive
    if isinstance(drive.joint, SliderSpec):
        slider = drive.joint
        start = b.tip(group.known, slider.point)
        moving = slider.block if group.known == slider.guide else slider.guide
        sign = 1.0 if moving == slider.block else -1.0
        end, _ = ctx.lay_coriolis(slider, start, slider.block, slider.guide, slider.point, sign)
        ctx.sliding[slider.name] = lay_driven_slider(b, slider, drive.rate(2), group.known, end)
        ctx.coriolis[slider.name] = np.asarray(sign * (end - start))
        return
    b.tip(group.known, drive.joint.point)
    known_rate = b.rate_of(group.known)
    assert known_rate is not None
    add_motor_rate(b, drive, group.link, group.known, known_rate)


def place(mechanism: Mechanism, group: DriveGroup, placed: Placement, policy: Policy, later: Later) -> Placed:
    """The link on the known one, the driven joint at its input's value at every row."""
    pose = place_on(mechanism, group.drive, group.link, placed.poses[group.known], placed.values[group.drive.index])
    return placed.with_poses({**placed.poses, group.link: pose}), False


KIND: Kind[DriveGroup] = Kind(find, place, velocity, acceleration, batched=True)
