"""Instant centers by the Aronhold-Kennedy theorem, found the way the circle diagram finds them.

The centers of the joints come first: a pin is the center of its two links; a slider's center
(block and guide) is the point at infinity perpendicular to the slide; a gear pair's is its pitch
point. A cam and its follower give a line at once, not a point: their center lies on the common
normal at the contact (a line edge of the circle diagram), and one triangle's Kennedy line crossed
with that normal finds it. A circle cam's equivalent link is not a node of the diagram: the centers
are asked between the scene's own links (the equivalent link serves the polygons). Every other center I_ij
is where the Kennedy line I_ik I_jk crosses the Kennedy line I_il I_jl, for an edge ij of the
circle diagram that closes the two triangles ijk and ijl (``circle_diagram``). Only the centers
on the path to the asked ones are derived.

All of it is projective (``geom.homogeneous``): a center at infinity is an ordinary value, a
Kennedy line through one runs parallel to its direction, the line through two of them is the
line at infinity. Where an edge closes more than two triangles the best-conditioned pair of
lines is taken. A center is reported with a warning when its step is ill-conditioned (two
centers almost one point, or two lines almost one line) or its estimated error is large; when no
pair of triangles gives one point (the centers of a line coincide, the two lines coincide) the
position is degenerate and a SingularityError says which centers and lines.

Two calls: ``plan_instant_centers`` before the position is solved (which links are needed),
``find_instant_centers`` after. The combinatorics live in ``circle_diagram``, the geometry in
``kennedy``, the omegas the centers give in ``center_velocity``, the values in ``center_values``.
"""

from __future__ import annotations

from itertools import combinations

from kinepoly.engine.center_values import CenterPlan, InstantCenter, InstantCenters, KennedyLine, KennedyStep
from kinepoly.engine.center_velocity import omegas_from_centers
from kinepoly.engine.circle_diagram import Edge, center_label, edge, pair_name, plan_kennedy, split_pair
from kinepoly.engine.kennedy import derive_centers
from kinepoly.engine.plan import make_plan
from kinepoly.errors import SceneError
from kinepoly.geom.vec import Vec
from kinepoly.model.mechanism import Joint, Mechanism, Revolute, joint_links
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import CamSpec, GearSpec

__all__ = [
    "CenterPlan",
    "InstantCenter",
    "InstantCenters",
    "KennedyLine",
    "KennedyStep",
    "diagram_links",
    "find_instant_centers",
    "plan_instant_centers",
]


def _asked_edge(source: str, key: str, links: tuple[str, ...]) -> Edge:
    try:
        return split_pair(key, links)
    except ValueError:
        raise SceneError(f"{source}: find.instant_centers: {key!r} is not a pair of links of the scene") from None


def diagram_links(mechanism: Mechanism) -> tuple[str, ...]:
    """The nodes of the circle diagram: the scene's links, without the equivalent links of circle cams."""
    return tuple(link for link in mechanism.link_names if link not in mechanism.scene.equivalent_links)


def _joints(mechanism: Mechanism) -> dict[Edge, Joint | GearSpec | CamSpec]:
    """Each primary center's joint: a pin is the center of every two links it joins (a compound
    hinge of k links gives k (k - 1) / 2 of them), a slider the center of its block and guide, a gear
    pair its pitch point; a cam pair its common normal (a line edge). Joints of equivalent links are
    left out."""
    links = diagram_links(mechanism)
    out: dict[Edge, Joint | GearSpec | CamSpec] = {}
    for gear in mechanism.scene.gears:  # a rolling pair's center is its pitch point
        out.setdefault(edge(*gear.links, links), gear)
    for joint in mechanism.joints:
        a, b = joint_links(joint)
        if a not in links or b not in links:
            continue
        out.setdefault(edge(a, b, links), joint)
        if isinstance(joint, Revolute):
            for other in mechanism.links_of_point(joint.point):
                for link in (a, b):
                    if other not in (a, b) and other in links:
                        out.setdefault(edge(link, other, links), Revolute(joint.point, (link, other)))
    for cam in mechanism.scene.cams:  # a cam pair's center: somewhere on the common normal at the contact
        out.setdefault(edge(cam.cam, cam.follower, links), cam)
    return out


def _joint_links_needed(mechanism: Mechanism, joint: Joint | GearSpec | CamSpec,
                        solved_index: dict[str, int]) -> set[str]:
    """A pin's place needs one of its links solved, a slide's direction one of its two; the ground none;
    a pitch point both gears."""
    if isinstance(joint, GearSpec):
        return {link for link in joint.links if link != mechanism.ground}
    if isinstance(joint, CamSpec):
        return {joint.cam, joint.follower}
    a, b = joint_links(joint)
    if mechanism.ground in (a, b):
        return set()
    return {min((a, b), key=lambda link: solved_index.get(link, len(solved_index)))}


def plan_instant_centers(mechanism: Mechanism) -> CenterPlan:
    """The centers the scene asks and the path of the circle diagram to them.

    Raises SceneError for a ``[given]`` scene (one body and no frame link: no pair of links) and
    for a center the Aronhold-Kennedy theorem cannot reach in this mechanism.
    """
    scene = mechanism.scene
    wanted = scene.find.instant_centers
    links = diagram_links(mechanism)
    if mechanism.ground is None:
        raise SceneError(
            f"{scene.source}: find.instant_centers: a [given] scene is one body with no frame link, so there "
            "is no pair of links to have an instant center; remove instant_centers from [find], or model the "
            "frame as a link with an [input] to find the centers of a mechanism"
        )
    if wanted == "all":
        asked = tuple((pair_name(e), e) for e in combinations(links, 2))
    else:
        asked = tuple((key, _asked_edge(scene.source, key, links)) for key in wanted)
    joints = _joints(mechanism)
    targets = tuple(dict.fromkeys(e for _, e in asked))
    lines = frozenset(e for e, joint in joints.items() if isinstance(joint, CamSpec))
    kennedy = plan_kennedy(links, frozenset(joints) - lines, targets, lines)
    if kennedy.unreachable:
        names = ", ".join(center_label(pair_name(e)) for e in kennedy.unreachable)
        raise SceneError(
            f"{scene.source}: find.instant_centers: {names} cannot be reached on the circle diagram: no edge "
            "closes two triangles of known centers any more, so the Aronhold-Kennedy theorem alone does not "
            "find it in this mechanism; ask for centers the diagram reaches"
        )
    solved = make_plan(mechanism)
    order = [*solved.driven, *(link for group in solved.groups for link in group.links)]
    solved_index = {link: n for n, link in enumerate(order)}
    used = {e for e in targets if e in joints}
    used.update(s for e in kennedy.order for s in kennedy.sides(e) if s in joints)
    used.update(e for e in kennedy.order if e in lines)
    needed: set[str] = set()
    for e in sorted(used, key=lambda pair: (links.index(pair[0]), links.index(pair[1]))):
        needed |= _joint_links_needed(mechanism, joints[e], solved_index)
    return CenterPlan(kennedy, joints, asked, frozenset(needed))


def find_instant_centers(mechanism: Mechanism, pose: Pose, plan: CenterPlan,
                         offset: Vec = (0.0, 0.0)) -> InstantCenters:
    """Derive the planned centers at this pose (``kennedy``), then the omegas they give.

    ``offset`` is added to every reported position (the solve's local frame to the user's).
    Raises SingularityError when a center on the path is degenerate at this position.
    """
    found = derive_centers(mechanism, pose, plan, offset)
    centers = {center.name: center for center in found.centers.values()}
    omegas = omegas_from_centers(mechanism, pose, found.inside, found.size)
    asked = tuple((key, pair_name(e)) for key, e in plan.asked)
    return InstantCenters(centers, asked, found.steps, found.diagram, omegas, found.notices)
