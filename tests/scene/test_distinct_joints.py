"""The check that a link's joints are at distinct places finds exactly the pairs comparing every pair finds, in
the same order, though it no longer compares every pair (a link with many joints is read in n log n)."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from kinepoly.scene.mechanism_tables import _close_pairs, _same_place

_COORD = st.one_of(st.sampled_from([0.0, 1.0, -1.0, 1e-13, 250.0, 1e6]),
                   st.floats(-1e7, 1e7, allow_nan=False, allow_infinity=False))


def _every_pair(places: list[tuple[float, float]]) -> list[tuple[int, int]]:
    return [(i, j) for i in range(len(places)) for j in range(i + 1, len(places)) if _same_place(places[i], places[j])]


@settings(max_examples=300, deadline=None)
@given(st.lists(st.tuples(_COORD, _COORD), max_size=12), st.data())
def test_the_same_pairs_as_comparing_every_pair(places: list[tuple[float, float]], data: st.DataObject) -> None:
    # repeat some places exactly, or nudged below the tolerance, so that pairs at one place are common
    for _ in range(data.draw(st.integers(0, 4))):
        if places:
            x, y = data.draw(st.sampled_from(places))
            nudge = data.draw(st.sampled_from([0.0, 1e-13, -1e-13, 1e-9]))
            places.insert(data.draw(st.integers(0, len(places))), (x + nudge * max(1.0, abs(x)), y))
    found = [(i, j) for i, j in _close_pairs(places) if _same_place(places[i], places[j])]
    assert found == _every_pair(places)


def test_a_link_with_two_joints_at_one_place_is_named_once_per_pair() -> None:
    places = [(0.0, 0.0), (5.0, 1.0), (0.0, 0.0), (5.0, 1.0 + 1e-14), (3.0, 3.0), (0.0, 0.0)]
    assert [(i, j) for i, j in _close_pairs(places) if _same_place(places[i], places[j])] == \
        [(0, 2), (0, 5), (1, 3), (2, 5)]
