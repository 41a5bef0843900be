"""The three writers: SVG parsed with ElementTree, DXF read back with ezdxf, PNG and PDF by matplotlib."""

from __future__ import annotations

import io
import math
import re
import xml.etree.ElementTree as ET
from functools import cache
from pathlib import Path

import pytest
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.render.dxf import write_dxf
from kinepoly.render.mpl import write_pdf, write_png
from kinepoly.render.primitives import LAYERS, Arrow, Circle, Sheet, Text
from kinepoly.render.primitives import Path as SheetPath
from kinepoly.render.sheet import build_sheet
from kinepoly.render.svg import number, svg_text

SVG = "{http://www.w3.org/2000/svg}"


@cache
def sheet_of(name: str) -> Sheet:
    return build_sheet(kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml")))


def _xy(d: str) -> list[tuple[float, float]]:
    return [tuple(float(c) for c in part.strip("MLZ ").split(",")) for part in d.split(" L")]  # type: ignore[misc]


@pytest.mark.parametrize("name", ["four-bar", "shaper", "centers-six-bar"])
def test_svg_has_one_group_per_layer_and_its_coordinates_are_the_sheets(name: str) -> None:
    sheet = sheet_of(name)
    root = ET.fromstring(svg_text(sheet))
    assert root.get("viewBox") == f"0 0 {number(sheet.width)} {number(sheet.height)}"
    groups = root.findall(f"{SVG}g")
    assert [g.get("id") for g in groups] == list(LAYERS)
    ids = [e.get("id") for e in root.iter() if e.get("id") is not None]
    assert ids == list(LAYERS)  # deterministic: no automatic ids
    for group, layer in zip(groups, sheet.layers, strict=True):
        arrows = [i for i in layer.items if isinstance(i, Arrow)]
        lines = group.findall(f"{SVG}line")
        assert len(lines) == len(arrows)
        for line, arrow in zip(lines, arrows, strict=True):
            assert float(line.get("x1", "nan")) == pytest.approx(arrow.start[0], abs=6e-4)
            assert float(line.get("y1", "nan")) == pytest.approx(sheet.height - arrow.start[1], abs=6e-4)
        heads = [p for p in group.findall(f"{SVG}path") if p.get("stroke") == "none"]
        assert len(heads) == len(arrows)
        for head, arrow in zip(heads, arrows, strict=True):
            tip = _xy(head.get("d", ""))[0]
            assert math.dist(tip, (arrow.end[0], sheet.height - arrow.end[1])) <= 1e-3
        texts = [i for i in layer.items if isinstance(i, Text)]
        assert ["".join(t.itertext()) for t in group.findall(f"{SVG}text")] == [t.string for t in texts]


def test_svg_is_deterministic_and_its_numbers_short() -> None:
    sheet = sheet_of("slider-crank")
    assert svg_text(sheet) == svg_text(build_sheet(kinepoly.solve(kinepoly.load_scene(EXAMPLES / "slider-crank.toml"))))
    assert number(1.23456) == "1.235" and number(-0.0001) == "0" and number(2.0) == "2" and number(-1.5) == "-1.5"
    attributes = re.findall(r'="([^"]*)"', svg_text(sheet))
    assert not [a for a in attributes if re.search(r"\d[eE][-+]?\d", a)]  # no exponents in coordinates


@pytest.mark.parametrize("name", ["four-bar", "slotted-lever", "image-point"])
def test_dxf_reads_back_with_its_layers_entities_and_a_clean_audit(name: str, tmp_path: Path) -> None:
    import ezdxf

    sheet = sheet_of(name)
    path = tmp_path / f"{name}.dxf"
    with open(path, "w", encoding="utf-8") as stream:
        write_dxf(sheet, stream)
    doc = ezdxf.readfile(str(path))
    assert doc.dxfversion >= "AC1024"  # R2010 or later
    assert doc.header["$INSUNITS"] == 4  # millimetres
    auditor = doc.audit()
    assert not auditor.has_errors, [str(e) for e in auditor.errors]
    msp = doc.modelspace()
    for layer in sheet.layers:
        assert layer.name in doc.layers
        entities = msp.query(f'*[layer=="{layer.name}"]')
        kinds = [e.dxftype() for e in entities]
        arrows = [i for i in layer.items if isinstance(i, Arrow)]
        runs = sum(len(i.runs) for i in layer.items if isinstance(i, Text))
        strokes = sum(1 for i in layer.items if isinstance(i, SheetPath) and i.stroke is not None)
        circles = sum(1 for i in layer.items if isinstance(i, Circle) and i.stroke is not None)
        assert kinds.count("SOLID") == len(arrows)
        assert kinds.count("LINE") == len(arrows)
        assert kinds.count("TEXT") == runs
        assert kinds.count("LWPOLYLINE") == strokes
        assert kinds.count("CIRCLE") == circles
        solids = [e for e in entities if e.dxftype() == "SOLID"]
        for solid, arrow in zip(solids, arrows, strict=True):
            assert math.dist((solid.dxf.vtx0[0], solid.dxf.vtx0[1]), arrow.end) <= 1e-9
    texts = " ".join(e.dxf.text for e in msp.query("TEXT"))  # a long title is wrapped into lines
    assert kinepoly.load_scene(EXAMPLES / f"{name}.toml").title in texts


def test_dxf_is_repeatable(tmp_path: Path) -> None:
    first, second = io.StringIO(), io.StringIO()
    write_dxf(sheet_of("four-bar"), first)
    write_dxf(sheet_of("four-bar"), second)
    assert first.getvalue() == second.getvalue()


def test_png_is_a4_at_the_asked_resolution_and_shows_the_drawing(tmp_path: Path) -> None:
    import numpy as np
    from PIL import Image

    path = tmp_path / "four-bar.png"
    write_png(sheet_of("four-bar"), path, dpi=100)
    with Image.open(path) as image:
        assert abs(image.size[0] - 297 / 25.4 * 100) <= 1 and abs(image.size[1] - 210 / 25.4 * 100) <= 1
        grey = np.asarray(image.convert("L"), dtype=float)
    assert 0.8 < grey.mean() / 255 < 0.99  # mostly paper, some ink
    # the page border: a dark line 10 mm in from the left edge, down the page's middle
    column = round(10 / 25.4 * 100)
    assert grey[grey.shape[0] // 2, column - 1: column + 2].min() < 80


def test_pdf_is_one_page_with_the_title(tmp_path: Path) -> None:
    path = tmp_path / "four-bar.pdf"
    write_pdf(sheet_of("four-bar"), path)
    data = path.read_bytes()
    assert data.startswith(b"%PDF") and data.count(b"/Type /Page\n") + data.count(b"/Type /Page ") >= 1
    assert b"Four-bar with coupler point C" in data
