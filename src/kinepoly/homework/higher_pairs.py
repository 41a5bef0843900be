"""Gears and cams in a variant: the scene as the user wrote it, and the lengths its pairs carry.

A loaded scene holds each cam's equivalent link (``scene.equivalent``); a variant is drawn on the
scene *without* them (the links, the slide of a flat face, and the disc's centre point the loader
added to the cam), written with its ``[[cams]]`` and ``[[gears]]`` as they were, and replaced again
(:func:`with_equivalent_links`) before it is solved.

The lengths a pair carries belong to a link and take that link's factor: a cam's profile centre and
radius (a ``points`` profile: every point's coordinates, so that the whole curve scales) are the cam's, its roller's
radius and flat face the follower's; a pitch circle's radius, a pitch line's ``through`` and a rack's phase (a length)
their gear's.
"""

from __future__ import annotations

from collections.abc import Sequence

from msgspec.structs import replace

from kinepoly.scene.equivalent import with_equivalent_links
from kinepoly.scene.spec import CamSpec, GearSpec, LinkSpec, PitchCircle, PitchLine, Scene

__all__ = ["PROFILE_EXTRA_DIGITS", "as_written", "pair_extra_digits", "pair_lengths", "pair_owners", "solvable",
           "with_pair_lengths"]


def _added_centre(scene: Scene, cam: CamSpec, link: LinkSpec) -> str | None:
    """The centre point the loader added to the cam (made at the ``[[cams]]`` table's line), if it did."""
    for p in link.points:
        if p.name == cam.center_point and p.line == cam.line and p.local == cam.center:
            return p.name
    return None


def as_written(scene: Scene) -> Scene:
    """``scene`` without its cams' equivalent links: the links, sliders and points the user wrote."""
    if not scene.equivalent_links:
        return scene
    replaced = set(scene.equivalent_links)
    added = {cam.cam: name for cam in scene.cams
             if (name := _added_centre(scene, cam, scene.link(cam.cam))) is not None}
    links = tuple(replace(link, points=tuple(p for p in link.points if p.name != added.get(link.name)))
                  for link in scene.links if link.name not in replaced)
    sliders = tuple(s for s in scene.sliders if s.block not in replaced and s.guide not in replaced)
    cams = tuple(replace(cam, equivalent="", center_point="") for cam in scene.cams)
    return replace(scene, links=links, sliders=sliders, cams=cams, equivalent_links=())


def solvable(scene: Scene) -> Scene:
    """A scene as written, its cams replaced by their equivalent links (as the loader does)."""
    return with_equivalent_links(scene)


PROFILE_EXTRA_DIGITS = 2
"""Decimal places a ``points`` profile's coordinates keep beyond the variant's other lengths: rounded as
coarsely, 36 points a few millimetres apart would make a wavy curve (its curvature, which the
construction uses, off by tens of percent); two more keep it within a few percent."""


def _cam_lengths(cam: CamSpec) -> list[tuple[str, float, int]]:
    if cam.is_spline:
        out = [(cam.cam, x, PROFILE_EXTRA_DIGITS) for point in cam.profile_points for x in point]
    else:
        out = [(cam.cam, cam.center[0], 0), (cam.cam, cam.center[1], 0), (cam.cam, cam.radius, 0)]
    out.append((cam.follower, cam.roller_radius, 0))
    if cam.flat is not None:
        out += [(cam.follower, cam.flat[0][0], 0), (cam.follower, cam.flat[0][1], 0)]
    return out


def _gear_lengths(gear: GearSpec) -> list[tuple[str, float, int]]:
    out: list[tuple[str, float, int]] = []
    for link, curve, phase in zip(gear.links, gear.pitch, gear.phase, strict=True):
        if isinstance(curve, PitchCircle):
            out.append((link, curve.radius, 0))
        else:
            out += [(link, curve.through[0], 0), (link, curve.through[1], 0), (link, phase, 0)]
    return out


def _lengths(scene: Scene) -> list[tuple[str, float, int]]:
    return [x for cam in scene.cams for x in _cam_lengths(cam)] + [x for gear in scene.gears
                                                                    for x in _gear_lengths(gear)]


def pair_lengths(scene: Scene) -> tuple[float, ...]:
    """Every length the scene's cams and gears carry, in one order."""
    return tuple(value for _, value, _ in _lengths(scene))


def pair_owners(scene: Scene) -> tuple[str, ...]:
    """The link whose factor scales each of :func:`pair_lengths`."""
    return tuple(link for link, _, _ in _lengths(scene))


def pair_extra_digits(scene: Scene) -> tuple[int, ...]:
    """The decimal places each of :func:`pair_lengths` keeps beyond the variant's rounding of lengths."""
    return tuple(extra for _, _, extra in _lengths(scene))


def _cam(cam: CamSpec, values: list[float]) -> CamSpec:
    if cam.is_spline:
        points = tuple((values.pop(0), values.pop(0)) for _ in cam.profile_points)
        centre, radius = cam.center, cam.radius
    else:
        points, centre, radius = (), (values.pop(0), values.pop(0)), values.pop(0)
    roller = values.pop(0)
    flat = None if cam.flat is None else ((values.pop(0), values.pop(0)), cam.flat[1])
    return replace(cam, center=centre, radius=radius, roller_radius=roller, flat=flat,
                               profile_points=points)


def _gear(gear: GearSpec, values: list[float]) -> GearSpec:
    pitch: list[PitchCircle | PitchLine] = []
    phase = list(gear.phase)
    for k, curve in enumerate(gear.pitch):
        if isinstance(curve, PitchCircle):
            pitch.append(replace(curve, radius=values.pop(0)))
        else:
            pitch.append(replace(curve, through=(values.pop(0), values.pop(0))))
            phase[k] = values.pop(0)
    return replace(gear, pitch=(pitch[0], pitch[1]), phase=(phase[0], phase[1]))


def with_pair_lengths(scene: Scene, lengths: Sequence[float]) -> Scene:
    """``scene`` (as written) with its pairs' lengths replaced, in the order of :func:`pair_lengths`."""
    values = list(lengths)
    cams = tuple(_cam(cam, values) for cam in scene.cams)
    gears = tuple(_gear(gear, values) for gear in scene.gears)
    return replace(scene, cams=cams, gears=gears)
