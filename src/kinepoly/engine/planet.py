"""A planet on an arm that no input drives, placed by rolling on two known gears about the arm's pivot.

The arm turns about its pivot O on a known link; the planet turns on the arm about its pitch centre C and
meshes two known gears (a sun, a ring, a second sun) whose pitch centres lie on O. Neither link is placed by
a dyad or by one rolling pair: the two meshes together fix both (a planetary train with the sun or the ring
driven and the arm free, a differential with the sun and the ring driven). Every pitch point lies on the
line O C, at the angle phi of the arm's line. With the rule of ``engine.gears`` at each mesh k (known gear
K of radius R_k, the planet's pitch circle of radius rho_k, c_k = -1 external, +1 internal),

    rho_k delta_Pk = c_k R_k delta_K,   delta_K = phi + alpha_k - theta_K,   delta_Pk = phi + beta_k - theta_P,

alpha_k and beta_k the angles of the mesh's m (0 or pi from the arm's line) less each side's phase. With
g_k = c_k R_k / rho_k and the planet's two deltas apart by beta_B - beta_A (taken in (-pi, pi], as a gear
placed by rolling carries its delta on to its next mesh), delta_A solves one linear equation:

    (g_B - g_A) delta_A = (beta_B - beta_A) + g_B ((alpha_A - theta_A) - (alpha_B - theta_B) + 2 pi m),

then phi = delta_A - alpha_A + theta_A and theta_P = phi + beta_A - g_A delta_A. The whole number m (which
turn of one known gear against the other the train is in) is the one that takes both known gears' deltas
the shorter way at the scene's input (the least of |delta_A| and |delta_B| there), as a single known gear's
is; the known gears' angles are followed continuously over the rows of a sweep. This is Willis' formula:
its rates are (omega_Pk - omega_arm) rho_k = c_k R_k (omega_K - omega_arm).
"""

from __future__ import annotations

import math

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.gears import Rolled, anchor_row, free_delta, mesh
from kinepoly.engine.groups import NewtonGroup
from kinepoly.engine.placement import Placement
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import Reals
from kinepoly.geom.tolerances import ROUNDING_REL, SAME_REL
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.scene.spec import GearSpec, PitchCircle

__all__ = ["Planet", "place_planet", "planet_of"]


class Planet(Struct, frozen=True):
    """The arm (pinned at ``pivot`` to the known link ``base``), the planet (pinned to the arm at ``pin``, its
    pitch centre) and the two pairs it meshes known gears in."""

    arm: str
    planet: str
    base: str
    pivot: Revolute
    pin: Revolute
    meshes: tuple[GearSpec, GearSpec]


def planet_of(group: NewtonGroup) -> Planet | None:
    """The group as a planet on its arm, or None where it is not one."""
    if len(group.links) != 2 or group.drives or group.cams or len(group.gears) != 2 or len(group.joints) != 2:
        return None
    if not all(isinstance(j, Revolute) for j in group.joints):
        return None
    for arm, planet in (group.links, group.links[::-1]):
        pins = [j for j in group.joints if isinstance(j, Revolute) and set(j.links) == {arm, planet}]
        pivots = [j for j in group.joints if isinstance(j, Revolute) and arm in j.links and planet not in j.links]
        if len(pins) != 1 or len(pivots) != 1:
            continue
        meshes = [g for g in group.gears if planet in g.links and arm not in g.links]
        if len(meshes) != 2:
            continue
        if not all(isinstance(curve, PitchCircle) for g in meshes for curve in g.pitch):
            continue
        if any(_curve(g, planet).center != pins[0].point for g in meshes):
            continue
        base = next(x for x in pivots[0].links if x != arm)
        return Planet(arm, planet, base, pivots[0], pins[0], (meshes[0], meshes[1]))
    return None


def _curve(gear: GearSpec, link: str) -> PitchCircle:
    curve = gear.pitch[gear.links.index(link)]
    assert isinstance(curve, PitchCircle)
    return curve


def _not_built(mechanism: Mechanism, group: NewtonGroup, why: str) -> SceneError:
    pairs = ", ".join(g.name for g in group.gears)
    return SceneError(f"{mechanism.scene.source}:{group.gears[0].line}: gears.{group.gears[0].name}: links "
                      f"{', '.join(group.links)} hold gears ({pairs}) in a group that no dyad and no single pair "
                      f"places; {why}. This version places such a group only as a planet on an arm: the arm pinned "
                      "to a known link, the planet pinned to the arm at its pitch centre, meshing two known gears "
                      "centred on the arm's pivot (drive the arm, or another link of the group, otherwise)")


class _Mesh(Struct, frozen=True):
    """One mesh of the planet with a known gear: g = c R / rho, and alpha, beta (rad)."""

    known: str
    ratio: float
    alpha: float
    beta: float


def _mesh_terms(gear: GearSpec, planet: str) -> _Mesh:
    side = gear.links.index(planet)
    known = gear.links[1 - side]
    rho, big = _curve(gear, planet).radius, _curve(gear, known).radius
    sign = 1.0 if gear.internal else -1.0
    # m from the known gear's centre O (and from the planet's C) as an angle from the arm's line O C
    if not gear.internal:
        off_known, off_planet = 0.0, math.pi  # the pitch point between O and C
    else:
        off_known = off_planet = 0.0 if big > rho else math.pi  # m from the larger circle's centre to the point
    return _Mesh(known, sign * big / rho, off_known - gear.phase[1 - side], off_planet - gear.phase[side])


def place_planet(mechanism: Mechanism, group: NewtonGroup, placed: Placement) -> Placement:
    """The arm's and the planet's poses at every row, in closed form (see the module's text)."""
    found = planet_of(group)
    if found is None:
        raise _not_built(mechanism, group, "it is not such a planet")
    poses = placed.poses
    pivot = poses[found.base].world(mechanism.local(found.base, found.pivot.point))
    size = max((abs(v) for link in mechanism.link_names for p in mechanism.scene.link(link).points for v in p.local),
               default=1.0) or 1.0
    for gear in found.meshes:
        known = gear.links[1 - gear.links.index(found.planet)]
        centre = poses[known].world(mechanism.local(known, _curve(gear, known).center))
        if np.max(np.abs(centre - pivot)) > SAME_REL * size:
            raise _not_built(mechanism, group, f"the pitch centre {_curve(gear, known).center} of gear {known} "
                                               f"is not on the arm's pivot {found.pivot.point}")
    one, two = (_mesh_terms(g, found.planet) for g in found.meshes)
    if math.isclose(one.ratio, two.ratio, rel_tol=ROUNDING_REL):
        raise _not_built(mechanism, group, "its two meshes have the same ratio, so they do not fix the arm")
    theta_one = free_delta(mechanism, np.angle(poses[one.known].rotation), placed.values)
    theta_two = free_delta(mechanism, np.angle(poses[two.known].rotation), placed.values)
    d_beta = math.remainder(two.beta - one.beta, math.tau)
    gap = (one.alpha - theta_one) - (two.alpha - theta_two)
    scale = two.ratio - one.ratio

    def deltas(turns: Reals | float) -> tuple[Reals, Reals]:
        first = (d_beta + two.ratio * (gap + math.tau * turns)) / scale
        return np.asarray(first), np.asarray(first - gap - math.tau * turns)

    k = anchor_row(mechanism, placed.values)
    centre_turn = round(-float(gap[k]) / math.tau)
    turns = min(range(centre_turn - 3, centre_turn + 4),
                key=lambda m: max(abs(float(x[k])) for x in deltas(m)))
    delta_one, _ = deltas(turns)
    phi = delta_one - one.alpha + theta_one
    theta_planet = phi + one.beta - one.ratio * delta_one
    lever = (complex(*mechanism.local(found.arm, found.pin.point))
             - complex(*mechanism.local(found.arm, found.pivot.point)))
    arm_rotation = np.exp(1j * (phi - np.angle(lever)))
    arm = ArrayPose(np.asarray(pivot - arm_rotation * complex(*mechanism.local(found.arm, found.pivot.point))),
                    np.asarray(arm_rotation))
    centre = arm.world(mechanism.local(found.arm, found.pin.point))
    planet_rotation = np.exp(1j * theta_planet)
    planet = ArrayPose(np.asarray(centre - planet_rotation * complex(*mechanism.local(found.planet, found.pin.point))),
                       np.asarray(planet_rotation))
    out = {**poses, found.arm: arm, found.planet: planet}
    for gear in found.meshes:
        mesh(mechanism, gear, out)  # the centre distances: a clear error where the arm's length does not fit
    rolled = Rolled(np.asarray(one.ratio * delta_one), np.asarray(phi + one.beta))
    return replace(placed, poses=out, rolled={**placed.rolled, found.planet: rolled})
