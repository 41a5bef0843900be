"""The backend-neutral sheet: arrows at scale times vector, labels clear of everything, only what is asked."""

from __future__ import annotations

import math
from functools import cache
from itertools import combinations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from tests.scenes import EXAMPLES, four_bar

import kinepoly
from kinepoly.render.labels import item_geometry
from kinepoly.render.layout import nice_floor, paper_size
from kinepoly.render.polygons import polygon_figure
from kinepoly.render.primitives import LAYERS, Arrow, Circle, Path, Sheet, Text
from kinepoly.render.sheet import build_sheet, layout_sheet, step_sheets
from kinepoly.render.text import text_width
from kinepoly.solution import Solution

NAMES = sorted(p.stem for p in EXAMPLES.glob("*.toml"))


@cache
def solved(name: str) -> Solution:
    return kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))


@cache
def sheet_of(name: str, paper: str = "A4") -> Sheet:
    return build_sheet(solved(name), paper)


def _arrows(sheet: Sheet, layer: str) -> dict[str, Arrow]:
    return {item.role: item for item in sheet.layer(layer).items if isinstance(item, Arrow)}


@pytest.mark.parametrize("name", NAMES)
def test_every_absolute_arrow_ends_at_scale_times_the_solved_vector(name: str) -> None:
    sol = solved(name)
    layout = layout_sheet(sol)
    sheet = sheet_of(name)
    for kind, polygon in (("velocity", sol.velocity), ("acceleration", sol.acceleration)):
        if polygon is None:
            assert not sheet.layer(f"{kind}-polygon").items
            continue
        panel = layout.panel(kind)
        assert panel is not None
        arrows = _arrows(sheet, f"{kind}-polygon")
        symbol = "v" if kind == "velocity" else "a"
        checked = 0
        for label, tip in polygon.tips.items():
            arrow = next((a for role, a in arrows.items() if role == f"vector {symbol}_{label}"
                          or role.startswith(f"vector {symbol}_{label} =")), None)
            if arrow is None:
                continue
            checked += 1
            assert arrow.start == pytest.approx(panel.origin, abs=1e-9)
            expected = (panel.origin[0] + panel.scale * tip[0], panel.origin[1] + panel.scale * tip[1])
            assert math.dist(arrow.end, expected) <= 1e-9
        assert checked >= 1


@pytest.mark.parametrize("name", NAMES)
def test_every_term_arrow_runs_from_scale_times_start_to_scale_times_end(name: str) -> None:
    sol = solved(name)
    layout = layout_sheet(sol)
    for figure in layout.figures:
        panel = layout.panel(figure.kind)
        assert panel is not None
        arrows = _arrows(sheet_of(name), f"{figure.kind}-polygon")
        for vector in figure.vectors:
            arrow = arrows.get(f"vector {vector.label}")
            if arrow is None:  # a tiny vector, drawn as a dot
                assert panel.scale * math.dist(vector.start, vector.end) < 4.0
                continue
            for drawn, physical in ((arrow.start, vector.start), (arrow.end, vector.end)):
                expected = (panel.origin[0] + panel.scale * physical[0], panel.origin[1] + panel.scale * physical[1])
                assert math.dist(drawn, expected) <= 1e-9


def test_the_figure_lays_each_intersection_term_from_its_line_to_the_new_tip() -> None:
    sol = solved("four-bar")
    figure = polygon_figure(sol, "velocity")
    v_ba = next(v for v in figure.vectors if v.label == "v_B/A")
    assert v_ba.start == pytest.approx(sol.velocity.tips["A"], abs=1e-12)  # type: ignore[union-attr]
    assert v_ba.end == pytest.approx(sol.velocity.tips["B"], abs=1e-12)  # type: ignore[union-attr]
    # v_B/A is perpendicular to AB (the textbook's direction line), independent of the construction
    a, b = sol.position("A"), sol.position("B")
    d = (v_ba.end[0] - v_ba.start[0], v_ba.end[1] - v_ba.start[1])
    assert abs(d[0] * (b[0] - a[0]) + d[1] * (b[1] - a[1])) <= 1e-9 * math.hypot(*d) * math.dist(a, b)


@pytest.mark.parametrize("name", NAMES)
def test_no_arrow_is_shorter_than_its_head(name: str) -> None:
    for item in sheet_of(name).items():
        if isinstance(item, Arrow):
            assert item.length >= item.head_length - 1e-12, item.role


def _own(text: Text, item: object) -> bool:
    role = getattr(item, "role", "")
    return role in (f"leader {text.role}", f"ring {text.role}")


@pytest.mark.parametrize("name", NAMES)
def test_no_label_touches_drawn_geometry_or_another_label(name: str) -> None:
    sheet = sheet_of(name)
    from shapely import STRtree

    drawn = [item for item in sheet.items() if not isinstance(item, Text)]
    geometries = [item_geometry(item) for item in drawn]
    tree = STRtree(geometries)
    labels = [item for item in sheet.items() if isinstance(item, Text) and item.anchor is not None]
    assert labels
    for text in labels:
        box = item_geometry(text)
        for k in tree.query(box, predicate="intersects"):
            assert _own(text, drawn[k]), f"{text.string!r} ({text.role}) touches {drawn[k].role}"
    for first, second in combinations([t for t in sheet.items() if isinstance(t, Text)], 2):
        if first.anchor is None and second.anchor is None:
            continue  # the title block's own lines are laid out in rows, not placed
        assert not item_geometry(first).intersects(item_geometry(second)), (first.string, second.string)


@pytest.mark.parametrize("name", NAMES)
def test_nothing_is_cut_off_by_the_page_and_panels_do_not_overlap(name: str) -> None:
    sheet = sheet_of(name)
    for item in sheet.items():
        x0, y0, x1, y1 = item_geometry(item).bounds
        assert 0.0 <= x0 and x1 <= sheet.width and 0.0 <= y0 and y1 <= sheet.height, item.role
    panels = layout_sheet(solved(name)).panels
    for p, q in combinations(panels, 2):
        overlap_x = min(p.rect[2], q.rect[2]) - max(p.rect[0], q.rect[0])
        overlap_y = min(p.rect[3], q.rect[3]) - max(p.rect[1], q.rect[1])
        assert overlap_x <= 1e-9 or overlap_y <= 1e-9, (p.name, q.name)


@pytest.mark.parametrize("name", NAMES)
def test_only_what_the_scene_asks_is_drawn(name: str) -> None:
    sol, sheet = solved(name), sheet_of(name)
    assert [layer.name for layer in sheet.layers] == list(LAYERS)
    assert bool(sheet.layer("acceleration-polygon").items) == (sol.acceleration is not None)
    assert bool(sheet.layer("velocity-polygon").items) == (sol.velocity is not None)
    assert bool(sheet.layer("instant-centers").items) == bool(sol.scene.find.instant_centers)


def test_no_acceleration_polygon_when_only_velocities_are_asked() -> None:
    text = four_bar(100, 40, 120, 80, 60, 10, 5, (110, 80), find='[find]\nvelocity = ["B"]\n')
    sheet = build_sheet(kinepoly.solve(kinepoly.loads_scene(text)))
    assert not sheet.layer("acceleration-polygon").items
    assert not any(isinstance(i, Text) and "Acceleration" in i.string for i in sheet.items())


def test_instant_centers_are_labelled_points_and_the_circle_diagram_has_every_link() -> None:
    sol, sheet = solved("centers-six-bar"), sheet_of("centers-six-bar")
    assert sol.centers is not None
    roles = {item.role for item in sheet.layer("instant-centers").items}
    for name in sol.centers.centers:
        assert f"center I{name}" in roles or f"center I{name} toward" in roles
    for link in sol.mechanism.link_names:
        assert f"diagram link {link}" in roles
    toward = [i for i in sheet.layer("instant-centers").items if isinstance(i, Arrow) and i.role == "center I16 toward"]
    assert len(toward) == 1  # the slider's center at infinity, perpendicular to the slide (straight up)
    d = (toward[0].end[0] - toward[0].start[0], toward[0].end[1] - toward[0].start[1])
    assert abs(d[0]) <= 1e-9 * math.hypot(*d) and d[1] > 0


@pytest.mark.parametrize("name", ["four-bar", "shaper", "image-point"])
def test_step_sheets_grow_one_step_at_a_time_and_end_as_the_drawing(name: str) -> None:
    sol = solved(name)
    sheets = step_sheets(sol)
    assert len(sheets) == len(sol.steps)
    counts = [sum(isinstance(i, Arrow) for layer in ("velocity-polygon", "acceleration-polygon")
                  for i in s.layer(layer).items) for s in sheets]
    assert counts == sorted(counts) and counts[0] < counts[-1]
    final = {i.role for layer in ("velocity-polygon", "acceleration-polygon") for i in sheet_of(name).layer(layer).items
             if isinstance(i, Arrow)}
    last = {i.role for layer in ("velocity-polygon", "acceleration-polygon") for i in sheets[-1].layer(layer).items
            if isinstance(i, Arrow)}
    assert last == final
    for number, sheet in enumerate(sheets, 1):
        title = [i.string for i in sheet.layer("title").items if isinstance(i, Text)]
        assert f"Step {number} of {len(sheets)}" in title


def test_text_widths_match_what_matplotlib_renders() -> None:
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(4, 2), dpi=200)
    canvas = FigureCanvasAgg(fig)
    renderer = canvas.get_renderer()
    for text, bold in (("v_B/A = 388.37 mm/s", False), ("Four-bar with coupler point C", True),
                       ("ωαθ°² o′, a′0", False)):
        size_mm = 10.0
        artist = fig.text(0, 0.5, text, fontsize=size_mm * 72 / 25.4, family="DejaVu Sans",
                          weight="bold" if bold else "normal")
        width_mm = artist.get_window_extent(renderer).width / 200 * 25.4
        assert width_mm == pytest.approx(text_width(text, size_mm, bold), rel=0.03)


@settings(max_examples=40, deadline=None)
@given(st.floats(min_value=1e-6, max_value=1e6))
def test_nice_floor_is_a_round_number_not_above_and_within_a_factor_of_two(x: float) -> None:
    y = nice_floor(x)
    assert y <= x * (1 + 1e-12) and y > x / 2.01
    mantissa = y / 10 ** math.floor(math.log10(y) + 1e-12)
    assert min(abs(mantissa - m) for m in (1, 2, 2.5, 5)) < 1e-9


def test_paper_sizes() -> None:
    assert paper_size("A4") == (297.0, 210.0)
    assert paper_size("a3-portrait") == (297.0, 420.0)
    assert paper_size("500x300") == (500.0, 300.0)
    with pytest.raises(ValueError, match="A4"):
        paper_size("B7")


def test_a_larger_paper_keeps_the_scenes_scales_and_a_portrait_one_still_fits() -> None:
    for paper in ("A3", "A4-portrait", "letter"):
        sheet = build_sheet(solved("shaper"), paper)
        for item in sheet.items():
            x0, y0, x1, y1 = item_geometry(item).bounds
            assert 0.0 <= x0 and x1 <= sheet.width and 0.0 <= y0 and y1 <= sheet.height


def test_paths_and_circles_have_finite_coordinates() -> None:
    for name in NAMES:
        for item in sheet_of(name).items():
            if isinstance(item, Path):
                assert all(math.isfinite(c) for p in item.points for c in p)
            if isinstance(item, Circle):
                assert item.radius > 0
