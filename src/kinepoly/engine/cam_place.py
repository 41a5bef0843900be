"""A spline cam's follower placed at every row: the contacts found, one kept per row as the policy says.

``engine.cam_contact`` finds every contact at every row; the assembly policy (``engine.assembly``) keeps
the one nearest the ``[guess]`` (a solve) or follows the seed row's by continuity (a sweep), with the helpers
below. A row without any contact (the follower cannot reach the profile) and a row where a roller is larger
than the concave profile's radius at the contact (it cannot touch there: the profile would be undercut) are
the policy's to raise (a solve: exit 3) or to mark (a sweep). The contact point Q, the centre of curvature K
and the contact parameter of the kept contact are recorded for the polygons.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.cam_contact import (
    Candidates,
    Ints,
    cam_spline,
    centre_label,
    contact_candidates,
    contact_label,
    contact_rows,
    face_direction,
    face_parameter,
    offset_of,
)
from kinepoly.engine.cam_curves import curve_candidates, curve_contact_rows, degenerate_rows, follower_centre_label
from kinepoly.engine.groups import CamGroup, NewtonGroup
from kinepoly.engine.inputs import describe_input
from kinepoly.engine.placement import Failure, Placement
from kinepoly.engine.policy import Continuity, FamilyContinuity, NearestGuess, Policy
from kinepoly.errors import AssemblyError
from kinepoly.geom.arrays import Bools, Reals
from kinepoly.geom.spline import nearest_parameter
from kinepoly.model.mechanism import Mechanism, Revolute
from kinepoly.model.pose import LinkPose
from kinepoly.notice import Notice
from kinepoly.scene.spec import CamSpec

__all__ = ["CamQuestion", "floating_unreachable", "follow_contact", "guessed_contact", "place_cam",
           "place_floating_contacts", "seeded_contact"]

Vec = tuple[float, float]


def guessed_contact(mechanism: Mechanism, group: CamGroup, candidates: Candidates,
                    guess: Mapping[str, Vec]) -> tuple[Ints, tuple[Notice, ...]]:
    """Row by row, the contact that puts the follower's guessed points nearest their guess; with no point of
    the follower guessed, the first contact along the profile, with a ``default-assembly`` warning."""
    found, link = candidates.found, group.link
    name = group.cam.point or f"the contact of {group.cam.name}"
    score = np.zeros(found.shape)
    guessed = [p for p in mechanism.scene.link(link).points if p.name in guess]
    for p in guessed:
        at = candidates.origin + candidates.rotation * complex(*p.local)
        score += np.abs(at - complex(*guess[p.name])) ** 2
    score = np.where(found, score, np.inf)
    choice = np.where(found.any(axis=1), np.argmin(score, axis=1), -1)
    if guessed or found[0].sum() < 2:
        return choice, ()
    w = complex(candidates.w[0, int(choice[0])])
    others = ", ".join(f"({complex(z).real:.6g}, {complex(z).imag:.6g})"
                       for z, ok in zip(candidates.w[0], found[0], strict=True) if ok and complex(z) != w)
    return choice, (Notice("default-assembly", f"follower {link}: no [guess] tells its contacts with the cam apart, so "
                           f"the first along the profile was taken, which puts {name} at ({w.real:.6g}, {w.imag:.6g}); "
                           f"the others put it at {others} (give [guess] positions of the follower's points "
                           "near the ones you mean)"),)


def follow_contact(candidates: Candidates, seed_row: int, seed_choice: int) -> Ints:
    """From the seed row's contact, each row's contact nearest the row before it (W's place), forward and
    backward; -1 where a row has none (the next row follows the last one found)."""
    n = len(candidates.found)
    choice = np.full(n, -1, np.intp)
    choice[seed_row] = seed_choice
    for order in (range(seed_row + 1, n), range(seed_row - 1, -1, -1)):
        last = complex(candidates.w[seed_row, seed_choice])
        for row in order:
            if not candidates.found[row].any():
                continue
            gaps = np.where(candidates.found[row], np.abs(candidates.w[row] - last), np.inf)
            choice[row] = int(np.argmin(gaps))
            last = complex(candidates.w[row, choice[row]])
    return choice


class CamQuestion(Struct, frozen=True):
    """A spline cam's contacts at every row (``candidates``), one to keep per row: the cam kind's answers to the
    assembly policies (``engine.policy``)."""

    group: CamGroup
    candidates: Candidates

    def by_guess(self, policy: NearestGuess, mechanism: Mechanism,
                 placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """The contact that puts the follower's guessed points nearest their guess."""
        return guessed_contact(mechanism, self.group, self.candidates, policy.guess)

    def by_seed(self, policy: Continuity, mechanism: Mechanism,
                placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """The seed row's contact (where the solve puts W), followed by continuity."""
        candidates, row = self.candidates, policy.seed_row
        if not candidates.found[row].any():
            return follow_contact(candidates, row, 0), ()
        seed = seeded_contact(mechanism, self.group, candidates, row, policy.seed_poses())
        return follow_contact(candidates, row, seed), ()

    def by_label(self, policy: FamilyContinuity, mechanism: Mechanism,
                 placed: Placement) -> tuple[Ints, tuple[Notice, ...]]:
        """Not asked: a family with cams is refused (``sweep.family``)."""
        raise AssertionError(f"group {self.group.name}: a family with cams is not swept")


def seeded_contact(mechanism: Mechanism, group: CamGroup, candidates: Candidates, seed_row: int,
                   seed: Mapping[str, LinkPose]) -> int:
    """The seed row's contact: the one that puts the follower's points where the seed pose has them."""
    pose = seed[group.link]
    gaps = np.zeros(candidates.found.shape[1])
    for p in mechanism.scene.link(group.link).points:
        target = complex(*pose.world(p.local))
        gaps += np.abs(candidates.origin[seed_row] + candidates.rotation[seed_row] * complex(*p.local) - target) ** 2
    return int(np.argmin(np.where(candidates.found[seed_row], gaps, np.inf)))


def _where(mechanism: Mechanism, cam: CamSpec) -> str:
    """The start of a solve's message: the file, the pair, the input."""
    return f"{mechanism.scene.source}:{cam.line}: cams.{cam.name}: at {describe_input(mechanism)}, "


def _unreachable(group: CamGroup) -> str:
    """Why a row has no contact."""
    cam = group.cam
    joint = group.joint
    if cam.kind == "flat":
        return (f"follower {group.link} cannot touch cam {group.known}: no tangent of the profile runs at the face's "
                f"distance from the pivot {getattr(joint, 'point', '')}, so the face cannot be laid on the profile; "
                "move the pivot or the face toward the cam")
    path = (f"the circle W runs on about the pivot {joint.point}" if isinstance(joint, Revolute)
            else f"the line W slides along on {group.carrier}")
    if cam.is_curve_pair:
        return (f"follower {group.link} cannot touch cam {group.known}: held by its joint, its profile cannot be laid "
                "against the cam's profile from outside; move the follower's joint or its profile toward the cam")
    what = _what(cam)
    offset = _offset_words(cam)
    return (f"follower {group.link} cannot touch cam {group.known}: {path} misses the profile{offset}, so {what} "
            "cannot reach it; move the follower's joint or its point toward the cam")


def _what(cam: CamSpec) -> str:
    """The follower's point that runs on the (offset) profile, in words."""
    if cam.kind != "roller":
        return f"the knife edge {cam.point}"
    return (f"the centre {cam.point} of the follower's arc" if cam.follower_profile
            else f"the roller's centre {cam.point}")


def _offset_words(cam: CamSpec) -> str:
    if cam.kind != "roller":
        return ""
    return " offset by the arc's radius" if cam.follower_profile else " offset by the roller"


def _concave(cam: CamSpec, curvature: Reals, unit: str) -> Callable[[int], str]:
    """Why a row's contact cannot be touched: the concave radius there."""

    def why(row: int) -> str:
        radius = f"{1.0 / abs(float(curvature[row])):.6g} {unit}"
        if cam.kind == "flat":
            return (f"the flat face meets the profile where it is concave (radius {radius}): a flat face can touch "
                    "only a convex profile; make the profile convex there, or use a knife edge or a roller")
        if cam.follower_profile:
            return (f"the follower's arc of radius {cam.roller_radius:g} {unit} is larger than the profile's concave "
                    f"radius {radius} at the contact: it cannot touch the profile there; use a smaller arc or a "
                    "profile whose hollows are wider than the arc")
        return (f"the roller of radius {cam.roller_radius:g} {unit} is larger than the profile's concave radius "
                f"{radius} at the contact: it cannot touch the profile there; use a smaller roller or a profile "
                "whose hollows are wider than the roller")
    return why


def _undercut(cam: CamSpec, curvature: np.ndarray) -> Bools:
    """Rows where a roller is larger than the profile's concave radius at the contact, or a flat face
    touches a concave stretch (it would cut into the cam on both sides of the contact)."""
    concave = -curvature if not cam.inside else curvature
    if cam.kind == "flat":
        return np.asarray(concave > 0.0)
    if cam.kind != "roller":
        return np.zeros(len(curvature), np.bool_)
    return np.asarray(concave * cam.roller_radius >= 1.0)


def place_cam(mechanism: Mechanism, group: CamGroup, placed: Placement, policy: Policy) -> Placement:
    """The follower of ``group`` placed on its cam at every row, with its contact recorded."""
    cam = group.cam
    curves = curve_candidates(mechanism, group, placed.poses) if cam.is_curve_pair else None
    candidates = contact_candidates(mechanism, group, placed.poses) if curves is None else curves.candidates
    ok, failures = placed.ok, placed.failures
    missing = ok & ~candidates.found.any(axis=1)
    if missing.any():
        policy.cannot_close(lambda: AssemblyError(_where(mechanism, cam) + _unreachable(group)))
        failures = (*failures, Failure(group.name, cam.point or "", missing, lambda _: _unreachable(group)))
        ok = ok & ~missing
    choice, notices = policy.assemble(mechanism, CamQuestion(group, candidates), replace(placed, ok=ok))
    u = candidates.parameter(choice)
    placed = replace(placed, poses={**placed.poses, group.link: candidates.pose(choice)}, ok=ok, failures=failures,
                     notices=(*placed.notices, *notices))
    placed = _recorded(mechanism, group.name, cam, u, placed, policy)
    if curves is None:
        return placed
    return _curve_recorded(mechanism, group.name, cam, u, curves.follower_parameter(choice), placed, policy)


def _curve_recorded(mechanism: Mechanism, group: str, cam: CamSpec, u: Reals, v: Reals, placed: Placement,
                    policy: Policy) -> Placement:
    """Two splines in contact: the follower profile's centre of curvature K2 marked, the rows where the
    curvatures leave no link between both centres raised or marked."""
    rows = curve_contact_rows(cam, placed.poses[cam.cam], placed.poses[cam.follower], u, v)
    bad, why = degenerate_rows(cam, rows)
    ok, failures = placed.ok, placed.failures
    bad = ok & bad
    if bad.any():
        policy.cannot_close(lambda: AssemblyError(_where(mechanism, cam) + why))
        failures = (*failures, Failure(group, follower_centre_label(cam), bad, lambda _: why))
        ok = ok & ~bad
    return replace(placed, ok=ok, failures=failures,
                   marks={**placed.marks, follower_centre_label(cam): rows.centre})


def _recorded(mechanism: Mechanism, group: str, cam: CamSpec, u: Reals, placed: Placement,
              policy: Policy) -> Placement:
    """The kept contact at parameters ``u`` recorded (Q, K and u), its undercut rows raised or marked."""
    rows = contact_rows(cam, placed.poses[cam.cam], u)
    ok, failures = placed.ok, placed.failures
    undercut = ok & _undercut(cam, rows.curvature)
    if undercut.any():
        why = _concave(cam, rows.curvature, mechanism.scene.units.length)
        policy.cannot_close(lambda: AssemblyError(_where(mechanism, cam) + why(int(np.flatnonzero(undercut)[0]))))
        failures = (*failures, Failure(group, cam.point or "", undercut, why))
        ok = ok & ~undercut
    marks = {**placed.marks, centre_label(cam): rows.centre, contact_label(cam): rows.point}
    return replace(placed, ok=ok, failures=failures, marks=marks,
                   contact_parameters={**placed.contact_parameters, cam.name: u})


def floating_unreachable(group: NewtonGroup) -> str:
    """Why a group with a floating follower on a spline cam does not close (empty without such a follower)."""
    def why(cam: CamSpec) -> str:
        if cam.kind == "flat":
            return (f"; or follower {cam.follower} cannot touch cam {cam.cam}: with the group's joints held, its flat "
                    "face cannot be laid along a tangent of the profile; move the follower's joints or its face "
                    "toward the cam")
        return (f"; or follower {cam.follower} cannot touch cam {cam.cam}: with the group's joints held, {_what(cam)} "
                f"cannot reach the profile{_offset_words(cam)}; move the follower's joints or its point toward the cam")
    return "".join(why(cam) for cam in group.cams)


def place_floating_contacts(mechanism: Mechanism, group: NewtonGroup, placed: Placement,
                            policy: Policy) -> Placement:
    """The contacts of the spline cams whose follower floats in ``group`` (closed by Newton with the contact's
    parameter as an unknown): each row's parameter is W's foot on the offset curve (a flat face: where the
    profile's tangent runs along the face), recorded as for a held follower."""
    for cam in group.cams:
        follower, cam_pose = placed.poses[cam.follower], placed.poses[cam.cam]
        if cam.kind == "flat":
            assert cam.flat is not None
            at = cam_pose.to_local(follower.world(cam.flat[0]))
            along = face_direction(placed.poses, cam) * cam_pose.rotation.conjugate()
            u = np.array([face_parameter(cam, complex(e), complex(z)) if ok else 0.0
                          for z, e, ok in zip(at, along, placed.ok, strict=True)])
        else:
            at = cam_pose.to_local(follower.world(mechanism.local(cam.follower, cam.point or "")))
            spline, rho = cam_spline(cam), offset_of(cam)
            u = np.array([nearest_parameter(spline, complex(z), rho) if ok else 0.0
                          for z, ok in zip(at, placed.ok, strict=True)])
        placed = _recorded(mechanism, group.name, cam, u, placed, policy)
    return placed
