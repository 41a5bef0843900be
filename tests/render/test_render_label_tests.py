"""The label search's cheaper tests give what the plain ones give: a box whose bounds hold a drawn piece's meets it
without the exact test, the others are tested exactly; the pairs come in the order the tree's own query gives (the
ink under a place is summed in that order), and the least inked place, weighed a chunk at a time, is the one all the
places weighed at once give."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st

from kinepoly.render import labels
from kinepoly.render.primitives import Path, Stroke

_COORD = st.floats(0.0, 40.0, allow_nan=False, width=32)


def _pieces(polyline: list[tuple[float, float]], width: float) -> list[Any]:
    return labels.item_pieces(Path(tuple(polyline), Stroke("#000000", width)))


def _boxes(corners: list[tuple[float, float]], size: tuple[float, float]) -> Any:
    b = np.array([(x, y, x + size[0], y + size[1]) for x, y in corners], dtype=float)
    return shapely.box(b[:, 0], b[:, 1], b[:, 2], b[:, 3])


@settings(max_examples=60, deadline=None)
@given(st.lists(st.tuples(_COORD, _COORD), min_size=2, max_size=12), st.floats(0.1, 1.5),
       st.lists(st.tuples(_COORD, _COORD), min_size=1, max_size=40), st.floats(0.5, 8.0), st.floats(0.5, 5.0))
def test_meeting_and_touching_find_what_the_trees_query_finds(polyline: list[tuple[float, float]], width: float,
                                                               corners: list[tuple[float, float]], w: float,
                                                               h: float) -> None:
    pieces = np.asarray(_pieces(polyline, width), dtype=object)
    tree = shapely.STRtree(pieces)
    bounds = shapely.bounds(pieces)
    boxes = _boxes(corners, (w, h))
    which, hit = tree.query(boxes, predicate="intersects")
    found = labels._meeting(tree, pieces, bounds, boxes)
    assert np.array_equal(found[0], which) and np.array_equal(found[1], hit)  # the same pairs, in the same order
    expected = np.zeros(len(boxes), dtype=bool)
    expected[which] = True
    assert np.array_equal(labels._touching(tree, bounds, boxes), expected)


def _least_inked_at_once(placer: labels.Placer, b: Any, leaders: Any) -> tuple[Any, ...] | None:
    """``Placer._least_inked`` as it was written before it weighed the places a chunk at a time: every place inside
    the region tested at once against the placed geometries (exactly), the first of the least weight taken."""
    x0, y0, x1, y1 = placer.region
    inside = (b[:, 0] >= x0) & (b[:, 1] >= y0) & (b[:, 2] <= x1) & (b[:, 3] <= y1)
    b, leaders = b[inside], leaders[inside]
    if not len(b):
        return None
    c = labels.CLEARANCE_MM
    grown = shapely.box(b[:, 0] - c, b[:, 1] - c, b[:, 2] + c, b[:, 3] + c)
    lined = leaders != None  # noqa: E711 (elementwise)
    reach = labels.LEADER.width / 2 + c
    ok = np.ones(len(b), dtype=bool)
    placed = placer._placed
    if len(placed):
        ok[shapely.STRtree(placed.geometries).query(grown, predicate="intersects")[0]] = False
        tags = [g for i, g in enumerate(placed.geometries) if not placed.is_leader(i)]
        tested = np.flatnonzero(ok & lined)
        if len(tested) and tags:
            ok[tested[shapely.STRtree(tags).query(leaders[tested], predicate="dwithin", distance=reach)[0]]] = False
    b, leaders, grown, lined = b[ok], leaders[ok], grown[ok], lined[ok]
    if not len(b):
        return None
    ink = np.zeros(len(b))
    which, hit = placer._hard_tree.query(grown, predicate="intersects")
    if len(which):
        pieces = np.asarray(placer._hard, dtype=object)[hit]
        bounds = shapely.bounds(pieces)
        g = b[which]
        wide = np.minimum(g[:, 2] + c, bounds[:, 2]) - np.maximum(g[:, 0] - c, bounds[:, 0])
        high = np.minimum(g[:, 3] + c, bounds[:, 3]) - np.maximum(g[:, 1] - c, bounds[:, 1])
        spans = np.maximum(bounds[:, 2] - bounds[:, 0], 1e-9) * np.maximum(bounds[:, 3] - bounds[:, 1], 1e-9)
        share = np.clip(wide, 0.0, None) * np.clip(high, 0.0, None) / spans
        np.add.at(ink, which, shapely.area(pieces) * np.minimum(share, 1.0))
    length = np.zeros(len(b))
    length[lined] = shapely.length(leaders[lined])
    cost = ink + labels._LEADER_INK_MM2 * length
    k = int(np.argmin(cost))
    return tuple(float(v) for v in b[k]), leaders[k], float(cost[k])


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(_COORD, _COORD), min_size=2, max_size=30), st.floats(0.1, 1.0),
       st.lists(st.tuples(_COORD, _COORD), min_size=0, max_size=12), st.tuples(_COORD, _COORD),
       st.integers(0, 3))
def test_the_least_inked_place_is_the_one_all_places_weighed_at_once_give(
        polyline: list[tuple[float, float]], width: float, taken: list[tuple[float, float]],
        anchor: tuple[float, float], feet: int) -> None:
    """A mesh of strokes, labels placed here and there (some with leaders), and a label set out from a point and from
    up to three feet: the place chosen (box, leader, weight) is the plain search's."""
    region = (-60.0, -60.0, 100.0, 100.0)
    hard = _pieces(polyline, width)
    placed = labels._Placed()
    placer = labels.Placer(region, hard, [], placed)
    size = (4.0, 2.5)
    for x, y in taken:  # the labels placed before, every other one set out with a leader
        box = (x, y, x + size[0], y + size[1])
        placed.append(shapely.box(*box))  # as ``Placer._accept`` places them
        if len(placed) % 3:
            placed.append(shapely.LineString([(x - 3.0, y - 3.0), (x - 0.2, y - 0.2)]).buffer(labels.LEADER.width / 2),
                          leader=True)
    points = [anchor] + [(anchor[0] + 2.0 * k, anchor[1] - 1.5 * k) for k in range(1, feet + 1)]
    boxes, leaders = labels._set_out_places(points, size)
    expected = _least_inked_at_once(placer, boxes, leaders)
    found = placer._least_inked(boxes, leaders, budgeted=False)
    if expected is None:
        assert found is None
        return
    assert found is not None
    assert found[0] == expected[0] and found[3] == expected[2]
    assert (found[1] is None) == (expected[1] is None)
    assert found[1] is None or shapely.equals_exact(found[1], expected[1], 0.0)
    assert math.isfinite(found[3])


def test_a_place_beyond_the_first_chunk_is_found_where_the_lighter_ones_lie_on_ink() -> None:
    """Lines 2 mm apart over 70 mm round the point, labels placed clear of them beyond: every place within the first
    chunk's reach lies on ink, and the place chosen further out is the plain search's."""
    hard = []
    for k in range(-17, 18):
        hard += _pieces([(-35.0, 2.0 * k + 0.5), (35.0, 2.0 * k + 0.5)], 0.3)
        hard += _pieces([(2.0 * k + 0.5, -35.0), (2.0 * k + 0.5, 35.0)], 0.3)
    placed = labels._Placed()
    for angle in range(0, 360, 30):  # labels out at 45 mm, each on every other direction
        x, y = 45.0 * math.cos(math.radians(angle)), 45.0 * math.sin(math.radians(angle))
        placed.append(shapely.box(x, y, x + 4.0, y + 2.5))
    placer = labels.Placer((-120.0, -120.0, 120.0, 120.0), hard, [], placed)
    boxes, leaders = labels._set_out_places([(0.0, 0.0), (1.0, -0.5)], (4.0, 2.5))
    expected = _least_inked_at_once(placer, boxes, leaders)
    found = placer._least_inked(boxes, leaders, budgeted=False)
    assert expected is not None and found is not None
    assert found[0] == expected[0] and found[3] == expected[2]
    weights = np.sort(labels._LEADER_INK_MM2 * shapely.length(leaders[leaders != None]))  # noqa: E711
    assert found[3] > weights[labels._INK_CHUNK]  # beyond the first chunk
