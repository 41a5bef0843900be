"""Edits of a scene's TOML text, made through tomlkit so that the user's comments, order and formatting stay.

An edit is a small JSON object (docs/editor.md lists them). Those that come from the mouse give a
place in the frame; the place is turned into what the scene writes by the solved pose of the
current text (``model.pose.LinkPose.to_local``, the input's angle, the slide's stroke):

- ``move-point``: the point's coordinates in every solved link that carries it become those of
  the place in that link's frame at the current pose (a frame pivot moves; a link's point moves
  and the link's lengths change with it);
- ``drive``: the input follows the place: a crank turns to point at it, a driven slider's stroke
  runs to the place's foot on its line;
- ``guess``: the ``[guess]`` of a point, which picks the assembly nearest it;
- ``set``: a value at a key path (``["input", "omega"]``);
- ``length``: a link's point moved along the line from the link's first point to it, to that distance.

Before an edit that moves something, every ``[guess]`` the scene has is set to where its point is now,
so that the mechanism keeps its assembly as it is dragged.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import tomlkit
from tomlkit.exceptions import TOMLKitError
from tomlkit.items import InlineTable, Table

from kinepoly.editor.values import EditError, decimals, is_finite_number, pair, place, store, tidy
from kinepoly.scene.spec import LinkInput, SliderInput

if TYPE_CHECKING:
    from tomlkit.toml_document import TOMLDocument

    from kinepoly.solution import Solution

__all__ = ["MOVING", "EditError", "apply_edit"]

MOVING = ("move-point", "drive", "length")
"""The edits that move the mechanism: before them, the guesses follow their points."""


def apply_edit(text: str, edit: dict[str, Any], solution: Solution | None) -> str:
    """``text`` with ``edit`` made; ``solution`` the current text's (needed by the edits that come from the mouse).
    Before an edit that moves the mechanism, the guesses follow their points in ``solution``."""
    bom = "\ufeff" if text.startswith("\ufeff") else ""
    try:
        doc = tomlkit.parse(text.removeprefix(bom))
    except TOMLKitError as error:
        raise EditError(f"the scene's text is not TOML ({error}); correct it (or undo) first") from None
    op = edit.get("op")
    if op in MOVING and solution is not None:
        _follow(doc, solution)
    if op == "set":
        _set(doc, _key(edit.get("key")), _value(edit.get("value")))
    elif op in ("move-point", "drive", "guess", "length"):
        if solution is None:
            raise EditError(f"{op}: the scene has no solved position to edit from; correct it first")
        if op == "move-point":
            _move_point(doc, solution, _name(edit.get("point")), place(edit.get("to")))
        elif op == "drive":
            _drive(doc, solution, place(edit.get("to")))
        elif op == "guess":
            _set(doc, ["guess", _name(edit.get("point"))], pair(solution, place(edit.get("to"))))
        else:
            _length(doc, solution, _name(edit.get("link")), _name(edit.get("point")), edit.get("value"))
    elif op in ("add-dyad", "remove-link"):
        from kinepoly.editor.structure import add_dyad, remove_link

        if solution is None:
            raise EditError(f"{op}: the scene has no solved position to edit from; correct it first")
        if op == "add-dyad":
            add_dyad(doc, solution, edit)
        else:
            remove_link(doc, solution, edit.get("link"))
    else:
        raise EditError(f"unknown edit {op!r}; expected set, move-point, drive, guess, length, add-dyad or remove-link")
    return bom + tomlkit.dumps(doc)


def _follow(doc: TOMLDocument, solution: Solution) -> bool:
    """Each ``[guess]`` point of ``doc`` put where ``solution`` has it; whether any moved."""
    guess = doc.get("guess")
    if not isinstance(guess, (Table, InlineTable)):
        return False
    changed = False
    for name in list(guess.keys()):
        try:
            at = solution.position(str(name))
        except KeyError:  # a guess point that no solved link holds
            continue
        new = pair(solution, at)
        if _numbers(guess[name]) != new:
            store(guess, str(name), new)
            changed = True
    return changed


def _move_point(doc: TOMLDocument, solution: Solution, point: str, to: tuple[float, float]) -> None:
    links = [link for link in solution.scene.links if any(p.name == point for p in link.points)]
    moved = [link.name for link in links if link.name in solution.pose.links and _written(doc, link.name, point)]
    if not moved:
        raise EditError(f"move-point: no solved link has a point {point!r} written in [links]")
    for name in moved:
        local = solution.pose.links[name].to_local(to)
        turn = _textbook_turn(solution, name, point, local)
        if turn is None:
            _set(doc, ["links", name, "points", point], pair(solution, local))
            continue
        origin, phi = turn  # the link's frame kept the textbook one: its first joint, its second on the x-axis
        c, s = math.cos(phi), math.sin(phi)
        for p in solution.scene.link(name).points:
            if not _written(doc, name, p.name):
                continue
            x, y = (local if p.name == point else p.local)
            x, y = x - origin[0], y - origin[1]
            _set_point(doc, solution, name, p.name, (c * x + s * y, -s * x + c * y))
        given = solution.scene.input
        if isinstance(given, LinkInput) and given.link == name and given.relative_to is None:
            theta = math.remainder(given.angle_rad + phi, 2 * math.pi)  # the crank stays where it is
            value = round(math.degrees(theta), 2) if solution.scene.units.angle == "deg" else round(theta, 5)
            _set(doc, ["input", "angle"], tidy(value))


def _textbook_turn(solution: Solution, link: str, point: str,
                   local: tuple[float, float]) -> tuple[tuple[float, float], float] | None:
    """Where link ``link``'s frame goes when ``point`` moves to ``local`` (its origin, and the turn of its x-axis) so
    that the frame stays the textbook one: the first joint at the origin, the second on the x-axis. None when the
    link is not written so, or its frame means more (the frame link, a slider's block or guide, a gear's or a
    cam's link, a link of a second input or of a relative one)."""
    scene = solution.scene
    points = scene.link(link).points
    if len(points) < 2 or points[0].local != (0.0, 0.0) or points[1].local[1] != 0.0 or points[1].local[0] <= 0.0:
        return None
    fixed = {scene.ground} | {n for s in scene.sliders for n in (s.block, s.guide)}
    fixed |= {n for g in scene.gears for n in g.links} | {n for c in scene.cams for n in (c.cam, c.follower)}
    fixed |= {n for i in scene.more_inputs if isinstance(i, LinkInput) for n in (i.link, i.relative_to)}
    given = scene.input
    if isinstance(given, LinkInput) and given.relative_to is not None:
        fixed |= {given.link, given.relative_to}
    if link in fixed:
        return None
    first = local if points[0].name == point else points[0].local
    second = local if points[1].name == point else points[1].local
    dx, dy = second[0] - first[0], second[1] - first[1]
    if math.hypot(dx, dy) == 0.0:
        return None
    return first, math.atan2(dy, dx)


def _set_point(doc: TOMLDocument, solution: Solution, link: str, point: str, local: tuple[float, float]) -> None:
    """A point's local coordinates written as the scene has them: ``[x, y]``, or ``{ polar = [r, angle] }``."""
    points = doc["links"][link]["points"]
    old = points.get(point)
    if isinstance(old, (Table, InlineTable)) and "polar" in old:
        d = decimals(solution)
        angle = math.atan2(local[1], local[0])
        shown = round(math.degrees(angle), 2) if solution.scene.units.angle == "deg" else round(angle, 5)
        store(old, "polar", [tidy(round(math.hypot(*local), d)), tidy(shown)])
    else:
        _set(doc, ["links", link, "points", point], pair(solution, local))


def _written(doc: TOMLDocument, link: str, point: str) -> bool:
    """Whether the scene's text writes ``point`` in link ``link``'s points (not one the loader made)."""
    links = doc.get("links")
    table = links.get(link) if isinstance(links, (Table, InlineTable)) else None
    points = table.get("points") if isinstance(table, (Table, InlineTable)) else None
    return isinstance(points, (Table, InlineTable)) and point in points


def _drive(doc: TOMLDocument, solution: Solution, to: tuple[float, float]) -> None:
    from kinepoly.editor.evaluate import input_handle

    handle = input_handle(solution)
    given = solution.scene.input
    if handle is None:
        raise EditError("drive: this scene's input cannot be dragged (several inputs, a relative or a given one); "
                        "use its fields")
    at = handle["at"]
    if isinstance(given, LinkInput):
        link = solution.scene.link(given.link)
        frame = {p.name for p in solution.scene.link(str(solution.scene.ground)).points}
        pivot = solution.position(next(p.name for p in link.points if p.name in frame))
        turn = math.atan2(to[1] - pivot[1], to[0] - pivot[0]) - math.atan2(at[1] - pivot[1], at[0] - pivot[0])
        theta = math.remainder(given.angle_rad + turn, 2 * math.pi)
        value = round(math.degrees(theta), 2) if solution.scene.units.angle == "deg" else round(theta, 5)
        _set(doc, ["input", "angle"], tidy(value))
    elif isinstance(given, SliderInput):
        slider = next(s for s in solution.scene.sliders if s.name == given.slider)
        direction = solution.pose.links[slider.guide].theta + slider.angle_rad
        s = given.s + (to[0] - at[0]) * math.cos(direction) + (to[1] - at[1]) * math.sin(direction)
        _set(doc, ["input", "s"], tidy(round(s, decimals(solution))))


def _length(doc: TOMLDocument, solution: Solution, link_name: str, point: str, value: object) -> None:
    if not is_finite_number(value) or value <= 0:
        raise EditError(f"length: {value!r} is not a length; expected a positive number")
    try:
        link = solution.scene.link(link_name)
    except KeyError:
        raise EditError(f"length: no link {link_name!r}") from None
    first, rest = link.points[0], {p.name: p for p in link.points[1:]}
    if point not in rest:
        raise EditError(f"length: link {link_name} has no point {point!r} other than its first, {first.name}")
    if not _written(doc, link_name, point):
        raise EditError(f"length: the scene's [links] does not write {point} in link {link_name} (the loader makes "
                        f"it); change the links it is made of")
    dx, dy = rest[point].local[0] - first.local[0], rest[point].local[1] - first.local[1]
    size = math.hypot(dx, dy)
    if size == 0.0:
        raise EditError(f"length: {point} lies on {first.name}; move it first")
    k = float(value) / size
    _set_point(doc, solution, link_name, point, (first.local[0] + k * dx, first.local[1] + k * dy))


def _set(doc: TOMLDocument, key: list[str | int], value: Any) -> None:
    """Store ``value`` at ``key``: an existing pair of numbers changed in place (its formatting kept), a missing
    table made."""
    node: Any = doc
    for part in key[:-1]:
        if isinstance(part, int):
            if not isinstance(node, list) or not -len(node) <= part < len(node):
                raise EditError(f"set: {'.'.join(map(str, key))}: no item {part}")
            node = node[part]
            continue
        if not isinstance(node, (dict, Table, InlineTable)):
            raise EditError(f"set: {'.'.join(map(str, key))}: {part!r} is not in a table")
        if part not in node:
            node[part] = tomlkit.table()
        node = node[part]
    last = key[-1]
    if not isinstance(node, (dict, Table, InlineTable)) or isinstance(last, int):
        raise EditError(f"set: {'.'.join(map(str, key))}: not a key of a table")
    store(node, last, value)


def _numbers(item: Any) -> list[float] | None:
    if isinstance(item, list) and all(isinstance(x, (int, float)) for x in item):
        return [float(x) for x in item]
    return None


def _key(key: object) -> list[str | int]:
    if not isinstance(key, list) or not key or not all(isinstance(k, (str, int)) and not isinstance(k, bool)
                                                         for k in key):
        raise EditError(f"set: key {key!r}; expected a list of table keys, such as [\"input\", \"omega\"]")
    return list(key)


def _value(value: object) -> Any:
    if isinstance(value, bool) or value is None:
        raise EditError(f"set: value {value!r}; expected a number, a string or a list of numbers")
    if isinstance(value, (int, float)):
        if not is_finite_number(value):
            raise EditError(f"set: value {value!r}; expected a finite number")
        return value
    if isinstance(value, str):
        return value
    if isinstance(value, list) and value and all(is_finite_number(x) for x in value):
        return list(value)
    raise EditError(f"set: value {value!r}; expected a number, a string or a list of numbers")


def _name(name: object) -> str:
    if not isinstance(name, str) or not name:
        raise EditError(f"{name!r} is not a name; expected a point's or a link's name")
    return name
