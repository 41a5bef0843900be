"""``layout.arrange`` skips the levels it knows cannot win (issue 28's speed-up): it still picks what trying every
arrangement at every level picks."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from kinepoly.render import layout
from kinepoly.render.layout import Content, Panel

_SIDE = st.floats(min_value=1.0, max_value=400.0)
_SCALE = st.sampled_from([0.05, 0.1, 0.2, 0.25, 0.5, 1.0, 2.0, 2.5, 5.0])


def _every_try(contents: list[Content], area: tuple[float, float, float, float]) -> list[Panel]:
    """The best panels over every arrangement and every level, each level's scales stepped down from scratch."""
    fixed = [k for k, c in enumerate(contents) if c.wanted is not None]
    best, best_score = None, None
    for columns in layout._columns(len(contents)):
        for levels in layout._levels(len(fixed)):
            scales = {k: layout._step_down(contents[k].wanted or 1.0, n) for k, n in zip(fixed, levels, strict=True)}
            panels = layout._try(contents, area, columns, scales)
            if panels is None:
                continue
            score = layout._score(panels, contents, area)
            if best_score is None or score > best_score:
                best, best_score = panels, score
    return best if best is not None else layout._one_row(contents, area, fixed)


@settings(max_examples=150, deadline=None)
@given(sides=st.lists(st.tuples(_SIDE, _SIDE), min_size=3, max_size=4), scales=st.lists(_SCALE, min_size=3, max_size=3),
       width=st.floats(min_value=120.0, max_value=800.0), height=st.floats(min_value=80.0, max_value=600.0))
def test_arrange_picks_what_trying_everything_picks(sides: list[tuple[float, float]], scales: list[float],
                                                    width: float, height: float) -> None:
    names = ["mechanism", "velocity", "acceleration", "centers"][:len(sides)]
    wanted: list[float | None] = [None, *scales[:len(sides) - 1]]
    contents = [Content(name, (0.0, 0.0, w, h), k, 9.0) for name, (w, h), k in zip(names, sides, wanted, strict=True)]
    area = (13.0, 40.0, 13.0 + width, 40.0 + height)
    assert layout.arrange(contents, area) == _every_try(contents, area)
