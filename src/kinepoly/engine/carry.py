"""A driven joint between two moving links: how one link sits on the other at each row.

A motor between links a and b (theta_ba given) or a cylinder (the block's stroke s on its guide
given) fixes b on a at every row: b turned relative to a by a known rotation, and each point of b
at a known place in a's frame. With that, the two links are one body of a known shape at each row
(a *carried* dyad's first side), or b is placed at once on a known a (a ``DriveGroup``).

The drive's own rates give the relative motion of a point Y of b over the point of a under it:

- a motor about the pin P: v_Y@b - v_Y@a = omega_ba x PY, and
  a_Y@b - a_Y@a = alpha_ba x PY - (omega_b^2 - omega_a^2) PY;
- a cylinder (b the block): v = s_dot e, a = s_ddot e + 2 omega_a x s_dot e (the Coriolis term),
  with the signs turned over when b is the guide.
"""

from __future__ import annotations

import numpy as np

from kinepoly.geom.arrays import Points, Reals, turn
from kinepoly.model.array_pose import ArrayPose, local_point
from kinepoly.model.mechanism import Drive, Mechanism, Revolute

__all__ = ["carried_local", "drive_values", "place_on", "relative_acceleration", "relative_turn", "relative_velocity"]


def drive_values(mechanism: Mechanism, inputs: Reals) -> tuple[Reals, ...]:
    """Each drive's value at every row: the first drive's are ``inputs``, the others keep the scene's."""
    n = len(inputs)
    return tuple(inputs if d.index == 0 else np.full(n, d.value()) for d in mechanism.drives)


def _sign(drive: Drive, link: str) -> float:
    """+1 when ``link`` is the drive's moving link (the block of a cylinder), -1 when it is the base."""
    return 1.0 if link == drive.moving else -1.0


def relative_turn(drive: Drive, link: str, values: Reals) -> Points:
    """The rotation of ``link`` relative to the drive's other link, at every row (a unit complex)."""
    if isinstance(drive.joint, Revolute):
        return np.asarray(np.exp(1j * (_sign(drive, link) * values)))
    return np.full(len(values), turn(_sign(drive, link) * drive.joint.angle_rad))


def carried_local(mechanism: Mechanism, drive: Drive, link: str, local: complex, values: Reals) -> Points:
    """Where the point ``local`` of ``link`` (in its own frame) lies in the frame of the drive's other
    link, at every row."""
    carrier = drive.base if link == drive.moving else drive.moving
    rel = relative_turn(drive, link, values)
    joint = drive.joint
    if isinstance(joint, Revolute):
        pin_on_carrier = local_point(mechanism.local(carrier, joint.point))
        return np.asarray(pin_on_carrier + rel * (local - local_point(mechanism.local(link, joint.point))))
    slide = turn(joint.angle_rad)
    block_point = local_point(mechanism.local(joint.block, joint.point))
    if link == joint.block:  # into the guide's frame
        return np.asarray(local_point(mechanism.slide_through(joint)) + values * slide + rel * (local - block_point))
    through = local_point(mechanism.slide_through(joint))
    return np.asarray(block_point + rel * (local - through) - values)  # into the block's frame


def place_on(mechanism: Mechanism, drive: Drive, link: str, known: ArrayPose, values: Reals) -> ArrayPose:
    """The pose of ``link`` when the drive's other link has pose ``known``."""
    rotation = np.asarray(known.rotation * relative_turn(drive, link, values))
    origin = known.origin + known.rotation * carried_local(mechanism, drive, link, 0j, values)
    return ArrayPose(np.asarray(origin), rotation)


def relative_velocity(drive: Drive, link: str, at: Points, pin: Points | None, slide: Points | None) -> Points:
    """v of the point of ``link`` at ``at`` over the point of the other link under it.

    ``pin``: where the motor's pin is (a motor); ``slide``: the unit slide direction (a cylinder)."""
    sign = _sign(drive, link)
    if pin is not None:
        return np.asarray(sign * drive.rate(1) * (1j * (at - pin)))
    assert slide is not None
    return np.asarray(sign * drive.rate(1) * slide)


def relative_acceleration(drive: Drive, link: str, at: Points, pin: Points | None, slide: Points | None,
                          omega_link: Reals, omega_other: Reals, omega_guide: Reals) -> Points:
    """a of the point of ``link`` at ``at`` over the point of the other link under it (see the module)."""
    sign = _sign(drive, link)
    if pin is not None:
        r = at - pin
        return np.asarray(sign * drive.rate(2) * (1j * r) - (omega_link * omega_link - omega_other * omega_other) * r)
    assert slide is not None
    return np.asarray(sign * (drive.rate(2) * slide + 2.0 * omega_guide * (1j * drive.rate(1) * slide)))
