"""An animation's label stays where it was on the frame before while that place is free (``LabelCache.hints``):
beside its point on the same side, along its arrow at the same spot, out on the same leader. Where that place is
taken, the free place nearest it is tried first. Frames then flicker less, and each costs less: most labels take
their first place tried."""

from __future__ import annotations

import math

from tests.render.clearance import conflicts
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.motion.frames import make_frames
from kinepoly.motion.sheets import frame_sheets, frame_solutions
from kinepoly.render.labels import LabelCache, Request, place
from kinepoly.render.primitives import Path as Line
from kinepoly.render.primitives import Sheet, Stroke, Text
from kinepoly.render.text import plain_runs
from kinepoly.sweep.run import prepare_sweep, run_sweep

_ANCHOR = (50.0, 50.0)
_REQUEST = Request("labels", (0.0, 0.0, 100.0, 100.0), plain_runs("B", 2.6), _ANCHOR, role="point B")
_KEY = "labels point B"


def _centre(items: dict[str, list[object]]) -> tuple[float, float]:
    text = next(item for item in items["labels"] if isinstance(item, Text))
    x0, y0, x1, y1 = text.box
    return ((x0 + x1) / 2, (y0 + y1) / 2)


def test_a_label_is_tried_first_where_it_was() -> None:
    alone = LabelCache()
    first = _centre(place([_REQUEST], [], alone))
    assert first[0] > _ANCHOR[0] and first[1] > _ANCHOR[1]  # the first place tried: up and to the right
    assert alone.taken == {_KEY: ("near", 0)}
    followed = LabelCache({_KEY: ("near", 5)})  # on the frame before it was left of its point (the 6th place)
    left = _centre(place([_REQUEST], [], followed))
    assert left[0] < _ANCHOR[0] - 1.0 and abs(left[1] - _ANCHOR[1]) < 0.5
    assert followed.taken == {_KEY: ("near", 5)}


def test_where_that_place_is_taken_the_nearest_free_one_is_tried_first() -> None:
    was = _centre(place([_REQUEST], [], LabelCache({_KEY: ("near", 5)})))  # left of B, as on the frame before
    wall = Line(((47.5, 40.0), (47.5, 60.0)), Stroke("#000000", 0.35))  # a line across that place
    alone = _centre(place([_REQUEST], [wall], LabelCache()))
    assert alone[0] > _ANCHOR[0]  # without a hint: up and to the right, the first place tried
    cache = LabelCache({_KEY: ("near", 5)})
    followed = _centre(place([_REQUEST], [wall], cache))
    assert cache.taken[_KEY] != ("near", 5) and followed[0] < _ANCHOR[0]  # moved, but still on the left
    assert math.dist(followed, was) < math.dist(alone, was)


def _frames(name: str, positions: int) -> list[Sheet]:
    scene = kinepoly.load_scene(EXAMPLES / f"{name}.toml")
    prepared = prepare_sweep(scene)
    frames = make_frames(run_sweep(prepared, steps=positions), prepared)
    return list(frame_sheets(frames, frame_solutions(frames, scene)))


def _offsets(sheet: Sheet) -> dict[tuple[str, str], tuple[float, float]]:
    """Each label's centre, from its anchor (mm)."""
    out = {}
    for layer in sheet.layers:
        for item in layer.items:
            if isinstance(item, Text) and item.anchor is not None and not item.role.startswith("caption"):
                x0, y0, x1, y1 = item.box
                out[layer.name, item.role] = ((x0 + x1) / 2 - item.anchor[0], (y0 + y1) / 2 - item.anchor[1])
    return out


def test_labels_keep_their_places_from_frame_to_frame() -> None:
    """A four-bar over 36 frames: the share of labels that move more than 3 mm about their anchor from one frame
    to the next (an arrow's label moves with its arrow's length and turn). Each frame placed alone: 0.43."""
    moved = compared = 0
    before: dict[tuple[str, str], tuple[float, float]] | None = None
    for sheet in _frames("four-bar", 36):
        now = _offsets(sheet)
        if before is not None:
            common = now.keys() & before.keys()
            compared += len(common)
            moved += sum(math.dist(now[k], before[k]) > 3.0 for k in common)
        before = now
    assert compared > 500
    assert moved / compared < 0.35, moved / compared


def test_no_label_lies_on_another_on_any_frame() -> None:
    """The lifting platform over 24 frames (each frame placed alone: 3 pairs of labels overlapped)."""
    for k, sheet in enumerate(_frames("platform-lift", 24)):
        found = [c for c in conflicts(sheet) if c.other.startswith("text ")]
        assert not found, (k, [str(c) for c in found])
