"""The sweep's columns of the higher pairs: a cam follower's motion and pressure angle, gear ratios.

For each ``[[cams]]`` pair the follower's own coordinate and its first two derivatives (a rocker's
``theta``, ``omega``, ``alpha``; a translating follower's slider ``s``, ``s_dot``, ``s_ddot``; what
a cam designer's s-v-a diagram shows) and ``pressure_angle_<pair>``; for each ``[[gears]]`` pair of
two turning gears ``ratio_<b>_<a>`` = omega_b / omega_a, and for each turning gear
``ratio_<gear>_<input>`` against a turning input. Every value is read off the engine's arrays
(``engine.contacts``, the polygons' rates, ``engine.sliders``): nothing here is geometry.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from kinepoly.engine.acceleration import AccelerationResult
from kinepoly.engine.contacts import contacts_over_rows, follower_coordinate, polygon_velocity, pressure_angles
from kinepoly.engine.sliders import slider_motion
from kinepoly.engine.velocity import VelocityResult
from kinepoly.geom.arrays import Reals
from kinepoly.scene.spec import LinkInput, PitchCircle

if TYPE_CHECKING:
    from kinepoly.sweep.columns import ColumnBuilder
    from kinepoly.sweep.result import Follower, Kind

__all__ = ["higher_pair_columns", "ratio_pairs"]


def _add(out: ColumnBuilder, name: str, kind: Kind, values: Reals | None) -> None:
    """A column, unless the scene's own asked columns (or the input) already have it."""
    if values is not None and all(name != taken for taken, *_ in out.raw):
        out.add(name, kind, values)


def _cam_columns(out: ColumnBuilder, velocity: VelocityResult | None, acceleration: AccelerationResult | None,
                 input_column: str) -> list[Follower]:
    mech, positions = out.mechanism, out.positions
    deg = mech.scene.units.angle == "deg"
    moving = polygon_velocity(mech, velocity.polygon) if velocity is not None else None
    contacts = contacts_over_rows(mech, positions.poses, moving, positions.contact_parameters)
    followers: list[Follower] = []
    for cam in mech.scene.cams:
        follower = follower_coordinate(mech, cam)
        names: tuple[str, ...] = ()
        if follower is not None and follower.pivot is not None:
            link = follower.link
            names = (f"theta_{link}", f"omega_{link}", f"alpha_{link}")
            if f"theta_{link}" != input_column:
                _add(out, f"theta_{link}", "angle", positions.poses[link].theta(degrees=deg))
            _add(out, f"omega_{link}", "omega", velocity.polygon.rate_of(link) if velocity is not None else None)
            _add(out, f"alpha_{link}", "alpha",
                 acceleration.polygon.rate_of(link) if acceleration is not None else None)
        elif follower is not None and follower.slider is not None:
            name = follower.slider.name
            names = (f"s_{name}", f"s_dot_{name}", f"s_ddot_{name}")
            motion = slider_motion(positions, follower.slider, velocity, acceleration)
            if f"s_{name}" != input_column:
                _add(out, f"s_{name}", "slider", motion.s)
            _add(out, f"s_dot_{name}", "slider-rate", motion.s_dot)
            _add(out, f"s_ddot_{name}", "slider-acceleration", motion.s_ddot)
        angle, valid = pressure_angles(mech, positions.poses, cam, contacts[cam.name], moving)
        out.add(f"pressure_angle_{cam.name}", "pressure", np.degrees(angle) if deg else angle, valid)
        taken = {name for name, *_ in out.raw} | {input_column}
        followers.append((cam.name, tuple(n for n in names if n in taken)))
    return followers


def ratio_pairs(out: ColumnBuilder) -> list[tuple[str, str]]:
    """(gear, over) pairs whose angular velocity ratio is reported: each mesh of two turning gears, then each
    turning gear against a turning input."""
    mech = out.mechanism
    turning = [link for gear in mech.scene.gears for link, curve in zip(gear.links, gear.pitch, strict=True)
               if isinstance(curve, PitchCircle) and link != mech.ground]
    pairs = [(gear.links[1], gear.links[0]) for gear in mech.scene.gears
             if all(link in turning for link in gear.links)]
    inp = mech.scene.input
    if isinstance(inp, LinkInput) and inp.relative_to is None:
        pairs += [(link, inp.link) for link in dict.fromkeys(turning) if link != inp.link]
    return list(dict.fromkeys(pairs))


def _gear_columns(out: ColumnBuilder, velocity: VelocityResult) -> None:
    for gear, over in ratio_pairs(out):
        top, bottom = velocity.polygon.rate_of(gear), velocity.polygon.rate_of(over)
        if top is None or bottom is None:
            continue
        turns = np.asarray(bottom != 0.0)
        out.add(f"ratio_{gear}_{over}", "ratio", np.asarray(top / np.where(turns, bottom, 1.0)), turns)


def higher_pair_columns(out: ColumnBuilder, velocity: VelocityResult | None, acceleration: AccelerationResult | None,
                        input_column: str) -> tuple[Follower, ...]:
    """The columns of the scene's cams and gears (none when it has neither); returns each cam's follower
    columns, for the s-v-a diagram."""
    followers = _cam_columns(out, velocity, acceleration, input_column) if out.mechanism.scene.cams else []
    if out.mechanism.scene.gears and velocity is not None:
        _gear_columns(out, velocity)
    return tuple(followers)
