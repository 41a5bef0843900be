"""Which side of a flat face a circle cam's disc touches, told by the ``[guess]`` (an assembly).

The disc may touch the face on its left or on its right; the mechanism closes either way. The side is
read from rough poses at the scene's input: the cam's and the follower's, each from what fixes it
without solving anything:

* its rotation: the frame's (none), the input's angle (a link turned about the frame), a slider's line
  (a block on the frame, or a guide on a frame block), or two of its points placed (see below);
* its origin: one of its points placed;

where a point is placed when it is a point of the frame (where the frame has it) or given in ``[guess]``.
The disc's centre K is then on one side of the face's line: that is the side it touches. Where a pose
cannot be read so, or K lies on the line, the guess does not tell, and the default (the left) is taken.
"""

from __future__ import annotations

import cmath
from collections.abc import Mapping
from typing import Literal

from kinepoly.geom.tolerances import SAME_REL
from kinepoly.scene.spec import CamSpec, LinkInput, Scene

__all__ = ["flat_side"]

Side = Literal["left", "right"]


def _placed_points(scene: Scene) -> dict[str, complex]:
    """World places known before solving: the frame's points, then the guessed ones."""
    placed = {name: complex(x, y) for name, (x, y) in scene.guess}
    if scene.ground is not None:
        placed.update({p.name: complex(*p.local) for p in scene.link(scene.ground).points})
    return placed


def _rotation(scene: Scene, link: str, placed: Mapping[str, complex]) -> complex | None:
    """The link's rotation (a unit complex number) where the scene fixes it before solving, else None."""
    if link == scene.ground:
        return 1.0 + 0.0j
    for spec in scene.inputs:
        if isinstance(spec, LinkInput) and spec.link == link and spec.relative_to in (None, scene.ground):
            return cmath.exp(1j * spec.angle_rad)
    for slider in scene.sliders:
        if slider.block == link and slider.guide == scene.ground:
            return cmath.exp(1j * slider.angle_rad)
        if slider.guide == link and slider.block == scene.ground:
            return cmath.exp(-1j * slider.angle_rad)
    known = [(complex(*p.local), placed[p.name]) for p in scene.link(link).points if p.name in placed]
    for i, (local_a, world_a) in enumerate(known):
        for local_b, world_b in known[i + 1:]:
            if abs(local_b - local_a) > 0.0 and abs(world_b - world_a) > 0.0:
                turn = (world_b - world_a) / (local_b - local_a)
                return turn / abs(turn)
    return None


def _to_world(scene: Scene, link: str, placed: Mapping[str, complex]) -> tuple[complex, complex] | None:
    """(origin, rotation) of the link's frame in the world, or None where the scene does not fix it."""
    rotation = _rotation(scene, link, placed)
    if rotation is None:
        return None
    if link == scene.ground:
        return 0.0j, rotation
    for p in scene.link(link).points:
        if p.name in placed:
            return placed[p.name] - rotation * complex(*p.local), rotation
    return None


def flat_side(scene: Scene, cam: CamSpec) -> Side | None:
    """The side of the flat face (``cam.flat``, through and angle in the follower's frame) on which the disc's
    centre lies at the guessed position, or None where the scene and its guess do not tell."""
    assert cam.flat is not None
    placed = _placed_points(scene)
    cam_pose, follower_pose = _to_world(scene, cam.cam, placed), _to_world(scene, cam.follower, placed)
    if cam_pose is None or follower_pose is None:
        return None
    (x, y), angle = cam.flat
    k = cam_pose[0] + cam_pose[1] * complex(*cam.center)
    through = follower_pose[0] + follower_pose[1] * complex(x, y)
    along = follower_pose[1] * cmath.exp(1j * angle)
    height = (k - through) * along.conjugate()  # K in the face's own frame: its y is the side
    if abs(height.imag) <= SAME_REL * max(cam.radius, abs(k - through)):
        return None
    return "left" if height.imag > 0.0 else "right"
