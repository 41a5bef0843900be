"""A draft sheet (the editor's while the user drags): the whole sheet but for its labels, each set at the first place
the search tries, next to what it names, with no search for a free one."""

from __future__ import annotations

import math
from collections import Counter

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.render.labels import LabelCache, Request, draft_place, place
from kinepoly.render.primitives import Item, Path, Sheet, Stroke, Text
from kinepoly.render.sheet import build_sheet, layout_sheet
from kinepoly.render.svg import svg_text
from kinepoly.render.text import Run

_REGION = (0.0, 0.0, 100.0, 100.0)


def _is_label(item: Item) -> bool:
    """What ``place`` adds to a sheet: a label's text (it names an anchor), its leader, its ring."""
    return (isinstance(item, Text) and item.anchor is not None) or item.role.startswith(("leader ", "ring "))


def _labels(sheet: Sheet) -> Counter[tuple[str, str, str, str]]:
    return Counter((layer.name, item.role, item.string, item.color) for layer in sheet.layers for item in layer.items
                   if isinstance(item, Text) and item.anchor is not None)


def _sheets(name: str) -> tuple[Sheet, Sheet]:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    whole = build_sheet(solution, layout=layout_sheet(solution, (297.0, 210.0), grow=False))
    draft = build_sheet(solution, layout=layout_sheet(solution, (297.0, 210.0), grow=False), draft=True)
    return whole, draft


@pytest.mark.parametrize("name", ["four-bar", "centers-six-bar", "shaper"])
def test_a_draft_is_the_whole_sheet_but_for_where_its_labels_sit(name: str) -> None:
    whole, draft = _sheets(name)
    assert [layer.name for layer in draft.layers] == [layer.name for layer in whole.layers]
    for a, b in zip(whole.layers, draft.layers, strict=True):  # everything drawn but the labels: the same, in order
        assert [i for i in a.items if not _is_label(i)] == [i for i in b.items if not _is_label(i)], a.name
    assert _labels(draft) == _labels(whole)  # the same labels, in the same layers
    moved = sum(1 for layer in draft.layers for item in layer.items
                if isinstance(item, Text) and item.anchor is not None and item not in whole.layer(layer.name).items)
    assert moved > 0  # the whole sheet searched some of them clear of the drawing
    assert not any(item.role.startswith("leader ") for layer in draft.layers for item in layer.items)
    # in the SVG too: the lines of the labels (their texts, leaders, rings) aside, the files are the same
    roles = {item.role for layer in whole.layers for item in layer.items if _is_label(item)}
    roles |= {item.role for layer in draft.layers for item in layer.items if _is_label(item)}

    def rest(svg: str) -> list[str]:
        return [line for line in svg.splitlines() if not any(f'data-role="{r}"' in line for r in roles)]

    assert rest(svg_text(draft)) == rest(svg_text(whole))
    assert svg_text(draft) != svg_text(whole)


def test_a_draft_point_label_sits_up_and_right_of_its_point_at_its_gap() -> None:
    runs = (Run("B", 0.0, 0.0, 3.0),)
    request = Request("mechanism", _REGION, runs, (50.0, 50.0), role="point B", gap=0.6)
    drawn = Path(((40.0, 40.0), (60.0, 60.0)), Stroke("#000000", 0.5))  # through the first place
    (text,) = draft_place([request])["mechanism"]
    assert isinstance(text, Text)
    x0, y0, x1, y1 = text.box
    assert (x0 + x1) / 2 - 50.0 == pytest.approx((y0 + y1) / 2 - 50.0)  # its centre on the ray at 45 degrees
    assert min(x0, y0) > 50.0  # wholly up and to the right of the point
    assert math.hypot(x0 - 50.0, y0 - 50.0) == pytest.approx(0.6 + 0.5)  # 0.5 mm beyond the gap
    (searched,) = place([request], [drawn], LabelCache())["mechanism"]
    assert isinstance(searched, Text) and searched.box != text.box  # the search takes it off the stroke


def test_a_draft_vector_label_sits_beside_the_middle_of_its_shaft() -> None:
    runs = (Run("v_B", 0.0, 0.0, 3.0),)
    request = Request("velocity-polygon", _REGION, runs, (10.0, 20.0), end=(30.0, 20.0), role="vector vB")
    (text,) = draft_place([request])["velocity-polygon"]
    assert isinstance(text, Text)
    x0, y0, x1, _ = text.box
    assert (x0 + x1) / 2 == pytest.approx(20.0) and y0 == pytest.approx(20.5)  # left of the shaft, 0.5 mm off


def test_a_draft_keeps_the_order_and_layers_of_the_labels_as_place_gives_them() -> None:
    requests = [Request("mechanism" if k % 2 else "velocity-polygon", _REGION, (Run(f"P{k}", 0.0, 0.0, 3.0),),
                        (10.0 * k, 10.0), role=f"point P{k}", priority=3 - k % 3) for k in range(1, 7)]
    whole = place(requests, [], LabelCache())
    draft = draft_place(requests)
    assert {layer: [t.role for t in items] for layer, items in draft.items()} == \
        {layer: [t.role for t in items] for layer, items in whole.items()}
