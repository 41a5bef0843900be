"""Each circle cam replaced by its equivalent link, permanently (a circle has one centre of curvature).

The contact's common normal always passes through the disc's centre K, so the pair is, at every
position, the same lower-pair linkage:

* a roller turning on W: a binary link K W of length R + r (R - r when it runs inside a groove);
* a knife edge at W: a binary link K W of length R (the edge rides the circle);
* a flat face: a block pinned at K sliding on the follower along the face's line moved R toward
  the disc. Which side of the face the disc touches is an assembly, told by the ``[guess]``
  (``scene.flat_side``): where the disc's centre lies on the face's right at the guessed position,
  the face's angle is turned half a turn, so that the disc is on its left (counter-clockwise of its
  direction) from then on; where the guess does not tell, the left is taken (a ``default-assembly``
  warning at the solve).

The equivalent link and its joints are added to the scene (``Scene.equivalent_links``), numbered as a
textbook numbers the link it adds (the next number: block 4 of cam 2 and follower 3; ``eq23`` where the
links are not numbered), so that the plan's dyads, the polygons and the analytic check use it like any
other link. Kennedy's theorem does not: it asks centers between the scene's own links and takes the
pair's common normal as a line edge (``engine.centers``).
"""

from __future__ import annotations

import math

from msgspec.structs import replace

from kinepoly.geom.tolerances import COINCIDENT_REL
from kinepoly.scene.flat_side import flat_side
from kinepoly.scene.spec import CamSpec, LinkSpec, PointSpec, Scene, SliderSpec

__all__ = ["with_equivalent_links"]


def _fresh(base: str, taken: set[str]) -> str:
    name, k = base, 1
    while name in taken:
        k += 1
        name = f"{base}{k}"
    taken.add(name)
    return name


def _number(taken: set[str]) -> str:
    """The next link number, as a textbook numbers the link it adds (the block 4 of a cam 2 and follower 3),
    where the links are numbered; else empty."""
    if not taken or not all(name.isdigit() for name in taken):
        return ""
    name = str(max(int(name) for name in taken) + 1)
    taken.add(name)
    return name


def _center_point(scene: Scene, cam: CamSpec, taken: set[str]) -> str:
    """A point of the cam already at the disc's centre, or a new one ``K<name>``."""
    for p in scene.link(cam.cam).points:
        if math.hypot(p.local[0] - cam.center[0], p.local[1] - cam.center[1]) <= COINCIDENT_REL * max(1.0, cam.radius):
            return p.name
    return _fresh(f"K{cam.name}", taken)


def with_equivalent_links(scene: Scene) -> Scene:
    """``scene`` with each cam's equivalent link (and, for a flat face, its slider) added."""
    if not any(not cam.is_spline for cam in scene.cams):
        return scene
    links = {link.name: link for link in scene.links}
    points = {p.name for link in scene.links for p in link.points}
    names = set(links)
    sliders = list(scene.sliders)
    cams = []
    for cam in scene.cams:
        if cam.is_spline:  # its centre of curvature moves on the cam: placed row by row (engine.cam_place)
            cams.append(cam)
            continue
        k = _center_point(scene, cam, points)
        if k not in scene.link(cam.cam).point_names:
            owner = links[cam.cam]
            links[cam.cam] = replace(owner, points=(*owner.points, PointSpec(k, cam.center, cam.line)))
        link = _number(names) or _fresh(f"eq{cam.name}", names)
        if cam.kind == "flat":
            assert cam.flat is not None
            if flat_side(scene, cam) == "right":
                cam = replace(cam, flat=(cam.flat[0], cam.flat[1] + math.pi))
            assert cam.flat is not None
            (x, y), angle = cam.flat
            left = (-math.sin(angle), math.cos(angle))
            through = (x + cam.radius * left[0], y + cam.radius * left[1])
            links[link] = LinkSpec(link, (PointSpec(k, (0.0, 0.0), cam.line),), cam.line)
            sliders.append(SliderSpec(f"{cam.follower}-{link}", link, cam.follower, k, through, angle, cam.line))
        else:
            assert cam.point is not None
            length = cam.radius + (-cam.roller_radius if cam.inside else cam.roller_radius)
            links[link] = LinkSpec(link, (PointSpec(k, (0.0, 0.0), cam.line), PointSpec(cam.point, (length, 0.0),
                                                                                          cam.line)), cam.line)
        cams.append(replace(cam, equivalent=link, center_point=k))
    return replace(scene, links=tuple(links.values()), sliders=tuple(sliders), cams=tuple(cams),
                   equivalent_links=tuple(c.equivalent for c in cams if not c.is_spline))
