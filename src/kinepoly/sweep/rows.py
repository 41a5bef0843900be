"""A sweep's rows one at a time: the link poses the sweep found there, as a per-row solve wants them.

``row_poses(result, row)`` is the pose of every link of the plan at a shown row, in the scene's
frame, as the sweep placed it (so in the assembly it followed from the scene's own input);
``row_guesses(result)`` is the same for every shown row as a ``[guess]``: every point of every
moving link where the sweep put it. A ``kinepoly solve`` of the scene at a row's input with that
guess lands in the sweep's assembly (the bench solves its rows so).
"""

from __future__ import annotations

import numpy as np

from kinepoly.model.mechanism import Mechanism
from kinepoly.model.pose import LinkPose
from kinepoly.sweep.result import SweepResult

__all__ = ["Guess", "row_guesses", "row_poses"]

Guess = tuple[tuple[str, tuple[float, float]], ...]
"""A scene's ``[guess]``: (point, (x, y)) pairs."""


def _computed_rows(result: SweepResult) -> np.ndarray:
    """The computed row of each shown row."""
    if result.positions is None or result.shown is None:
        raise ValueError("this sweep result keeps no poses (it was not made by kinepoly.sweep.run_sweep)")
    return np.flatnonzero(result.shown)


def _poses_at(result: SweepResult, computed: int) -> dict[str, LinkPose] | None:
    positions = result.positions
    assert positions is not None
    return positions.row(computed) if bool(positions.ok[computed]) else None


def row_poses(result: SweepResult, row: int) -> dict[str, LinkPose] | None:
    """Each link's pose at the shown row ``row`` (the scene's frame); None where the mechanism cannot be assembled."""
    return _poses_at(result, int(_computed_rows(result)[row]))


def _guess(mechanism: Mechanism, poses: dict[str, LinkPose]) -> Guess:
    scene = mechanism.scene
    frame = set(scene.link(scene.ground).point_names) if scene.ground else set()
    out: dict[str, tuple[float, float]] = {}
    for link, pose in poses.items():
        if link == scene.ground:
            continue
        for name in scene.link(link).point_names:
            if name not in frame and name not in out:
                out[name] = pose.world(mechanism.local(link, name))
    return tuple(out.items())


def row_guesses(result: SweepResult) -> list[Guess | None]:
    """A ``[guess]`` for every shown row: each point of each moving link where the sweep put it (None where
    the mechanism cannot be assembled)."""
    out: list[Guess | None] = []
    for computed in _computed_rows(result):
        poses = _poses_at(result, int(computed))
        assert result.positions is not None
        out.append(None if poses is None else _guess(result.positions.mechanism, poses))
    return out
