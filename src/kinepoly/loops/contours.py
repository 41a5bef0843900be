"""The independent loops of a mechanism and their vectors, from the positions the engine placed.

The links are the nodes of a graph and the joints (pins, sliders) its edges; a spanning tree grown
from the frame leaves N = j - n + 1 joints out (RO 2.2.1, eq. 7: N = sum of c_i - n + 1 with every
joint a pair of class 5), and each of them closes one loop with the tree: the loops are independent,
each holding a joint no other loop holds. Going round a loop, every link crossed adds the vector from
the joint it is entered at to the joint it is left at (a constant length at the angle theta_1k plus a
constant offset), and every slider crossed adds s times the unit vector of its line.
"""

from __future__ import annotations

import cmath
import math
from collections import deque

from msgspec import Struct

from kinepoly.errors import OutputError
from kinepoly.geom.tolerances import ROUNDING_REL
from kinepoly.model.mechanism import Joint, Mechanism, Revolute, joint_links
from kinepoly.model.pose import Pose
from kinepoly.scene.spec import SliderSpec

__all__ = ["Loop", "LoopMethodError", "Term", "choose_loops", "class_name", "loop_count", "spanning_tree"]

_ZERO_LENGTH = ROUNDING_REL


class LoopMethodError(OutputError):
    """``--method loops`` asked of a scene with a pair the loop method does not cover (gears, cams): exit 2."""


class Term(Struct, frozen=True):
    """One vector of a loop, ``sign`` times ``length`` e^{i angle}, angle = theta_1k + ``offset``.

    A link's vector (``slider`` None) has a constant length and turns with ``link``; a slider's has the
    length s (variable) along its line, which turns with the guide ``link``. ``start`` and ``end`` name
    the points it joins, as the loop is travelled.
    """

    link: str
    start: str
    end: str
    length: float
    angle: float
    offset: float
    sign: int
    slider: str | None = None

    @property
    def unit(self) -> complex:
        return complex(cmath.exp(1j * self.angle))

    @property
    def value(self) -> complex:
        return self.sign * self.length * self.unit


class Loop(Struct, frozen=True):
    """One independent loop: the links it goes round, in order, and its vectors (their sum is zero)."""

    number: int
    members: tuple[str, ...]
    terms: tuple[Term, ...]
    closing: str
    """The joint this loop alone holds (the one the spanning tree leaves out)."""
    joints: tuple[str, ...] = ()
    """Every joint the loop crosses, in order."""

    def closure(self) -> complex:
        """The sum of the loop's vectors at the engine's positions: zero to rounding."""
        return sum((t.value for t in self.terms), 0j)


def loop_count(mechanism: Mechanism) -> int:
    """N = j - n + 1: the independent loops of the mechanism's lower pairs."""
    return len(mechanism.joints) - len(mechanism.link_names) + 1


def class_name(mechanism: Mechanism, link: str) -> str:
    """The link whose theta_1k names a rotation class: the one with most points (a block turns with its guide)."""
    members = mechanism.turning_together(link)
    if mechanism.ground in members:
        return mechanism.ground or link
    return max(members, key=lambda m: (len(mechanism.scene.link(m).points), -mechanism.link_names.index(m)))


def uncovered(mechanism: Mechanism) -> str | None:
    """Why the loop method cannot be used on this mechanism, or None."""
    scene = mechanism.scene
    if mechanism.ground is None:
        return "a [given] scene has no loops"
    if scene.gears:
        return "its gears are higher pairs (a loop of lower pairs cannot hold a pitch point's rolling)"
    if scene.cams:
        return "its cams are higher pairs (a loop of lower pairs cannot hold a sliding contact)"
    return None


def _point_on(mechanism: Mechanism, pose: Pose, link: str, joint: Joint) -> tuple[str, complex]:
    """Where a loop crossing ``joint`` enters or leaves ``link``: the pin, the block's point or the guide's line
    point."""
    if isinstance(joint, Revolute):
        x, y = pose.world(mechanism.local(link, joint.point), link)
        return joint.point, complex(x, y)
    if link == joint.block:
        x, y = pose.world(mechanism.local(link, joint.point), link)
        return joint.point, complex(x, y)
    x, y = pose.world(joint.through, link)
    return f"{joint.name}'", complex(x, y)


def _slide_term(mechanism: Mechanism, pose: Pose, joint: SliderSpec, sign: int) -> Term:
    guide = pose.links[joint.guide]
    angle = guide.theta + joint.angle_rad
    tx, ty = guide.world(joint.through)
    px, py = pose.world(mechanism.local(joint.block, joint.point), joint.block)
    s = ((px - tx) * math.cos(angle) + (py - ty) * math.sin(angle))
    start, end = (f"{joint.name}'", joint.point) if sign > 0 else (joint.point, f"{joint.name}'")
    return Term(joint.guide, start, end, s, angle, joint.angle_rad, sign, joint.name)


def _link_term(mechanism: Mechanism, pose: Pose, link: str, entry: Joint, leave: Joint) -> Term | None:
    start, a = _point_on(mechanism, pose, link, entry)
    end, b = _point_on(mechanism, pose, link, leave)
    if abs(b - a) <= _ZERO_LENGTH * max(1.0, abs(a), abs(b)):
        return None
    angle = cmath.phase(b - a)
    theta = pose.links[link].theta
    offset = math.remainder(angle - theta, 2.0 * math.pi)
    return Term(link, start, end, abs(b - a), theta + offset, offset, 1)


def spanning_tree(mechanism: Mechanism) -> tuple[dict[str, tuple[str, Joint] | None], list[Joint]]:
    """A spanning tree grown breadth-first from the frame (each link's parent and joint) and the joints left out."""
    ground = mechanism.ground
    assert ground is not None
    parent: dict[str, tuple[str, Joint] | None] = {ground: None}
    used: set[int] = set()
    queue = deque([ground])
    while queue:
        link = queue.popleft()
        for joint in mechanism.joints_of(link):
            a, b = joint_links(joint)
            other = b if a == link else a
            if other not in parent:
                parent[other] = (link, joint)
                used.add(id(joint))
                queue.append(other)
    return parent, [j for j in mechanism.joints if id(j) not in used]


def _path_to_root(parent: dict[str, tuple[str, Joint] | None], link: str) -> list[tuple[str, Joint | None]]:
    out: list[tuple[str, Joint | None]] = []
    here: str | None = link
    while here is not None:
        up = parent[here]
        out.append((here, up[1] if up else None))
        here = up[0] if up else None
    return out


def _cycle(parent: dict[str, tuple[str, Joint] | None], closing: Joint) -> list[tuple[str, Joint]]:
    """The loop as (link, the joint it is left by): up from the closing joint's first link to where the
    two paths to the frame meet, down to its second link, and across the closing joint back."""
    a, b = joint_links(closing)
    up_a, up_b = _path_to_root(parent, a), _path_to_root(parent, b)
    on_a, on_b = [link for link, _ in up_a], [link for link, _ in up_b]
    meet = next(link for link in on_a if link in on_b)
    a_side, b_side = up_a[: on_a.index(meet)], up_b[: on_b.index(meet)]
    links = [link for link, _ in a_side] + [meet] + [link for link, _ in reversed(b_side)]
    joints = [j for _, j in a_side] + [j for _, j in reversed(b_side)] + [closing]
    cycle = [(link, joint) for link, joint in zip(links, joints, strict=True) if joint is not None]
    start = links.index(meet)  # the texts start a loop where it leaves the frame (or the link nearest it)
    return cycle[start:] + cycle[:start]


def joint_name(mechanism: Mechanism, joint: Joint) -> str:
    """A pin by its point, a slider by its name; a pin of a compound hinge with the two links it joins."""
    if isinstance(joint, Revolute) and len(mechanism.links_of_point(joint.point)) > 2:
        return f"{joint.point} ({joint.links[0]}-{joint.links[1]})"
    return joint.name


def choose_loops(mechanism: Mechanism, pose: Pose) -> tuple[Loop, ...]:
    """The independent loops at ``pose`` (every link placed), each with its vectors; the frame's loops first."""
    why = uncovered(mechanism)
    if why is not None:
        raise LoopMethodError(f"{mechanism.scene.source}: --method loops: the loop-closure method does not cover "
                              f"this scene: {why}; solve it without --method (the polygon method)")
    parent, closing = spanning_tree(mechanism)
    loops = []
    for number, joint in enumerate(closing, 1):
        cycle = _cycle(parent, joint)
        order = mechanism.link_names.index
        if len(cycle) > 2 and order(cycle[-1][0]) < order(cycle[1][0]):  # round it in the scene's order of links
            cycle = [(cycle[0][0], cycle[-1][1])] + [(cycle[k][0], cycle[k - 1][1])
                                                     for k in range(len(cycle) - 1, 0, -1)]
        terms: list[Term] = []
        for k, (link, leave) in enumerate(cycle):
            entry = cycle[k - 1][1]
            term = _link_term(mechanism, pose, link, entry, leave)
            if term is not None:
                terms.append(term)
            if isinstance(leave, SliderSpec):
                terms.append(_slide_term(mechanism, pose, leave, 1 if link == leave.guide else -1))
        loops.append(Loop(number, tuple(link for link, _ in cycle), tuple(terms), joint_name(mechanism, joint),
                          tuple(joint_name(mechanism, leave) for _, leave in cycle)))
    return tuple(loops)
