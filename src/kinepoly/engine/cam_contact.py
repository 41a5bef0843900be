"""A spline cam's follower placed on the known cam: the contact found by a 1-D root on the spline parameter.

The profile is the periodic cubic spline P(u) of the ``points`` (``geom.spline``), in the cam's frame, n(u)
its left normal (inward: the points run counter-clockwise). The follower touches it with the point W (a knife
edge) or with a roller of radius r turning on W, so that W runs on the offset curve

    X(u) = P(u) + rho n(u),   rho = 0 (knife), -r (a roller outside the profile), +r (inside a groove).

The follower is held by ONE joint to a known carrier, so W has one freedom left, and the contact is where
W's path on the carrier, seen in the cam's frame, crosses X:

* a pivoted rocker (a pin at Q): |X(u) - Q| = |Q W|, W then at X(u), the rocker turned to it;
* a translating follower (the block of a slider on the carrier): X(u) on the line W travels along,
  s read off along the slide.

A flat face touches where the profile's tangent runs along the face, the cam on the face's left: a
translating face keeps its direction (tangent(u) parallel to it), a rocker's face keeps its distance h from
the pivot Q (the tangent line at P(u) passes h from Q), the follower then turned to the tangent.

Each row has every root (``geom.spline.roots_by_row``, all rows at once); the assembly policy keeps one per row
(nearest the ``[guess]`` for a solve, followed by continuity in a sweep). The centre of curvature K = P + n / kappa (the
same for the offset curve) is a point of the cam at that instant: the equivalent link K W replaces the pair
for the polygons (``engine.cam_polygons``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from functools import lru_cache

import numpy as np
import numpy.typing as npt
from msgspec import Struct

from kinepoly.engine.groups import CamGroup
from kinepoly.engine.polygon import Polygon
from kinepoly.engine.steps import Step
from kinepoly.errors import SceneError
from kinepoly.geom.arrays import Bools, Points, Reals, turn
from kinepoly.geom.spline import PeriodicSpline, nearest_parameter, periodic_spline, roots_by_row
from kinepoly.geom.tolerances import LAST_BITS_REL, PARALLEL_SIN
from kinepoly.geom.vec import magnitude
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import CamSpec, SliderSpec, Vector

__all__ = [
    "Candidates",
    "ProfileContactRows",
    "cam_spline",
    "centre_label",
    "contact_candidates",
    "contact_label",
    "contact_on_profile",
    "contact_rows",
    "face_direction",
    "face_parameter",
    "offset_of",
    "parameter_at",
    "parameter_near",
    "record_spline_equivalent",
]

Ints = npt.NDArray[np.intp]


def centre_label(cam: CamSpec) -> str:
    """The mark of the profile's centre of curvature at the contact: ``K23`` (a circle cam's centre is K too)."""
    return f"K{cam.name}"


def contact_label(cam: CamSpec) -> str:
    """The mark of the contact point: ``Q23``."""
    return f"Q{cam.name}"


@lru_cache(maxsize=64)
def _spline(points: tuple[Vector, ...]) -> PeriodicSpline:
    return periodic_spline(points)


def cam_spline(cam: CamSpec) -> PeriodicSpline:
    """The profile's spline (made once per profile)."""
    return _spline(cam.profile_points)


def offset_of(cam: CamSpec) -> float:
    """rho: how far W's curve lies along the inward normal from the profile."""
    if cam.kind != "roller":
        return 0.0
    return cam.roller_radius if cam.inside else -cam.roller_radius


def _offset_point(spline: PeriodicSpline, rho: float, u: Reals) -> Points:
    frame = spline.frame(u)
    return np.asarray(frame.point + rho * frame.normal)


class Candidates(Struct, frozen=True):
    """Every contact at every row, padded to ``width`` columns: the parameter, whether it exists, and the
    follower's pose each one gives (``origin``, ``rotation``), with W's place."""

    u: Reals
    found: Bools
    origin: Points
    rotation: Points
    w: Points

    def pose(self, choice: Ints) -> ArrayPose:
        rows = np.arange(len(choice))
        pick = np.maximum(choice, 0)
        return ArrayPose(np.asarray(self.origin[rows, pick]), np.asarray(self.rotation[rows, pick]))

    def parameter(self, choice: Ints) -> Reals:
        return np.asarray(self.u[np.arange(len(choice)), np.maximum(choice, 0)])


def _path_function(group: CamGroup, mechanism: Mechanism, cam_pose: ArrayPose,
                   carrier_pose: ArrayPose) -> tuple[Points, Points, float | None]:
    """W's path on the carrier, in the cam's frame, at every row: (point, direction, None) for a line
    (the point W at s = 0), (pivot, 0, radius) for a circle."""
    follower = group.link
    w_local = mechanism.local(follower, group.cam.point or "")
    joint = group.joint
    if isinstance(joint, Revolute):
        pivot = carrier_pose.world(mechanism.local(group.carrier, joint.point))
        px, py = mechanism.local(follower, joint.point)
        radius = math.hypot(w_local[0] - px, w_local[1] - py)
        return cam_pose.to_local(pivot), np.zeros(len(pivot), np.complex128), radius
    origin, rotation = _slid(mechanism, group, carrier_pose, np.zeros((len(carrier_pose.origin), 1)))
    start = origin[:, 0] + rotation[:, 0] * complex(*w_local)
    return cam_pose.to_local(start), np.asarray(rotation[:, 0] * cam_pose.rotation.conjugate()), None


def _packed(rows: Ints, roots: Reals, n: int) -> tuple[Reals, Bools]:
    """The roots of each row side by side, padded: (u, found), ``n`` rows."""
    counts = np.bincount(rows, minlength=n)
    width = max(1, int(counts.max(initial=0)))
    rank = np.arange(len(rows)) - np.concatenate(([0], np.cumsum(counts)))[rows]
    u = np.zeros((n, width))
    found = np.zeros((n, width), np.bool_)
    u[rows, rank] = roots
    found[rows, rank] = True
    return u, found


def contact_candidates(mechanism: Mechanism, group: CamGroup, poses: dict[str, ArrayPose]) -> Candidates:
    """Every contact of the pair at every row, with the follower's pose each gives."""
    if group.cam.kind == "flat":
        return _flat_candidates(mechanism, group, poses)
    cam, spline, rho = group.cam, cam_spline(group.cam), offset_of(group.cam)
    cam_pose, carrier_pose = poses[group.known], poses[group.carrier]
    start, direction, radius = _path_function(group, mechanism, cam_pose, carrier_pose)
    n = len(start)
    if radius is not None:
        def gap(row: Ints, u: Reals) -> Reals:
            return np.asarray(np.abs(_offset_point(spline, rho, u) - start[row]) ** 2 - radius * radius)
    else:
        def gap(row: Ints, u: Reals) -> Reals:
            return np.asarray(((_offset_point(spline, rho, u) - start[row]) * direction[row].conjugate()).imag)
    u, ok = _packed(*roots_by_row(spline, gap, n), n)
    x_cam = _offset_point(spline, rho, u)
    w = np.asarray(cam_pose.origin[:, None] + cam_pose.rotation[:, None] * x_cam)
    w_local = complex(*mechanism.local(group.link, cam.point or ""))
    joint = group.joint
    if isinstance(joint, Revolute):
        pivot_local = complex(*mechanism.local(group.link, joint.point))
        pivot = carrier_pose.world(mechanism.local(group.carrier, joint.point))[:, None]
        arm = w - pivot
        rotation = np.asarray((arm / np.where(arm == 0, 1.0, np.abs(arm))) / ((w_local - pivot_local)
                                                                              / abs(w_local - pivot_local)))
        origin = np.asarray(pivot - rotation * pivot_local)
    else:
        s = ((x_cam - start[:, None]) * direction.conj()[:, None]).real
        origin, rotation = _slid(mechanism, group, carrier_pose, s)
    return Candidates(u, ok, origin, rotation, w)


def _slid(mechanism: Mechanism, group: CamGroup, carrier_pose: ArrayPose, s: Reals) -> tuple[Points, Points]:
    """A translating follower's poses (origin, rotation) at slide values ``s`` (rows x candidates)."""
    joint = group.joint
    assert isinstance(joint, SliderSpec)
    rotation = np.asarray(np.broadcast_to((carrier_pose.rotation * turn(joint.angle_rad))[:, None], s.shape))
    on_line = carrier_pose.world(joint.through)[:, None] + s * rotation
    return np.asarray(on_line - rotation * complex(*mechanism.local(group.link, joint.point))), rotation


def _flat_candidates(mechanism: Mechanism, group: CamGroup, poses: dict[str, ArrayPose]) -> Candidates:
    """A flat face touches where the profile's tangent runs along the face (the cam on the face's left):
    a translating follower's face turns with its guide, so the tangent's direction is known; a rocker's
    face keeps its distance h from the pivot, so the tangent line at P(u) must pass h from it."""
    cam, spline = group.cam, cam_spline(group.cam)
    assert cam.flat is not None
    (fx, fy), face_angle = cam.flat
    face_local, along_local = complex(fx, fy), turn(face_angle)
    cam_pose, carrier_pose = poses[group.known], poses[group.carrier]
    n = len(cam_pose.origin)
    joint = group.joint
    if isinstance(joint, Revolute):
        pivot_local = complex(*mechanism.local(group.link, joint.point))
        pivot = carrier_pose.world(mechanism.local(group.carrier, joint.point))
        pivot_cam = cam_pose.to_local(pivot)
        h = ((face_local - pivot_local) * along_local.conjugate()).imag

        def gap(row: Ints, u: Reals) -> Reals:
            frame = spline.frame(u)
            return np.asarray(((frame.point - pivot_cam[row]) * frame.tangent.conjugate()).imag - h)
        u, ok = _packed(*roots_by_row(spline, gap, n), n)
        frame = spline.frame(u)
        rotation = np.asarray(cam_pose.rotation[:, None] * frame.tangent / along_local)
        origin = np.asarray(pivot[:, None] - rotation * pivot_local)
    else:
        assert isinstance(joint, SliderSpec)
        along_cam = np.asarray(carrier_pose.rotation * turn(joint.angle_rad) * along_local
                               * cam_pose.rotation.conjugate())

        def gap(row: Ints, u: Reals) -> Reals:
            return np.asarray((spline.frame(u).tangent * along_cam[row].conjugate()).imag)
        u, ok = _packed(*roots_by_row(spline, gap, n), n)
        frame = spline.frame(u)
        ok &= (frame.tangent * along_cam[:, None].conjugate()).real > 0.0  # the same sense: the cam on the left
        across = along_local.conjugate().imag  # Im(conj(d) e), e the block's x-axis along the slide
        if abs(across) < PARALLEL_SIN:
            raise SceneError(f"{mechanism.scene.source}:{cam.line}: cams.{cam.name}: the flat face runs along the "
                             f"slide of {joint.name}, so the cam cannot move the follower; expected a "
                             "face across the slide")
        zero = np.zeros((n, 1))
        start_origin, start_rotation = _slid(mechanism, group, carrier_pose, zero)
        face_world = start_origin + start_rotation * face_local
        point = cam_pose.origin[:, None] + cam_pose.rotation[:, None] * frame.point
        direction = start_rotation * along_local
        s = ((point - face_world) * direction.conjugate()).imag / across
        origin, rotation = _slid(mechanism, group, carrier_pose, np.asarray(s))
    point = np.asarray(cam_pose.origin[:, None] + cam_pose.rotation[:, None] * frame.point)
    return Candidates(u, ok, origin, rotation, point)


class ProfileContactRows(Struct, frozen=True):
    """The chosen contact at every row, in the frame: the parameter, the contact point Q, the centre of
    curvature K, the unit normal from the cam's side to the follower's, the curvature (1/length, positive
    where the profile is convex) and whether K is at infinity (a straight stretch)."""

    u: Reals
    point: Points
    centre: Points
    normal: Points
    curvature: Reals
    straight: Bools


def contact_rows(cam: CamSpec, cam_pose: ArrayPose, u: Reals) -> ProfileContactRows:
    """The contact at parameters ``u`` with the cam at ``cam_pose``."""
    frame = cam_spline(cam).frame(u)
    point = cam_pose.world((0.0, 0.0)) + cam_pose.rotation * frame.point
    centre = cam_pose.world((0.0, 0.0)) + cam_pose.rotation * frame.centre_of_curvature
    outward = -frame.normal if not cam.inside else frame.normal
    return ProfileContactRows(u, np.asarray(point), np.asarray(centre), np.asarray(cam_pose.rotation * outward),
                       frame.curvature, frame.is_straight)


def face_direction(poses: Mapping[str, ArrayPose], cam: CamSpec) -> Points:
    """A flat face's unit direction in the frame at every row (it turns with the follower)."""
    assert cam.flat is not None
    return np.asarray(poses[cam.follower].rotation * turn(cam.flat[1]))


def face_parameter(cam: CamSpec, along: complex, through: complex) -> float:
    """Where a flat face touches the profile: the parameter whose tangent runs along the face (unit direction
    ``along``, the same sense: the cam on the face's left) nearest the face's line through ``through``, both
    in the cam's frame. The best of a dense sampling, settled by Newton's method on Im(conj(along) r'(u)) = 0."""
    spline = cam_spline(cam)
    count = _FACE_SAMPLES_PER_PIECE * spline.pieces
    grid = spline.period * np.arange(count) / count
    frame = spline.frame(grid)
    sine = (frame.tangent * along.conjugate()).imag
    gap = ((frame.point - through) * along.conjugate()).imag
    size = float(np.abs(frame.point - frame.point.mean()).max())
    score = np.where((frame.tangent * along.conjugate()).real > 0.0, np.abs(sine) * size + np.abs(gap), np.inf)
    u = float(grid[int(np.argmin(score))])
    for _ in range(_FACE_STEPS):
        _, first, second = (complex(z[0]) for z in spline.derivatives(np.array([u])))
        slope = (second * along.conjugate()).imag
        if slope == 0.0:
            break
        step = (first * along.conjugate()).imag / slope
        u -= step
        if abs(step) <= LAST_BITS_REL * spline.period:
            break
    return u % spline.period


_FACE_SAMPLES_PER_PIECE = 16
_FACE_STEPS = 30


def parameter_near(cam: CamSpec, local: complex) -> float:
    """The parameter of the profile's point nearest ``local`` (a point on the profile, in the cam's frame)."""
    return nearest_parameter(cam_spline(cam), local)

def parameter_at(cam: CamSpec, pose: Pose) -> float:
    """The contact's parameter on the profile at one row, from the contact point Q marked when the follower
    was placed."""
    link = pose.links[cam.cam]
    rotation = complex(math.cos(link.theta), math.sin(link.theta))
    local = (complex(*pose.marks[contact_label(cam)]) - complex(link.x, link.y)) * rotation.conjugate()
    return parameter_near(cam, local)


def contact_on_profile(cam: CamSpec, pose: Pose) -> tuple[complex, complex]:
    """The contact point and the unit normal there, from the cam's side to the follower's, at one row."""
    found = contact_rows(cam, ArrayPose.of_rows([pose.links[cam.cam]]), np.array([parameter_at(cam, pose)]))
    return complex(found.point[0]), complex(found.normal[0])


def record_spline_equivalent(polygon: Polygon, cam: CamSpec) -> None:
    """The step that says the pair is replaced, at this instant, by the link K W (K the centre of curvature),
    or for a flat face by a block pinned at K sliding on the follower parallel to the face."""
    k = centre_label(cam)
    if k not in polygon.positions.marks:
        return
    w = (f"K2{cam.name}" if cam.is_curve_pair else cam.point) or contact_label(cam)  # K2: engine.cam_curves
    length = magnitude(complex(polygon.world(w)[0]) - complex(polygon.world(k)[0]))
    flat = cam.kind == "flat"
    polygon.step(Step(polygon="velocity", kind="known",
                      equation=(f"cam {cam.name}: equivalent block {k} pinned at {k}, sliding on {cam.follower}" if flat
                                else f"cam {cam.name}: equivalent link {k}{w} from {k} to {w}"),
                      result=k if flat else f"{k}{w}", topic="equivalent-link",
                      params=(("pair", cam.name), ("cam", cam.cam), ("follower", cam.follower),
                              ("link", k if flat else f"{k}{w}"), ("centre", k), ("point", w), ("length", length),
                              ("kind", cam.kind), ("spline", "yes"))))
