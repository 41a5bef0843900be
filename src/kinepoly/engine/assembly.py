"""The positions at the scene's own input: the solve's batch of one row, its assemblies nearest the ``[guess]``
(``engine.policy.NearestGuess``), with the warnings a solve adds.
"""

from __future__ import annotations

import numpy as np
from msgspec.structs import replace

from kinepoly.engine.groups import PositionPlan
from kinepoly.engine.policy import NearestGuess
from kinepoly.engine.position import Positions, input_values, solve_positions
from kinepoly.model.mechanism import Mechanism
from kinepoly.notice import Notice
from kinepoly.scene.flat_side import flat_side

__all__ = ["position_at_input"]

Vec = tuple[float, float]

def position_at_input(mechanism: Mechanism, plan: PositionPlan, origin: Vec = (0.0, 0.0)) -> Positions:
    """The positions at the scene's own input (a batch of one row), the assembly nearest the ``[guess]``.

    ``origin``: where the mechanism's frame origin lies in the user's frame, for messages.
    """
    with np.errstate(all="ignore"):  # a row that does not close raises by name
        found = solve_positions(mechanism, plan, input_values(mechanism), NearestGuess(dict(mechanism.scene.guess),
                                                                                       origin))
    return replace(found, notices=(*found.notices, *_untold_flat_sides(mechanism)))


def _untold_flat_sides(mechanism: Mechanism) -> list[Notice]:
    """A ``default-assembly`` warning for each circle cam's flat face whose side the ``[guess]`` does not tell
    (``scene.flat_side``: the disc was put on the face's left)."""
    scene = mechanism.scene
    return [Notice("default-assembly", f"cam {cam.name}: no [guess] tells which side of follower {cam.follower}'s flat "
                   f"face the disc touches, so the default was taken: the disc on the face's left; give [guess] "
                   f"positions of a point of the follower and of the cam (or two of the follower's) with the disc's "
                   f"centre on the side you mean")
            for cam in scene.cams if cam.kind == "flat" and not cam.is_spline and flat_side(scene, cam) is None]
