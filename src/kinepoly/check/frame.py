"""A local frame for the solve: every link's points taken relative to a point of that link.

A point 1e6 from the origin carries an absolute rounding of about 1e-10; a mechanism 100
long built from such points loses six digits before any construction starts. So the solve
runs on a *localized* copy of the scene: the frame link's points (and the slider lines it
carries, and the ``[guess]``) are taken relative to a local origin ``origin``, and a moving
link whose own points sit far from its own origin is re-anchored at its first point. Inside,
every coordinate is of the size of the mechanism; only a reported position gets ``origin``
added back, once. Angles, velocities, accelerations and slider values do not change.

A mechanism near its origin (the usual case) is left exactly as it is: no link moves unless
its coordinates exceed ``FAR_FACTOR`` times its own extent.
"""

from __future__ import annotations

from msgspec import Struct
from msgspec.structs import replace

from kinepoly.geom.hull import diameter
from kinepoly.geom.vec import Vec, rotate
from kinepoly.model.pose import LinkPose, Pose
from kinepoly.scene.spec import LinkSpec, PointSpec, Scene, SliderSpec

__all__ = ["FAR_FACTOR", "LocalFrame", "localize"]

FAR_FACTOR = 4.0
"""A link is re-anchored when its largest coordinate exceeds this many times its extent."""


class LocalFrame(Struct, frozen=True):
    """A scene with its links re-anchored, and how to go back to the user's frames.

    ``anchors[k]`` is the user's local coordinates of link k's new local origin; for the frame
    link it is ``origin``, the user's frame coordinates of the point that is (0, 0) inside.
    """

    scene: Scene
    frame_link: str
    origin: Vec
    anchors: dict[str, Vec]

    @property
    def is_identity(self) -> bool:
        return all(a == (0.0, 0.0) for a in self.anchors.values())

    def to_user(self, point: Vec) -> Vec:
        """A frame position computed inside, in the user's frame."""
        return (point[0] + self.origin[0], point[1] + self.origin[1])

    def pose_to_user(self, pose: Pose) -> Pose:
        """Poses inside, as poses of the user's links in the user's frame (the frame link stays put)."""
        out = {}
        for link, p in pose.links.items():
            if link == self.frame_link:
                out[link] = p
                continue
            arm = rotate(self.anchors.get(link, (0.0, 0.0)), p.theta)
            out[link] = LinkPose(p.x + self.origin[0] - arm[0], p.y + self.origin[1] - arm[1], p.theta)
        return Pose(out, {name: self.to_user(at) for name, at in pose.marks.items()})


def _extent(points: list[Vec]) -> tuple[float, float]:
    """(largest coordinate, largest distance between two points)."""
    far = max((max(abs(x), abs(y)) for x, y in points), default=0.0)
    spread = diameter(points)
    return far, spread


def _anchor(points: list[Vec]) -> Vec:
    far, spread = _extent(points)
    if far == 0.0 or far <= FAR_FACTOR * spread:
        return (0.0, 0.0)
    return points[0]


def _shift(v: Vec, anchor: Vec) -> Vec:
    return (v[0] - anchor[0], v[1] - anchor[1])


def _link_points(scene: Scene, link: LinkSpec) -> list[Vec]:
    pts = [p.local for p in link.points]
    pts += [s.through for s in scene.sliders if s.guide == link.name]
    return pts


def localize(scene: Scene) -> LocalFrame:
    """The scene with every far-off link re-anchored (see the module's docstring)."""
    frame_link = scene.ground if scene.ground is not None else scene.links[0].name
    anchors = {link.name: _anchor(_link_points(scene, link)) for link in scene.links}
    origin = anchors[frame_link]
    if all(a == (0.0, 0.0) for a in anchors.values()):
        return LocalFrame(scene, frame_link, origin, anchors)
    links = tuple(
        replace(link, points=tuple(PointSpec(p.name, _shift(p.local, anchors[link.name]), p.line) for p in link.points))
        for link in scene.links
    )
    sliders = tuple(_shift_slider(s, anchors[s.guide]) for s in scene.sliders)
    guess = tuple((name, _shift(at, origin)) for name, at in scene.guess)
    local = replace(scene, links=links, sliders=sliders, guess=guess)
    return LocalFrame(local, frame_link, origin, anchors)


def _shift_slider(slider: SliderSpec, anchor: Vec) -> SliderSpec:
    """The line's point moves with its guide's anchor; s (measured from it) does not change."""
    return replace(slider, through=_shift(slider.through, anchor))
