"""The geometry of the circle diagram's plan: joint centers from the pose, then each Kennedy step.

Every center is a projective value (``geom.homogeneous``) in a frame local to the mechanism: a
pin is a point, a slider's center the point at infinity perpendicular to its slide. A derived
center I_ij is the crossing of the lines I_ik I_jk and I_il I_jl; of all the triangles that
close edge ij with centers already known, the pair whose crossing has the smallest estimated
error is taken. A pair is unusable when the two centers of a line coincide or the two lines are
one line; when no pair is usable the position is degenerate (SingularityError naming them).
Where the planned path is blocked so, one more center is derived if it opens other triangles.

A cam pair is a line edge: the common normal at its contact (from ``engine.contacts``, the one
computation of the contact, on a batch of one row) is known at once as a line through the contact
C and its direction at infinity. Its center I_ij is where the Kennedy line I_ik I_jk of one
triangle crosses that normal, the best-conditioned triangle again; a Kennedy line that is the
normal itself is unusable. Once found, I_ij is a center like any other.

A step is reported with a ``center-ill-conditioned`` warning when one of its products has a sine
below NEAR_SINGULAR_SIN (two centers almost one point, two lines almost one line) or the center's
estimated relative error exceeds LOUD_ERROR (a crossing so far away that its distance lost digits).
"""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np
from msgspec import Struct
from msgspec.structs import replace

from kinepoly.engine.cam_contact import parameter_at
from kinepoly.engine.center_values import CenterPlan, InstantCenter, KennedyLine, KennedyStep
from kinepoly.engine.circle_diagram import (
    CircleDiagram,
    DiagramEdge,
    Edge,
    center_label,
    circle_positions,
    edge,
    pair_name,
    split_pair,
    triangle_name,
)
from kinepoly.engine.contacts import contacts_over_rows
from kinepoly.engine.gears import mesh
from kinepoly.engine.inputs import describe_input
from kinepoly.errors import SingularityError
from kinepoly.geom.homogeneous import LocalFrame, Place, Projective, Wedge, canonical_direction, wedge
from kinepoly.geom.tolerances import LOUD_ERROR, NEAR_SINGULAR_SIN
from kinepoly.geom.vec import Vec, add, cross, dot, norm, perp, rotate, sub
from kinepoly.model.array_pose import ArrayPose
from kinepoly.model.mechanism import Joint, Mechanism, Revolute
from kinepoly.model.pose import Pose
from kinepoly.notice import Notice
from kinepoly.scene.spec import CamSpec, GearSpec

__all__ = ["KennedyResult", "derive_centers"]


class KennedyResult(Struct, frozen=True):
    """The centers found (as reported, and in the pose's own coordinates), the steps, the diagram."""

    centers: dict[Edge, InstantCenter]
    inside: dict[Edge, InstantCenter]
    steps: tuple[KennedyStep, ...]
    diagram: CircleDiagram
    notices: tuple[Notice, ...]
    size: float


class _Known(Struct, frozen=True):
    """A center found: its projective value, its place in the pose's own coordinates, the reported center."""

    value: Projective
    inside: Place
    center: InstantCenter


class _Line(Struct, frozen=True):
    """A Kennedy line that may carry a center: through the known centers of ``sides``, the two edges that
    close a triangle with the sought one at the ``third`` link; ``join`` is the line through them."""

    third: str
    sides: tuple[Edge, Edge]
    join: Wedge


class _Candidate(Struct, frozen=True):
    """Two Kennedy lines that cross at the center, or (a cam pair's center) one and the common normal."""

    first: _Line
    second: _Line | _Normal
    meet: Wedge


def _frame(mechanism: Mechanism, pose: Pose, offset: Vec) -> LocalFrame:
    """Origin at the middle of the solved links' points, size their largest distance from it."""
    points = [pose.links[k].world(p.local) for k in pose.links for p in mechanism.scene.link(k).points]
    xs, ys = [p[0] for p in points], [p[1] for p in points]
    origin = ((min(xs) + max(xs)) / 2.0, (min(ys) + max(ys)) / 2.0)
    size = max((norm(sub(p, origin)) for p in points), default=0.0)
    return LocalFrame(origin, size if size > 0.0 else 1.0, offset)


def _joint_center(mechanism: Mechanism, pose: Pose, frame: LocalFrame,
                  joint: Joint | GearSpec) -> tuple[Projective, Place] | None:
    """A pin's point, the point at infinity perpendicular to a slide, or a gear pair's pitch point; None
    when its links were not solved."""
    if isinstance(joint, GearSpec):
        if not all(link in pose.links for link in joint.links):
            return None
        arrays = {link: ArrayPose.of_rows([pose.links[link]]) for link in joint.links}
        pitch = complex(mesh(mechanism, joint, arrays).point[0])
        value = frame.point((pitch.real, pitch.imag))
        return value, Place((pitch.real, pitch.imag), None, value.error)
    if isinstance(joint, Revolute):
        owner = next((link for link in joint.links if link in pose.links), None)
        if owner is None:
            return None
        at = pose.links[owner].world(mechanism.local(owner, joint.point))
        value = frame.point(at)
        return value, Place(at, None, value.error)
    if joint.guide in pose.links:
        slide = rotate((1.0, 0.0), pose.links[joint.guide].theta + joint.angle_rad)
    elif joint.block in pose.links:
        slide = rotate((1.0, 0.0), pose.links[joint.block].theta)
    else:
        return None
    value = frame.point_at_infinity(perp(slide))
    return value, Place(None, canonical_direction(perp(slide)), value.error)


class _Normal(Struct, frozen=True):
    """A cam pair's line edge: the common normal at the contact, as the contact C and the normal's
    direction (both in the pose's own coordinates) and as a projective line."""

    contact: str
    at: Vec
    direction: Vec
    line: Projective


def _common_normals(mechanism: Mechanism, pose: Pose, frame: LocalFrame) -> dict[str, _Normal]:
    """Each cam's common normal at its contact, by the contacts' one computation on a batch of one row;
    a cam whose links were not solved has none."""
    poses = {link: ArrayPose.of_rows([pose.links[link]]) for link in pose.links}
    parameters = {cam.name: np.array([parameter_at(cam, pose)]) for cam in mechanism.scene.cams
                  if cam.is_spline and cam.cam in pose.links and cam.follower in pose.links}
    found = contacts_over_rows(mechanism, poses, None, parameters)
    out = {}
    for cam in mechanism.scene.cams:
        if cam.name not in found:
            continue
        at, n = complex(found[cam.name].point[0]), complex(found[cam.name].normal[0])
        line = wedge(frame.point((at.real, at.imag)), frame.point_at_infinity((n.real, n.imag))).value
        assert line is not None  # a finite point and a point at infinity are never one point
        out[cam.name] = _Normal(f"C{cam.name}", (at.real, at.imag), (n.real, n.imag), line)
    return out


def _joint_name(joint: Joint | GearSpec | CamSpec) -> str:
    if isinstance(joint, CamSpec):
        return f"common normal of cam {joint.name}"
    if isinstance(joint, GearSpec):
        return f"pitch point of gears {joint.name}"
    return f"pin {joint.point}" if isinstance(joint, Revolute) else f"slider {joint.name}"


class _Finder:
    """Mutable while the centers are derived; its output is frozen into InstantCenters."""

    def __init__(self, mechanism: Mechanism, pose: Pose, plan: CenterPlan, offset: Vec) -> None:
        self.mechanism, self.pose, self.plan = mechanism, pose, plan
        self.links = plan.kennedy.links
        self.frame = _frame(mechanism, pose, offset)
        self.known: dict[Edge, _Known] = {}
        self.normals: dict[Edge, _Normal] = {}
        self.steps: list[KennedyStep] = []
        self.notices: list[Notice] = []
        self.via: dict[Edge, str] = {}
        normals = _common_normals(mechanism, pose, self.frame) if mechanism.scene.cams else {}
        for e, joint in plan.joints.items():
            if isinstance(joint, CamSpec):
                if joint.name in normals:
                    self.normals[e] = normals[joint.name]
                continue
            found = _joint_center(mechanism, pose, self.frame, joint)
            if found is not None:
                value, inside = found
                place = inside if inside.position is None else replace(inside, position=add(offset, inside.position))
                self.known[e] = _Known(value, inside, InstantCenter(e, place, _joint_name(joint), 0))

    def where(self) -> str:
        return f"at {describe_input(self.mechanism)}"

    def label(self, e: Edge) -> str:
        return center_label(pair_name(e))

    # -- one derived center -----------------------------------------------------------------
    def lines_for(self, e: Edge) -> tuple[list[_Line], list[str]]:
        i, j = e
        lines, trouble = [], []
        for k in self.links:
            if k in e:
                continue
            sides = (edge(i, k, self.links), edge(j, k, self.links))
            if sides[0] not in self.known or sides[1] not in self.known:
                continue
            join = wedge(self.known[sides[0]].value, self.known[sides[1]].value)
            if join.value is None:
                trouble.append(f"{self.label(sides[0])} and {self.label(sides[1])} coincide, so no line runs "
                               f"through them (triangle {triangle_name(self.links, i, j, k)})")
            lines.append(_Line(k, sides, join))
        return lines, trouble

    def derive(self, e: Edge) -> tuple[_Candidate | None, list[str]]:
        """The best-conditioned crossing that finds ``e``: of two Kennedy lines, or for a cam pair's center
        of one Kennedy line with the common normal at the contact."""
        lines, trouble = self.lines_for(e)
        usable = [line for line in lines if line.join.value is not None]
        normal = self.normals.get(e)
        pairs: list[tuple[_Line, _Line | _Normal]] = (
            [(line, normal) for line in usable] if normal is not None else list(combinations(usable, 2)))
        best: _Candidate | None = None
        for first, second in pairs:
            assert first.join.value is not None
            meet = wedge(first.join.value, _line_value(second))
            if meet.value is None:
                trouble.append(f"the Kennedy line {self.line_label(first)} is the common normal at "
                               f"{second.contact} itself, so they meet in no single point"
                               if isinstance(second, _Normal)
                               else f"the Kennedy lines {self.line_label(first)} and {self.line_label(second)} are "
                               "one line (all four centers lie on it), so they meet in no single point")
                continue
            if best is None or meet.value.error < (best.meet.value.error if best.meet.value else math.inf):
                best = _Candidate(first, second, meet)
        if len(lines) < (1 if normal is not None else 2):
            trouble.append("fewer than two triangles of known centers close it yet" if normal is None
                           else "fewer triangles of known centers than the one its common normal needs close it yet")
        return best, trouble

    def line_label(self, line: _Line | _Normal) -> str:
        if isinstance(line, _Normal):
            return f"n({line.contact})"
        return f"{self.label(line.sides[0])} {self.label(line.sides[1])}"

    def record(self, e: Edge, candidate: _Candidate) -> None:
        assert candidate.meet.value is not None
        number = len(self.steps) + 1
        place = self.frame.place(candidate.meet.value)
        center = InstantCenter(e, place, f"Kennedy step {number}", number)
        inside = replace(self.frame, offset=(0.0, 0.0)).place(candidate.meet.value)
        self.known[e] = _Known(candidate.meet.value, inside, center)
        i, j = e
        second = candidate.second
        triangles = tuple(triangle_name(self.links, i, j, line.third) for line in (candidate.first, second)
                          if isinstance(line, _Line))
        if isinstance(second, _Normal):
            cam = self.plan.joints[e]
            assert isinstance(cam, CamSpec)
            self.via[e] = f"common normal of cam {cam.name} and triangle {triangles[0]}"
        else:
            self.via[e] = f"triangles {triangles[0]} and {triangles[1]}"
        lines = (self.kennedy_line(candidate.first), self.kennedy_line(second))
        sin_angle = _planar_sin(lines[0], lines[1])
        conditioning = min(candidate.first.join.sin, _join_sin(second), candidate.meet.sin)
        equation = f"{center.label} = ({lines[0].label}) x " + (
            lines[1].label if lines[1].is_common_normal else f"({lines[1].label})")
        self.steps.append(KennedyStep(number, center.name, triangles, lines, place.homogeneous, sin_angle,
                                      conditioning, place.relative_error, equation))
        if conditioning < NEAR_SINGULAR_SIN or place.relative_error > LOUD_ERROR:
            self.notices.append(Notice("center-ill-conditioned", self.ill_text(center, candidate, lines, sin_angle)))

    def kennedy_line(self, line: _Line | _Normal) -> KennedyLine:
        if isinstance(line, _Normal):
            at = add(self.frame.offset, line.at)
            return KennedyLine("", (), ((at[0], at[1], 1.0), (line.direction[0], line.direction[1], 0.0)),
                               at, line.direction, line.contact)
        assert line.join.value is not None
        a, b = (self.known[s].center for s in line.sides)
        placed = self.frame.line(line.join.value)
        through: Vec | None = None
        direction: Vec | None = None
        if placed is not None:
            through, direction = placed
            if a.position is not None:  # a point of the line a reader can find: the first finite center
                through = a.position
            elif b.position is not None:
                through = b.position
            if a.position is not None and b.position is not None and dot(direction, sub(b.position, a.position)) < 0:
                direction = (-direction[0], -direction[1])
        return KennedyLine(line.third, (a.name, b.name), (a.homogeneous, b.homogeneous), through, direction)

    def ill_text(self, center: InstantCenter, candidate: _Candidate, lines: tuple[KennedyLine, KennedyLine],
                 sin_angle: float | None) -> str:
        what = "direction" if center.is_at_infinity else "position"
        tail = f"its {what} has a relative error of about {center.place.relative_error:.1g}"
        worst = min((candidate.first.join.sin, f"the centers {self.line_label(candidate.first)} almost coincide"),
                    (_join_sin(candidate.second), f"the centers {self.line_label(candidate.second)} almost coincide"),
                    (candidate.meet.sin, f"the Kennedy lines {lines[0].label} and {lines[1].label} almost coincide"))
        if worst[0] < NEAR_SINGULAR_SIN:
            return (f"instant center {center.label} {self.where()}: {worst[1]} "
                    f"(conditioning sine {worst[0]:.2g}); " + tail)
        assert center.position is not None  # a far crossing of two lines that are nearly parallel
        distance = norm(sub(center.position, add(self.frame.offset, self.frame.origin)))
        angle = ("" if sin_angle is None
                 else f" (they meet at {math.degrees(math.asin(min(1.0, abs(sin_angle)))):.3g} deg)")
        return (f"instant center {center.label} {self.where()}: the Kennedy lines {lines[0].label} and "
                f"{lines[1].label} are nearly parallel{angle}, so {center.label} lies far away, {distance:.3g} "
                f"{self.mechanism.scene.units.length} from the mechanism ({distance / self.frame.size:.2g} times its "
                f"size); {tail}, while its direction from the mechanism is accurate")

    def degenerate(self, e: Edge, trouble: list[str]) -> SingularityError:
        return SingularityError(
            f"instant center {self.label(e)} cannot be found {self.where()}: the position is degenerate for the "
            f"Aronhold-Kennedy theorem: " + "; ".join(dict.fromkeys(trouble))
            + f"; no other pair of triangles of the circle diagram closes edge {pair_name(e)}"
        )

    # -- the whole ----------------------------------------------------------------------------
    def run(self) -> None:
        pending = [e for e in self.plan.kennedy.order if e not in self.known]
        trouble: dict[Edge, list[str]] = {}
        while pending:
            progress = False
            for e in list(pending):
                candidate, trouble[e] = self.derive(e)
                if candidate is not None:
                    self.record(e, candidate)
                    pending.remove(e)
                    progress = True
            if not progress and not self.open_more(set(pending)):
                stuck = next((e for e in pending if any(not t.startswith("fewer") for t in trouble[e])), pending[0])
                raise self.degenerate(stuck, trouble[stuck])

    def open_more(self, pending: set[Edge]) -> bool:
        """Degenerate on the planned path: derive one more center that may open other triangles."""
        for e in combinations(self.links, 2):
            if e in self.known or e in pending:
                continue
            candidate, _ = self.derive(e)
            if candidate is not None:
                self.record(e, candidate)
                return True
        return False

    def diagram(self) -> CircleDiagram:
        """The joints' edges (a cam pair's as its line edge, numbered when its point was derived), then the
        derived points' edges in the order found."""
        numbers = {_by_name(self.links, s.center): s.number for s in self.steps}
        edges = [DiagramEdge(e, "line", numbers.get(e, 0), self.via.get(e, _joint_name(joint)))
                 if isinstance(joint, CamSpec) else DiagramEdge(e, "joint", 0, _joint_name(joint))
                 for e, joint in self.plan.joints.items()]
        edges += [DiagramEdge(e, "derived", number, self.via[e]) for e, number in numbers.items()
                  if e not in self.plan.kennedy.lines]
        return CircleDiagram(self.links, circle_positions(self.links), tuple(edges))


def _by_name(links: tuple[str, ...], name: str) -> Edge:
    return split_pair(name, links)


def _line_value(line: _Line | _Normal) -> Projective:
    if isinstance(line, _Normal):
        return line.line
    assert line.join.value is not None
    return line.join.value


def _join_sin(line: _Line | _Normal) -> float:
    """The conditioning of the line's join: a common normal is made from a point and a direction, always apart."""
    return 1.0 if isinstance(line, _Normal) else line.join.sin


def _planar_sin(first: KennedyLine, second: KennedyLine) -> float | None:
    if first.direction is None or second.direction is None:
        return None
    return cross(first.direction, second.direction)


def derive_centers(mechanism: Mechanism, pose: Pose, plan: CenterPlan, offset: Vec = (0.0, 0.0)) -> KennedyResult:
    """The joints' centers at this pose and the planned derived ones, in the order found.

    ``offset`` is added to every reported position (the solve's local frame to the user's).
    Raises SingularityError when a center on the path is degenerate at this position.
    """
    finder = _Finder(mechanism, pose, plan, offset)
    finder.run()
    for _, e in plan.asked:
        if e not in finder.known:  # a joint's center is known once one of its links is solved, as planned
            raise SingularityError(f"instant center {finder.label(e)} {finder.where()}: not found")
    return KennedyResult({e: k.center for e, k in finder.known.items()},
                         {e: replace(k.center, place=k.inside) for e, k in finder.known.items()},
                         tuple(finder.steps), finder.diagram(), tuple(finder.notices), finder.frame.size)
