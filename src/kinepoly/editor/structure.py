"""Edits that add and remove links: a dyad built by clicks, a link taken away, in the scene's TOML (tomlkit).

- ``add-dyad``: two new links and the pins between them: from a point of the mechanism to a new
  joint, and from the joint to a point of the mechanism or to a new frame pivot; with
  ``"slider": true`` the second link is a block on the frame whose joint runs on a line through
  the joint toward the third place. The joint is placed where it was clicked (its ``[guess]``), so
  the dyad closes there; the new links keep the textbook frame (first joint at the origin, the
  second on the x-axis); a ``[find]`` that lists what to find lists the new links and joint too.
- ``remove-link``: a link taken away with what names it: its sliders, gears and cams, its pivots
  on the frame, and its points in ``[guess]`` and ``[find]`` where no other link has them. What is left may no longer
  move with one degree of freedom; the page then says so, as ``kinepoly solve`` does.
"""

from __future__ import annotations

import math
import string
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import tomlkit
from tomlkit.items import AoT, Array, InlineTable, Table

from kinepoly.editor.values import EditError, number, pair, place, store
from kinepoly.geom.tolerances import EDIT_SAME_REL, SIZE_FLOOR
from kinepoly.model.pose import LinkPose
from kinepoly.scene.link_point import LinkPoint

if TYPE_CHECKING:
    from tomlkit.toml_document import TOMLDocument

    from kinepoly.solution import Solution

__all__ = ["add_dyad", "removable", "remove_link"]


def _point_names(solution: Solution) -> set[str]:
    return {p.name for link in solution.scene.links for p in link.points}


def _new_point(used: set[str], after: str = "") -> str:
    """The first capital letter not used as a point's name (then with digits)."""
    for suffix in ("", *map(str, range(1, 100))):
        for letter in string.ascii_uppercase:
            if letter + suffix not in used and letter + suffix + "0" not in used:
                return letter + suffix
    raise EditError("no free point name")  # pragma: no cover - 2600 names


def _new_link(solution: Solution, doc: TOMLDocument) -> str:
    names = {link.name for link in solution.scene.links} | set(_table(doc, "links").keys())
    numbers = [int(n) for n in names if n.isdigit()]
    k = max(numbers, default=0) + 1
    while str(k) in names:
        k += 1
    return str(k)


def _table(doc: Any, key: str) -> Any:
    value = doc.get(key)
    if not isinstance(value, (Table, InlineTable)):
        raise EditError(f"the scene has no [{key}] table to edit")
    return value


def _solved_point(solution: Solution, name: object) -> tuple[str, tuple[float, float]]:
    if not isinstance(name, str) or not any(name in {p.name for p in solution.scene.link(link).points}
                                            for link in solution.pose.links):
        raise EditError(f"add-dyad: {name!r} is not a point of the mechanism as solved")
    return name, solution.position(name)


def _link_table(points: dict[str, list[float]]) -> InlineTable:
    table = tomlkit.inline_table()
    inner = tomlkit.inline_table()
    for name, xy in points.items():
        inner[name] = [number(x) for x in xy]
    table["points"] = inner
    return table


def _local(origin: Sequence[float], toward: Sequence[float], at: Sequence[float]) -> tuple[float, float]:
    """``at`` in the frame whose origin is ``origin`` and whose x-axis points at ``toward``."""
    angle = math.atan2(toward[1] - origin[1], toward[0] - origin[0])
    dx, dy = at[0] - origin[0], at[1] - origin[1]
    c, s = math.cos(angle), math.sin(angle)
    return (c * dx + s * dy, -s * dx + c * dy)


def _append(doc: TOMLDocument, key: str, names: Sequence[str]) -> None:
    """Append ``names`` to ``[find] key`` where the scene lists that key (absent: everything is found already)."""
    find = doc.get("find")
    if not isinstance(find, (Table, InlineTable)):
        return
    listed = find.get(key)
    if isinstance(listed, Array):
        for name in names:
            if name not in listed:
                listed.append(name)


def add_dyad(doc: TOMLDocument, solution: Solution, edit: dict[str, Any]) -> None:
    """Add a dyad (two links, an RRR or, with ``slider``, an RRP whose block slides on the frame)."""
    scene = solution.scene
    if scene.ground is None:
        raise EditError("add-dyad: a scene with [given] motion has no frame to pin a dyad to")
    start, start_at = _solved_point(solution, edit.get("from"))
    joint_at = place(edit.get("joint"))
    used = _point_names(solution) | {str(k) for k in doc.get("guess", {})}
    joint = _new_point(used)
    slider = edit.get("slider") is True
    to = edit.get("to")
    size = max(SIZE_FLOOR, max(math.hypot(*p) for p in (start_at, joint_at)))
    if math.hypot(joint_at[0] - start_at[0], joint_at[1] - start_at[1]) < EDIT_SAME_REL * size:
        raise EditError("add-dyad: the new joint lies on the point it starts from; click another place")
    links = _table(doc, "links")
    first = _new_link(solution, doc)
    links[first] = _link_table({start: [0, 0], joint: pair(solution, _local(start_at, joint_at, joint_at))})
    second = str(int(first) + 1) if first.isdigit() else first + "b"
    ground_pose = solution.pose.links.get(scene.ground, LinkPose(0.0, 0.0, 0.0))
    if slider:
        toward = place(to.get("at") if isinstance(to, dict) else None)
        if math.hypot(toward[0] - joint_at[0], toward[1] - joint_at[1]) < EDIT_SAME_REL * size:
            raise EditError("add-dyad: the slide's direction is from the joint to a place away from it")
        links[second] = _link_table({joint: [0, 0]})
        through = ground_pose.to_local(joint_at)
        direction = math.atan2(toward[1] - joint_at[1], toward[0] - joint_at[0]) - ground_pose.theta
        angle = math.degrees(direction) if scene.units.angle == "deg" else direction
        line = tomlkit.inline_table()
        line["through"] = [number(x) for x in pair(solution, through)]
        line["angle"] = round(math.remainder(angle, 360.0 if scene.units.angle == "deg" else 2 * math.pi), 2)
        table = tomlkit.table()
        table.update({"block": second, "guide": scene.ground, "point": joint})
        table["line"] = line
        sliders = doc.get("sliders")
        if isinstance(sliders, AoT):
            sliders.append(table)
        else:
            doc["sliders"] = tomlkit.aot()
            doc["sliders"].append(table)
    else:
        if isinstance(to, dict) and "point" in to:
            end, end_at = _solved_point(solution, to.get("point"))
            if end == start:
                raise EditError("add-dyad: the dyad ends where it starts; pick another point")
        elif isinstance(to, dict) and "at" in to:
            end_at = place(to.get("at"))
            end = joint + "0"
            ground_points = _table(_table(doc, "links").get(scene.ground) or {}, "points")
            ground_points[end] = [number(x) for x in pair(solution, ground_pose.to_local(end_at))]
        else:
            raise EditError("add-dyad: \"to\" is {\"point\": name} or {\"at\": [x, y]} (a new frame pivot)")
        if math.hypot(end_at[0] - joint_at[0], end_at[1] - joint_at[1]) < EDIT_SAME_REL * size:
            raise EditError("add-dyad: the new joint lies on the point it ends at; click another place")
        links[second] = _link_table({end: [0, 0], joint: pair(solution, _local(end_at, joint_at, joint_at))})
    guess = doc.get("guess")
    if not isinstance(guess, (Table, InlineTable)):
        doc["guess"] = guess = tomlkit.table()
    store(guess, joint, pair(solution, joint_at))
    _append(doc, "velocity", [joint])
    _append(doc, "acceleration", [joint])
    _append(doc, "omega", [first] + ([] if slider else [second]))
    _append(doc, "alpha", [first] + ([] if slider else [second]))


def removable(solution: Solution) -> list[str]:
    """The links the page offers to remove: all but the frame, those the inputs drive, and equivalent links."""
    scene = solution.scene
    inputs = [scene.input, *scene.more_inputs]
    driven = {getattr(i, "link", None) for i in inputs} | {getattr(i, "relative_to", None) for i in inputs}
    driven |= {s.block for s in scene.sliders for i in inputs if getattr(i, "slider", None) == s.name}
    driven |= {s.guide for s in scene.sliders for i in inputs if getattr(i, "slider", None) == s.name}
    return [link.name for link in scene.links
            if link.name != scene.ground and link.name not in driven and link.name not in scene.equivalent_links]


def _named_in(table: Any, link: str) -> bool:
    return any(str(table.get(key)) == link for key in ("block", "guide", "cam", "follower")) or \
        link in [str(x) for x in table.get("links", [])]


def remove_link(doc: TOMLDocument, solution: Solution, link: object) -> None:
    """Take link ``link`` away, with its sliders, gears and cams and the mentions of what was only its."""
    scene = solution.scene
    links = _table(doc, "links")
    if not isinstance(link, str) or link not in links:
        raise EditError(f"remove-link: no link {link!r} in [links]")
    if link not in removable(solution):
        raise EditError(f"remove-link: link {link} is the frame or driven by the input; change [input] first")
    own = {p.name for p in scene.link(link).points} if link in {x.name for x in scene.links} else set()
    del links[link]
    removed_sliders = set()
    for key in ("sliders", "gears", "cams"):
        tables = doc.get(key)
        if isinstance(tables, AoT):
            keep = [t for t in tables if not _named_in(t, link)]
            removed_sliders |= ({s.name for s in scene.sliders if link in (s.block, s.guide)} if key == "sliders"
                                else set())
            if len(keep) != len(tables):
                if keep:
                    new = tomlkit.aot()
                    for t in keep:
                        new.append(t)
                    doc[key] = new
                else:
                    del doc[key]
    ground = links.get(scene.ground) if scene.ground is not None else None
    ground_points = ground.get("points") if isinstance(ground, (Table, InlineTable)) else None
    others = [other for name, other in links.items() if name != scene.ground]
    left = {str(name) for other in others for name in other.get("points", {})}
    if isinstance(ground_points, (Table, InlineTable)):  # its pivots on the frame go with it
        for name in (own & {str(k) for k in ground_points}) - left:
            del ground_points[name]
        left |= {str(k) for k in ground_points}
    gone = own - left
    guess = doc.get("guess")
    if isinstance(guess, (Table, InlineTable)):
        for name in gone & {str(k) for k in guess}:
            del guess[name]
    find = doc.get("find")
    if isinstance(find, (Table, InlineTable)):
        for key, drop in (("velocity", gone), ("acceleration", gone), ("omega", {link}), ("alpha", {link}),
                          ("sliders", removed_sliders)):
            listed = find.get(key)
            if isinstance(listed, Array):
                for i in reversed(range(len(listed))):
                    named = LinkPoint.parse(str(listed[i]))
                    if named.point in drop or str(listed[i]) in drop or named.link == link:
                        del listed[i]
