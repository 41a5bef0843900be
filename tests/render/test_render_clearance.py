"""No label touches another label, a line, an arrow or a symbol, and none leaves the page: every example's
drawing, the layout test scenes (a Whitworth quick return, a Stephenson six-bar), and the measure itself
shown to fail where labels do overlap."""

from __future__ import annotations

from pathlib import Path

import pytest
from tests.render.builds import chain
from tests.render.clearance import conflicts
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.render import labels
from kinepoly.render.primitives import Arrow, Layer, Sheet, Stroke, Text
from kinepoly.render.primitives import Path as Line
from kinepoly.render.sheet import build_sheet, layout_sheet
from kinepoly.render.text import plain_runs

LAYOUT_SCENES = Path(__file__).resolve().parent / "scenes"
SCENES = sorted(EXAMPLES.glob("*.toml")) + sorted(LAYOUT_SCENES.glob("*.toml"))


def _sheet(path: Path) -> Sheet:
    return build_sheet(kinepoly.solve(kinepoly.load_scene(path)))


@pytest.mark.parametrize("path", SCENES, ids=lambda p: p.stem)
def test_no_label_touches_anything_on_the_drawing(path: Path) -> None:
    found = conflicts(_sheet(path))
    assert not found, "\n".join(map(str, found))


@pytest.mark.parametrize("paper", ["A4", "A3"])
def test_no_two_labels_overlap_where_a_long_chains_polygon_tips_cluster(paper: str) -> None:
    """A chain of seven four-bar loops: its polygons' tips and short vectors crowd round a few spots, where no place
    near them is free of the lines. Each label there is set out with a leader to a place clear of every other
    label (before: at its anchor, on top of its neighbours, 34 pairs overlapping on A4 and 36 on A3)."""
    solution = chain(7)
    sheet = build_sheet(solution, layout=layout_sheet(solution, paper, grow=False))  # on the paper asked
    overlapping = [c for c in conflicts(sheet) if c.other.startswith("text ")]
    assert not overlapping, "\n".join(map(str, overlapping))
    labels = [item for item in sheet.items() if isinstance(item, Text) and item.anchor is not None]
    leaders = [item for item in sheet.items() if item.role.startswith("leader ")]
    assert len(labels) > 100 and len(leaders) > 10  # the chain's labels are all drawn, the crowded set out


@pytest.mark.slow  # about 1.5 s of CPU each
@pytest.mark.parametrize("paper", ["A4", "A3"])
def test_no_two_labels_overlap_on_a_fifteen_loop_chains_drawing(paper: str) -> None:
    """A chain of fifteen four-bar loops (the scaling benchmark's): its last loops' points converge, their arrows are
    drawn one on another and named in one label, and a label no place out from its point leaves clear of the other
    labels is set where one is, anywhere in its panel, and no label lies on another's leader (before: 41 pairs
    overlapping on A4, 28 on A3, and labels on leaders)."""
    solution = chain(15)
    sheet = build_sheet(solution, layout=layout_sheet(solution, paper, grow=False))
    overlapping = [c for c in conflicts(sheet) if c.other.startswith(("text ", "Path 'leader "))]
    assert not overlapping, "\n".join(map(str, overlapping))
    texts = [item for item in sheet.items() if isinstance(item, Text) and item.anchor is not None]
    assert len(texts) > 120  # the chain's labels are all drawn (144 on A4)


def test_arrows_drawn_one_on_another_are_named_in_one_label() -> None:
    """The fifteen-loop chain's last points converge: v_Q13, v_Q14 and v_Q15 are drawn one on another, and so are
    a_P8 to a_Q15 (before: a label each, the same text three times at one spot, sixteen labels along one shaft).
    Each shaft drawn has one label, which names every arrow drawn there."""
    from kinepoly.render.polygons import FigureDrawing

    def spot(p: tuple[float, float]) -> tuple[float, float]:
        return (round(p[0], 2), round(p[1], 2))

    solution = chain(15)
    layout = layout_sheet(solution, "A4", grow=False)
    joined = 0
    for figure in layout.figures:
        panel = layout.panel(figure.kind)
        assert panel is not None
        items, requests = FigureDrawing(figure, panel).at()
        named = {(spot(r.anchor), spot(r.end)): r.role.removeprefix("vector ").split(", ")
                 for r in requests if r.end is not None}
        labelled = [(spot(r.anchor), spot(r.end)) for r in requests if r.end is not None]
        assert len(labelled) == len(named)  # one label per shaft
        arrows = [item for item in items if isinstance(item, Arrow)]
        assert {(spot(a.start), spot(a.end)) for a in arrows} == set(named)
        for arrow in arrows:
            names = {n for name in named[(spot(arrow.start), spot(arrow.end))] for n in name.split(" = ")}
            assert set(arrow.role.removeprefix("vector ").split(" = ")) <= names
        joined += sum(len(names) > 1 for names in named.values())
    assert joined >= 2


def test_the_layout_scenes_include_six_bars_and_the_whitworth() -> None:
    names = {p.stem for p in SCENES}
    assert {"centers-six-bar", "triad", "stephenson", "whitworth", "toggle-press", "shaper"} <= names


def _label(x: float, y: float, text: str = "v_B") -> Text:
    return Text(x, y, plain_runs(text, 2.6), role=f"tip {text}", anchor=(x, y))


def _one_layer(*items: Text | Arrow | Line) -> Sheet:
    return Sheet(100.0, 80.0, "test", (Layer("mechanism", tuple(items)),))


def test_the_measure_sees_a_label_on_an_arrow_a_label_a_block_and_the_page_edge() -> None:
    arrow = Arrow((10.0, 20.0), (40.0, 20.0), "#000000", 0.35, 2.6, 0.75, role="vector v_A")
    block = Line(((60.0, 50.0), (70.0, 50.0), (70.0, 56.0), (60.0, 56.0)), Stroke(), fill="#ffffff", closed=True,
                 role="block 4")
    assert not conflicts(_one_layer(arrow, block, _label(20.0, 25.0)))  # clear of both: nothing to report
    on_arrow = conflicts(_one_layer(arrow, _label(20.0, 19.5)))
    assert [c.other for c in on_arrow] == ["Arrow 'vector v_A'"]
    on_label = conflicts(_one_layer(_label(20.0, 40.0, "a"), _label(21.0, 40.5, "b")))
    assert len(on_label) == 1 and "text 'b'" in on_label[0].other
    # inside the block's outline, touching no stroke
    inside_block = conflicts(_one_layer(block, _label(62.0, 52.0, "4")))
    assert [c.other for c in inside_block] == ["Path 'block 4'"]
    off_page = conflicts(_one_layer(_label(98.0, 40.0, "long label")))
    assert [c.other for c in off_page] == ["the page's edge"]
    near = conflicts(_one_layer(arrow, _label(20.0, 20.0 + 0.175 + 0.1 + 0.24 * 2.6)))  # 0.1 mm above the shaft
    assert near, "a label 0.1 mm from a line is too close"


def test_the_measure_fails_on_a_real_sheet_whose_labels_are_placed_blindly(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every label at its first candidate place, free or not: the shaper's sheet then has overlaps, and they are
    seen."""
    monkeypatch.setattr(labels.Placer, "_free_of", lambda self, boxes, avoid_fill: (self._inside(b) for b in boxes))
    found = conflicts(_sheet(EXAMPLES / "shaper.toml"))
    assert len(found) >= 5
    assert any("text" in c.other for c in found) and any("Arrow" in c.other for c in found)


def test_labels_with_no_free_place_are_set_clear_of_each_other() -> None:
    """Twelve labels of one point in a mesh of lines 2 mm apart, where every place touches a line (set out with a
    leader from the start, as ``place`` does a point among many): each is put clear of the others (before: all
    twelve at one place, on top of each other), and said to be crowded."""
    from shapely.geometry import box

    mesh = [Line(((x, 0.0), (x, 200.0)), Stroke()) for x in range(0, 201, 2)]
    hard = [g for line in mesh for g in labels.item_pieces(line)]
    placer = labels.Placer((0.0, 0.0, 200.0, 200.0), hard, [], labels._Placed())
    texts = []
    for k in range(12):
        items = placer.at_point((100.0, 100.0), plain_runs(f"p{k}", 2.6), role=f"tip p{k}", far=True)
        texts.append(items[-1])
    boxes = [box(*t.box).buffer(labels.CLEARANCE_MM / 2, join_style="mitre") for t in texts if isinstance(t, Text)]
    assert len(boxes) == 12
    assert not [(i, j) for i in range(12) for j in range(i) if boxes[i].intersects(boxes[j])]
    assert placer.crowded == placer.set_out == [f"tip p{k}" for k in range(12)]


def test_a_label_walled_in_by_other_labels_is_set_where_a_leader_reaches_it_clear_of_them() -> None:
    """A vector's label whose shaft is walled in by other labels from 12 % to 88 % of its length: every place beside
    the shaft touches the wall, and every leader from its middle or from the points along it that the far rings start
    from crosses it. The label is set where a leader from the shaft's free part reaches it, clear of every label
    (before: at its middle, on the wall)."""
    from shapely.geometry import LineString, box

    wall = [box(62.0, 101.5, 138.0, 102.0), box(62.0, 98.0, 138.0, 98.5), box(62.0, 98.0, 62.5, 102.0),
            box(137.5, 98.0, 138.0, 102.0)]
    placed = labels._Placed()
    for brick in wall:
        placed.append(brick)
    shaft = Arrow((50.0, 100.0), (150.0, 100.0), "#000000", 0.35, 2.6, 0.75, role="vector v_B")
    placer = labels.Placer((0.0, 0.0, 200.0, 200.0), labels.item_pieces(shaft), [], placed)
    items = placer.along(shaft.start, shaft.end, plain_runs("v_B", 2.6), role="vector v_B")
    text = items[-1]
    assert isinstance(text, Text)
    label = box(*text.box).buffer(labels.CLEARANCE_MM / 2, join_style="mitre")
    assert not any(label.intersects(brick) for brick in wall)
    leaders = [item for item in items if isinstance(item, Line) and item.role == "leader vector v_B"]
    assert len(leaders) == 1
    leader = LineString(leaders[0].points)
    assert not any(leader.intersects(brick) for brick in wall)
    assert leader.coords[0][1] == pytest.approx(100.0) and not 62.0 <= leader.coords[0][0] <= 138.0  # from the shaft
    assert placer.set_out == ["vector v_B"]
