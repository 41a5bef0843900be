"""``follow_members``: a family's rows, member after member, each followed as ``follow_branch`` follows one sweep.

The telling points are drawn at random: two curves that cross (a parallelogram's change point, where the rule must
keep its course), or stay apart, with rows that do not close; every member's labels must be the labels
``follow_branch`` gives its rows alone.
"""

from __future__ import annotations

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from kinepoly.engine.branches import follow_branch, follow_members


def _member(rng: np.random.Generator, rows: int, crossing: bool, gaps: bool) -> tuple[np.ndarray, np.ndarray,
                                                                                          np.ndarray]:
    t = np.linspace(0.0, 2.0 * np.pi, rows, endpoint=False) + rng.uniform(0, 1)
    path = 10.0 * np.exp(1j * t) + rng.normal(size=2) @ np.array([1.0, 1j])
    apart = (np.sin(t) if crossing else 3.0 + np.cos(t)) * rng.uniform(0.5, 4.0)
    c0, c1 = path + apart * 1j * np.exp(1j * t), path - apart * 1j * np.exp(1j * t)
    ok = np.ones(rows, np.bool_)
    if gaps:
        start = int(rng.integers(0, rows))
        ok[start:start + int(rng.integers(1, max(2, rows // 4)))] = False
    return c0, c1, ok


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), members=st.integers(1, 6), rows=st.integers(3, 80),
       periodic=st.booleans(), gaps=st.booleans(), label=st.integers(0, 1), with_gap=st.booleans())
def test_every_member_is_followed_as_alone(seed: int, members: int, rows: int, periodic: bool, gaps: bool,
                                           label: int, with_gap: bool) -> None:
    rng = np.random.default_rng(seed)
    parts = [_member(rng, rows, bool(rng.integers(0, 2)), gaps) for _ in range(members)]
    c0, c1, ok = (np.concatenate([p[i] for p in parts]) for i in range(3))
    seed_row = int(rng.integers(0, rows))
    gap = np.abs(c0 - c1) if with_gap else None
    found = follow_members(c0, c1, ok, rows, seed_row, label, periodic, gap)
    labels = np.broadcast_to(np.asarray(found, np.int8), (members * rows,))
    for k, (a, b, fine) in enumerate(parts):
        own_gap = None if gap is None else gap[k * rows:(k + 1) * rows]
        alone = follow_branch(a, b, fine, seed_row, label, periodic, own_gap)
        assert np.array_equal(labels[k * rows:(k + 1) * rows], np.broadcast_to(np.asarray(alone, np.int8), (rows,)))


def test_a_member_that_crosses_is_walked_and_the_others_are_settled_at_once() -> None:
    rng = np.random.default_rng(4)
    apart = _member(rng, 40, False, False)
    crossing = _member(rng, 40, True, False)
    c0, c1, ok = (np.concatenate([apart[i], crossing[i]]) for i in range(3))
    found = follow_members(c0, c1, ok, 40, 0, 0, True)
    assert not isinstance(found, int)
    assert (found[:40] == 0).all()
    assert np.array_equal(found[40:], follow_branch(*crossing, 0, 0, True))
