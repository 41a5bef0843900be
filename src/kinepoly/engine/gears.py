"""Gears by their pitch curves: where the pitch point is, and how rolling places the second gear.

At the pitch point P the two pitch curves touch. For a circle, m is the unit vector from its centre
to P, its tangent t = k x m, and its *rolling coordinate* sigma = r delta, delta the angle of P in
the gear's own frame less its ``phase`` (0 at the reference mesh); for a rack's line, t is the line's
direction d and sigma the distance of P from ``through`` along d, less its phase. Rolling without
slip is d sigma_a t_a = d sigma_b t_b, so, both zero at the reference mesh,

    sigma_b = c sigma_a,   c = t_a . t_b = -1 (external pair), +1 (internal pair), +-1 (rack).

A gear whose angle is not itself placed by rolling (the input, the frame, a link of a dyad) has
delta taken the shorter way at the scene's input (in (-pi, pi]) and followed continuously over the
rows of a sweep; a gear placed by rolling carries its delta on to its next mesh.
"""

from __future__ import annotations

import math

import numpy as np
from msgspec import Struct

from kinepoly.engine.inputs import describe_input
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import Points, Reals, turn
from kinepoly.geom.tolerances import PARALLEL_SIN, ROUNDING_REL, SAME_REL, TINY_POSITIVE
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import GearSpec, PitchCircle, PitchLine

__all__ = ["Mesh", "Rolled", "anchor_row", "free_delta", "mesh", "pitch_label", "place_rolling"]


class Rolled(Struct, frozen=True):
    """A gear placed by rolling: its delta (unwrapped) and the angle of the pitch point it was measured
    at, less that mesh's phase, at every row."""

    delta: Reals
    aim: Reals


class Mesh(Struct, frozen=True):
    """One pair at every row: the pitch point, each side's unit m (centre to P; for a line the unit
    normal from the circle's centre toward it) and tangent t, and the contact normal (side 0 to side 1)."""

    point: Points
    m: tuple[Points, Points]
    t: tuple[Points, Points]
    normal: Points

    @property
    def sign(self) -> Reals:
        """c = t_0 . t_1: +1 or -1 at every row."""
        return np.asarray(np.sign((self.t[0] * np.conj(self.t[1])).real))


def pitch_label(gear: GearSpec) -> str:
    """The pitch point's name: ``P23``."""
    return f"P{gear.name}"


def _centre(mechanism: Mechanism, link: str, curve: PitchCircle, pose: ArrayPose) -> Points:
    return pose.world(mechanism.local(link, curve.center))


def _line(curve: PitchLine, pose: ArrayPose) -> tuple[Points, Points]:
    through = pose.world(curve.through)
    return through, np.asarray(pose.rotation * turn(curve.angle_rad))


def _where(mechanism: Mechanism) -> str:
    return describe_input(mechanism)


def _distance_error(mechanism: Mechanism, gear: GearSpec, actual: Reals, expected: float, what: str) -> None:
    bad = np.flatnonzero(~(np.abs(actual - expected) <= SAME_REL * max(expected, TINY_POSITIVE) * 10.0 + ROUNDING_REL))
    if len(bad) == 0:
        return
    k = int(bad[0])
    unit = mechanism.scene.units.length
    raise SceneError(f"{mechanism.scene.source}:{gear.line}: gears.{gear.name}: {what} are {float(actual[k]):.10g} "
                     f"{unit} apart at {_where(mechanism)}{'' if len(actual) == 1 else f' (row {k})'}; expected "
                     f"{expected:.10g} {unit}, or the pitch curves do not touch (move the centres, "
                     "or change the radii)")


def mesh(mechanism: Mechanism, gear: GearSpec, poses: dict[str, ArrayPose]) -> Mesh:
    """The pair's pitch point and directions at every row, from the poses of both gears' links (a rack's
    place along its line does not matter). Raises SceneError where the curves do not touch."""
    a, b = gear.links
    one, two = gear.pitch
    if isinstance(one, PitchCircle) and isinstance(two, PitchCircle):
        o1, o2 = _centre(mechanism, a, one, poses[a]), _centre(mechanism, b, two, poses[b])
        d = o2 - o1
        dist = np.abs(d)
        expected = abs(one.radius - two.radius) if gear.internal else one.radius + two.radius
        names = f"the centres {one.center} and {two.center}"
        _distance_error(mechanism, gear, np.asarray(dist), expected, names)
        u = np.asarray(d / np.where(dist == 0.0, 1.0, dist))
        if not gear.internal:
            return Mesh(np.asarray(o1 + one.radius * u), (u, -u), (1j * u, -1j * u), u)
        m = u if one.radius > two.radius else -u
        point = np.asarray(o1 + one.radius * m)
        normal = -m if one.radius > two.radius else m
        return Mesh(point, (m, m), (1j * m, 1j * m), np.asarray(normal))
    circle_first = isinstance(one, PitchCircle)
    c_link, l_link = (a, b) if circle_first else (b, a)
    circle = one if circle_first else two
    line = two if circle_first else one
    assert isinstance(circle, PitchCircle) and isinstance(line, PitchLine)
    o = _centre(mechanism, c_link, circle, poses[c_link])
    through, d = _line(line, poses[l_link])
    nu = 1j * d
    h = np.asarray(((through - o) * np.conj(nu)).real)
    _distance_error(mechanism, gear, np.abs(h), circle.radius, f"the centre {circle.center} and the pitch line")
    m = np.asarray(np.where(h >= 0.0, 1.0, -1.0) * nu)
    point = np.asarray(o + circle.radius * m)
    if circle_first:
        return Mesh(point, (m, m), (1j * m, d), m)
    return Mesh(point, (m, m), (d, 1j * m), np.asarray(-m))


def _sigma(gear: GearSpec, side: int, delta: Reals | None, point: Points, pose: ArrayPose) -> Reals:
    curve = gear.pitch[side]
    if isinstance(curve, PitchCircle):
        assert delta is not None
        return np.asarray(curve.radius * delta)
    through, d = _line(curve, pose)
    return np.asarray(((point - through) * np.conj(d)).real - gear.phase[side])


def anchor_row(mechanism: Mechanism, values: tuple[Reals, ...]) -> int:
    """The row of the scene's own input (the sweep's seed row): where delta is taken the shorter way."""
    if not values or not mechanism.drives:
        return 0
    drive = mechanism.drives[0]
    gap = values[0] - drive.value()
    if isinstance(drive.joint, Revolute):
        gap = np.remainder(gap + math.pi, 2.0 * math.pi) - math.pi
    return int(np.argmin(np.abs(gap)))


def free_delta(mechanism: Mechanism, angle: Reals, values: tuple[Reals, ...]) -> Reals:
    """delta of a gear not placed by rolling: continuous over the rows, in (-pi, pi] at the scene's input."""
    smooth = np.unwrap(angle)
    k = anchor_row(mechanism, values)
    at = float(smooth[k])
    wrapped = math.remainder(at, 2.0 * math.pi)
    wrapped = math.pi if wrapped == -math.pi else wrapped
    return np.asarray(smooth + (wrapped - at))


def _known_delta(mechanism: Mechanism, gear: GearSpec, side: int, the_mesh: Mesh, pose: ArrayPose,
                 rolled: Rolled | None, values: tuple[Reals, ...]) -> Reals:
    aim = np.angle(the_mesh.m[side]) - gear.phase[side]
    if rolled is not None:  # carried on from its last mesh: the angle between the two pitch points
        return np.asarray(rolled.delta + np.remainder(aim - rolled.aim + math.pi, 2.0 * math.pi) - math.pi)
    return free_delta(mechanism, np.asarray(aim - np.angle(pose.rotation)), values)


def place_rolling(mechanism: Mechanism, gear: GearSpec, link: str, joint: Revolute | object, carrier: str,
                  poses: dict[str, ArrayPose], rolled: dict[str, Rolled],
                  values: tuple[Reals, ...]) -> tuple[ArrayPose, Rolled | None]:
    """The pose of the gear ``link`` (pinned at its pitch centre to ``carrier``, or a rack sliding on it)
    that rolls on the other gear of ``gear``, known in ``poses``."""
    from kinepoly.scene.spec import SliderSpec

    side = gear.links.index(link)
    other = 1 - side
    known = gear.links[other]
    curve = gear.pitch[side]
    carrier_pose = poses[carrier]
    if isinstance(curve, PitchCircle):
        assert isinstance(joint, Revolute)
        centre = carrier_pose.world(mechanism.local(carrier, joint.point))
        trial = ArrayPose(np.asarray(centre - complex(*mechanism.local(link, curve.center))), carrier_pose.rotation)
    else:
        assert isinstance(joint, SliderSpec)
        rotation = np.asarray(carrier_pose.rotation * turn(joint.angle_rad))  # the block turns with its guide
        trial = _slide_pose(mechanism, joint, link, carrier_pose, rotation, np.zeros(len(rotation)))
    the_mesh = mesh(mechanism, gear, {**poses, link: trial})
    known_delta = _known_delta(mechanism, gear, other, the_mesh, poses[known], rolled.get(known), values)
    sigma = the_mesh.sign * _sigma(gear, other, known_delta, the_mesh.point, poses[known])
    if isinstance(curve, PitchCircle):
        delta = np.asarray(sigma / curve.radius)
        aim = np.asarray(np.angle(the_mesh.m[side]) - gear.phase[side])
        theta = aim - delta
        rotation = np.asarray(np.exp(1j * theta))
        pose = ArrayPose(np.asarray(centre - rotation * complex(*mechanism.local(link, curve.center))), rotation)
        return pose, Rolled(delta, aim)
    assert isinstance(joint, SliderSpec)
    through, d = _line(curve, trial)  # at s = 0
    along = ((the_mesh.point - through) * np.conj(d)).real
    e_dot_d = (trial.rotation * np.conj(d)).real  # the slide's direction is the block's x-axis
    if np.any(np.abs(e_dot_d) < PARALLEL_SIN):
        raise SceneError(f"{mechanism.scene.source}:{gear.line}: gears.{gear.name}: the rack {link} slides square to "
                         "its pitch line; expected the slide along the pitch line")
    s = np.asarray((along - (sigma + gear.phase[side])) / e_dot_d)
    rotation = trial.rotation
    return _slide_pose(mechanism, joint, link, carrier_pose, rotation, s), None


def _slide_pose(mechanism: Mechanism, joint: object, link: str, carrier_pose: ArrayPose, rotation: Points,
                s: Reals) -> ArrayPose:
    """A rack (the block of ``joint``) on its guide at slide value ``s``."""
    from kinepoly.scene.spec import SliderSpec

    assert isinstance(joint, SliderSpec)
    if joint.block != link:
        raise SceneError(f"{mechanism.scene.source}: sliders.{joint.name}: a rack must be the block of its slider "
                         f"(block = \"{link}\"); expected the rack to slide on the link that holds it")
    e = np.asarray(carrier_pose.rotation * turn(joint.angle_rad))
    on_line = carrier_pose.world(joint.through) + s * e
    return ArrayPose(np.asarray(on_line - rotation * complex(*mechanism.local(link, joint.point))), rotation)
