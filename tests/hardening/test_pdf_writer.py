"""Issue 15: the PDF written directly (``render.pdf``) draws what matplotlib draws, text that reads back,
and layers shared by pages written once (a handout's file grows with what its pages add).

The file is read here with a parser of its own (objects, streams, the ToUnicode map), not with
the writer's code; the page is rasterised by poppler (``pdftoppm``, when installed) and compared
with matplotlib's PNG of the same sheet.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import zlib
from functools import cache
from pathlib import Path
from typing import Any

import pytest
from msgspec.structs import replace
from tests.scenes import EXAMPLES

import kinepoly
from kinepoly.render.mpl import write_pdf, write_png
from kinepoly.render.pdf import pdf_bytes
from kinepoly.render.primitives import Layer, Sheet, Stroke, Text
from kinepoly.render.primitives import Path as Line
from kinepoly.render.sheet import build_sheet
from kinepoly.render.text import Run

_PT_PER_MM = 72.0 / 25.4


@cache
def sheet_of(name: str) -> Sheet:
    return build_sheet(kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml")))


def _objects(data: bytes) -> dict[int, bytes]:
    return {int(m.group(1)): m.group(2) for m in re.finditer(rb"(\d+) 0 obj\n(.*?)\nendobj\n", data, re.DOTALL)}


def _stream(body: bytes) -> bytes:
    raw = body.split(b"stream\n", 1)[1].rsplit(b"\nendstream", 1)[0]
    return zlib.decompress(raw) if b"/FlateDecode" in body.split(b"stream\n", 1)[0] else raw


def _cmaps(objects: dict[int, bytes]) -> dict[str, dict[int, str]]:
    """Font resource name (F1, F2) -> glyph id -> the text it stands for, from each font's ToUnicode map."""
    out = {}
    resources = next(body for body in objects.values() if body.startswith(b"<< /Font <<"))
    for name, number in re.findall(rb"/(F\d) (\d+) 0 R", resources):
        font = objects[int(number)]
        cmap = _stream(objects[int(re.search(rb"/ToUnicode (\d+) 0 R", font).group(1))]).decode()
        out[name.decode()] = {int(g, 16): bytes.fromhex(u).decode("utf-16-be")
                              for part in re.findall(r"beginbfchar\n(.*?)\nendbfchar", cmap, re.DOTALL)
                              for g, u in re.findall(r"<([0-9A-F]{4})> <([0-9A-F]+)>", part)}
    return out


def _shown_text(data: bytes) -> list[str]:
    """Every run of text the file shows, decoded through its fonts' ToUnicode maps."""
    objects = _objects(data)
    cmaps = _cmaps(objects)
    runs = []
    for body in objects.values():
        if b"/Subtype /Form" not in body.split(b"stream\n", 1)[0]:
            continue
        for font, hexes in re.findall(r"/(F\d) [\d.]+ Tf [^<]*<([0-9A-F]*)> Tj", _stream(body).decode()):
            runs.append("".join(cmaps[font].get(int(hexes[k:k + 4], 16), "\ufffd") for k in range(0, len(hexes), 4)))
    return runs


def test_a_sheet_is_one_page_of_its_size_with_every_label_readable_back() -> None:
    sheet = sheet_of("four-bar")
    data = pdf_bytes([sheet], sheet.title)
    assert data.startswith(b"%PDF-") and data.rstrip().endswith(b"%%EOF")
    assert len(re.findall(rb"/Type /Page[^s]", data)) == 1
    box = [float(v) for v in re.search(rb"/MediaBox \[0 0 ([\d.]+) ([\d.]+)\]", data).groups()]
    assert box == pytest.approx([sheet.width * _PT_PER_MM, sheet.height * _PT_PER_MM], abs=1e-3)
    assert data.count(b"/FontFile2") == 2 and b"/CIDFontType2" in data  # both weights embedded, TrueType
    shown = _shown_text(data)
    expected = [run.text for item in sheet.items() if isinstance(item, Text) for run in item.runs if run.text]
    assert sorted(shown) == sorted(expected)


def test_the_same_sheets_give_the_same_bytes_and_titles_of_any_script_are_kept() -> None:
    sheet = sheet_of("four-bar")
    assert pdf_bytes([sheet], "a") == pdf_bytes([sheet], "a")
    assert b"/Title (Four-bar \\(x\\))" in pdf_bytes([sheet], "Four-bar (x)")
    turkish = "Dört çubuk: hız çokgeni"
    assert b"/Title <FEFF" + turkish.encode("utf-16-be").hex().upper().encode() + b">" in pdf_bytes([sheet], turkish)


def test_a_letter_the_font_lacks_is_its_box_and_nothing_fails() -> None:
    sheet = Sheet(100.0, 100.0, "t", (Layer("title", (Text(10.0, 10.0, (Run("a中b", 0.0, 0.0, 3.0),)),)),))
    data = pdf_bytes([sheet], "t")
    assert _shown_text(data) == ["a\ufffdb"]  # glyph 0 (.notdef) has no Unicode: drawn as the font's box


def test_layers_the_pages_share_are_written_once() -> None:
    sheet = sheet_of("four-bar")
    layers = [layer for layer in sheet.layers if layer.items]
    pages = [replace(sheet, layers=(*sheet.layers, Layer("title", (Text(5.0, 5.0, (Run(f"page {k}", 0, 0, 3.0),)),))))
             for k in range(12)]
    data = pdf_bytes(pages, "t")
    forms = sum(1 for body in _objects(data).values() if b"/Subtype /Form" in body.split(b"stream\n", 1)[0])
    assert len(re.findall(rb"/Type /Page[^s]", data)) == 12
    assert forms == len(layers) + 12  # each shared layer once, each page's own text once
    one = len(pdf_bytes(pages[:1], "t"))
    assert len(data) < one + 12 * 1200  # a page more costs its few bytes, not the drawing again


def test_strokes_keep_their_width_dash_and_colour() -> None:
    line = Line(((10.0, 20.0), (50.0, 20.0)), Stroke("#ff0000", 0.5, (2.0, 1.0)))
    data = pdf_bytes([Sheet(100.0, 50.0, "t", (Layer("mechanism", (line,)),))], "t")
    form = next(_stream(b) for b in _objects(data).values() if b"/Subtype /Form" in b.split(b"stream\n", 1)[0])
    assert form.decode().strip() == "1 0 0 RG 0.5 w 0 J 0 j [2 1] 0 d 10 20 m 50 20 l S"


@pytest.mark.skipif(shutil.which("pdftoppm") is None, reason="poppler's pdftoppm is not installed")
@pytest.mark.parametrize("name", ["four-bar", "slider-crank"])
def test_the_page_looks_as_matplotlib_draws_it(name: str, tmp_path: Path) -> None:
    """Rasterised at 100 dpi, the PDF page and matplotlib's PNG of the sheet differ only at the edges of
    strokes and glyphs (antialiasing, dash phase): the same ink in the same places."""
    import numpy as np
    from PIL import Image

    sheet = sheet_of(name)
    write_pdf(sheet, tmp_path / "s.pdf")
    write_png(sheet, tmp_path / "m.png", dpi=100)
    subprocess.run(["pdftoppm", "-png", "-r", "100", "-singlefile", str(tmp_path / "s.pdf"), str(tmp_path / "p")],
                   check=True)
    with Image.open(tmp_path / "p.png") as a, Image.open(tmp_path / "m.png") as b:
        pdf, png = (np.asarray(i.convert("L"), dtype=float) / 255 for i in (a, b))
    h, w = min(pdf.shape[0], png.shape[0]), min(pdf.shape[1], png.shape[1])
    assert abs(pdf.shape[0] - png.shape[0]) <= 1 and abs(pdf.shape[1] - png.shape[1]) <= 1
    pdf, png = pdf[:h, :w], png[:h, :w]
    ink_pdf, ink_png = pdf < 0.5, png < 0.5
    assert abs(ink_pdf.mean() - ink_png.mean()) < 0.15 * ink_png.mean()  # as much ink
    # every dark pixel of one lies within 2 pixels of a dark pixel of the other
    assert (ink_pdf & ~_grown(ink_png, 2)).mean() < 5e-4
    assert (ink_png & ~_grown(ink_pdf, 2)).mean() < 5e-4


def _grown(mask: Any, reach: int) -> Any:
    """The pixels within ``reach`` (a square) of a set pixel of ``mask``."""
    import numpy as np

    padded = np.pad(mask, reach)
    out = np.zeros_like(mask)
    h, w = mask.shape
    for dy in range(2 * reach + 1):
        for dx in range(2 * reach + 1):
            out |= padded[dy:dy + h, dx:dx + w]
    return out
