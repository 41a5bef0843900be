"""The scene's inputs as values: their textbook names and a solve's batch of one row."""

from __future__ import annotations

import math

import numpy as np

from kinepoly.geom.arrays import Reals
from kinepoly.model.mechanism import Mechanism
from kinepoly.scene.spec import GivenInput, LinkInput, SliderInput

__all__ = ["describe_input", "input_values"]


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
