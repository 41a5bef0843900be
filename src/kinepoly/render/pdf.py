"""PDF written directly from the sheet: each primitive becomes a few content-stream operators.

A page's content is in millimetres (one scaling to points at its start), every primitive sets
the state it needs, so its bytes are made once per document however many pages draw it. Each
layer is a form XObject, written once and drawn by every page whose layer is the same (a
handout's mechanism, its fixed labels): a handout's file and its writing grow with what its
pages add, not with pages times drawing. Text is DejaVu Sans (Bold), the font whose advance
widths ``render.text`` measures, embedded as a TrueType subset (CID-keyed, glyph ids kept,
with a ToUnicode map so the text can be searched and copied), placed run by run at the
positions the sheet gives, without kerning, so each label's drawn box is the box it was placed with.
"""

from __future__ import annotations

import functools
import hashlib
import io
import zlib
from collections.abc import Sequence
from typing import Any

from msgspec import Struct, field

from kinepoly.render.primitives import Arrow, Circle, Item, Path, Sheet, Stroke

__all__ = ["pdf_bytes", "write_pdf_pages"]

_PT_PER_MM = 72.0 / 25.4
_KAPPA = 0.5522847498307936
"""A quarter circle's Bezier control distance, in radii."""


def _num(x: float) -> str:
    """A number of the content stream: to 0.1 micrometre, no trailing zeros (``-0`` is ``0``)."""
    text = f"{x:.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _rgb(color: str) -> str:
    return " ".join(_num(int(color[k:k + 2], 16) / 255) for k in (1, 3, 5))


class _Face(Struct, frozen=True):
    """What the writer reads of a TrueType file: glyph ids by code point, advances, metrics (font units)."""

    path: str
    name: str
    units: int
    glyphs: dict[int, int]
    advances: tuple[int, ...]
    bbox: tuple[int, int, int, int]
    ascent: int
    descent: int
    cap_height: int
    bold: bool


@functools.cache
def _face(bold: bool) -> _Face:
    """DejaVu Sans (Bold), found as matplotlib finds it (the font ``render.text`` measures)."""
    from fontTools.ttLib import TTFont
    from matplotlib import font_manager

    weight = "bold" if bold else "normal"
    path = font_manager.findfont(font_manager.FontProperties(family="DejaVu Sans", weight=weight))
    with open(path, "rb") as stream:  # read whole: no file left open
        font = TTFont(io.BytesIO(stream.read()), lazy=True)
    order = font.getGlyphOrder()
    ids = {name: k for k, name in enumerate(order)}
    glyphs = {code: ids[name] for code, name in font.getBestCmap().items()}
    metrics = font["hmtx"].metrics
    head, hhea, os2 = font["head"], font["hhea"], font["OS/2"]
    cap = getattr(os2, "sCapHeight", 0) or round(0.729 * head.unitsPerEm)
    name = font["name"].getDebugName(6) or ("DejaVuSans-Bold" if bold else "DejaVuSans")
    return _Face(path, name, head.unitsPerEm, glyphs, tuple(metrics[n][0] for n in order),
                 (head.xMin, head.yMin, head.xMax, head.yMax), hhea.ascent, hhea.descent, cap, bold)


def _subset(bold: bool, gids: frozenset[int]) -> bytes:
    """The font file holding only ``gids`` (and .notdef), every glyph keeping its id."""
    from fontTools import subset
    from fontTools.ttLib import TTFont

    options = subset.Options()
    options.retain_gids = True
    options.notdef_outline = True
    options.glyph_names = False
    options.layout_features = []
    options.name_IDs = ["*"]
    options.drop_tables += ["GPOS", "GSUB", "GDEF", "MATH", "FFTM", "kern"]
    with open(_face(bold).path, "rb") as stream:
        font = TTFont(io.BytesIO(stream.read()), recalcTimestamp=False)  # the same sheets give the same bytes
    subsetter = subset.Subsetter(options)
    subsetter.populate(gids=sorted(gids | {0}))
    subsetter.subset(font)
    out = io.BytesIO()
    font.save(out)
    return out.getvalue()


class _Writer(Struct):
    """One PDF document being written: its objects, the glyphs its text uses, its shared layers."""

    objects: list[bytes | None] = field(default_factory=list)
    used: dict[bool, dict[int, int]] = field(default_factory=lambda: {False: {}, True: {}})
    """Per font (bold or not): glyph id -> the code point it shows (for the ToUnicode map)."""
    alphas: dict[float, str] = field(default_factory=dict)
    forms: dict[tuple[Item, ...], str] = field(default_factory=dict)
    form_objects: dict[str, int] = field(default_factory=dict)
    item_bytes: dict[Item, bytes] = field(default_factory=dict)

    def reserve(self) -> int:
        self.objects.append(None)
        return len(self.objects)

    def put(self, number: int, body: bytes) -> None:
        self.objects[number - 1] = body

    def add(self, body: bytes) -> int:
        number = self.reserve()
        self.put(number, body)
        return number

    @staticmethod
    def stream(entries: str, data: bytes) -> bytes:
        packed = zlib.compress(data, 6)
        return (f"<< {entries} /Filter /FlateDecode /Length {len(packed)} >>\nstream\n".encode()
                + packed + b"\nendstream")

    # -- content -----------------------------------------------------------------------------------

    def _alpha(self, opacity: float) -> str:
        name = self.alphas.get(opacity)
        if name is None:
            name = self.alphas[opacity] = f"GA{len(self.alphas)}"
        return name

    def _glyphs(self, text: str, bold: bool) -> str:
        face, used = _face(bold), self.used[bold]
        out = []
        for ch in text:
            gid = face.glyphs.get(ord(ch), 0)  # a letter the font lacks: its .notdef box, as matplotlib draws it
            if gid:
                used.setdefault(gid, ord(ch))
            out.append(f"{gid:04X}")
        return "".join(out)

    def item(self, item: Item) -> bytes:
        found = self.item_bytes.get(item)
        if found is None:
            found = self.item_bytes[item] = self._content(item).encode("ascii")
        return found

    def _content(self, item: Item) -> str:
        if isinstance(item, Path):
            out = []
            if item.closed and item.fill is not None and len(item.points) >= 3:
                fill = f"{_rgb(item.fill)} rg {_outline(item.points, True)} f\n"
                out.append(fill if item.fill_opacity >= 1.0 else f"q /{self._alpha(item.fill_opacity)} gs {fill}Q\n")
            if item.stroke is not None and item.points:
                out.append(f"{_stroke_state(item.stroke)} {_outline(item.points, item.closed)} S\n")
            return "".join(out)
        if isinstance(item, Circle):
            paint = "B" if item.fill and item.stroke else "f" if item.fill else "S" if item.stroke else "n"
            state = (f"{_rgb(item.fill)} rg " if item.fill else "") + (
                f"{_stroke_state(item.stroke)} " if item.stroke else "")
            return f"{state}{_circle(item.center, item.radius)} {paint}\n"
        if isinstance(item, Arrow):
            (sx, sy), (ex, ey) = item.start, item.shaft_end
            shaft = (f"{_stroke_state(Stroke(item.color, item.width))} {_num(sx)} {_num(sy)} m {_num(ex)} {_num(ey)} "
                     "l S\n")
            return shaft + f"{_rgb(item.color)} rg {_outline(item.head, True)} f\n"
        font = "F2" if item.bold else "F1"
        runs = " ".join(f"/{font} {_num(run.size)} Tf 1 0 0 1 {_num(item.x + run.dx)} {_num(item.y + run.dy)} Tm "
                        f"<{self._glyphs(run.text, item.bold)}> Tj" for run in item.runs if run.text)
        return f"{_rgb(item.color)} rg BT {runs} ET\n" if runs else ""

    def form(self, items: tuple[Item, ...], box: str) -> str:
        """The name of the form XObject drawing ``items``, made on first use."""
        name = self.forms.get(items)
        if name is None:
            name = self.forms[items] = f"L{len(self.forms)}"
            data = b"".join(self.item(item) for item in items)
            self.form_objects[name] = self.add(self.stream(f"/Type /XObject /Subtype /Form /BBox [{box}] "
                                                           f"/Resources {{resources}}", data))
        return name

    # -- fonts ---------------------------------------------------------------------------------------

    def font(self, bold: bool) -> int:
        face, used = _face(bold), self.used[bold]
        gids = frozenset(used)
        tag = "".join(chr(65 + b % 26) for b in hashlib.sha256(repr(sorted(gids)).encode()).digest()[:6])
        base = f"{tag}+{face.name}"
        data = _subset(bold, gids)
        file = self.add(self.stream(f"/Length1 {len(data)}", data))
        scale = 1000.0 / face.units
        x0, y0, x1, y1 = (round(v * scale) for v in face.bbox)
        descriptor = self.add(
            (f"<< /Type /FontDescriptor /FontName /{base} /Flags 32 /FontBBox [{x0} {y0} {x1} {y1}] "
             f"/ItalicAngle 0 /Ascent {round(face.ascent * scale)} /Descent {round(face.descent * scale)} "
             f"/CapHeight {round(face.cap_height * scale)} /StemV {140 if bold else 80} /FontFile2 {file} 0 R >>"
             ).encode())
        widths = " ".join(f"{gid} [{_num(face.advances[gid] * scale)}]" for gid in sorted(gids | {0}))
        cid = self.add(
            (f"<< /Type /Font /Subtype /CIDFontType2 /BaseFont /{base} /CIDSystemInfo << /Registry (Adobe) "
             f"/Ordering (Identity) /Supplement 0 >> /FontDescriptor {descriptor} 0 R /CIDToGIDMap /Identity "
             f"/DW {round(face.advances[0] * scale)} /W [{widths}] >>").encode())
        unicode = self.add(self.stream("", _to_unicode(used).encode("ascii")))
        return self.add((f"<< /Type /Font /Subtype /Type0 /BaseFont /{base} /Encoding /Identity-H "
                         f"/DescendantFonts [{cid} 0 R] /ToUnicode {unicode} 0 R >>").encode())


def _stroke_state(stroke: Stroke) -> str:
    dash = " ".join(_num(d) for d in stroke.dash)
    return f"{_rgb(stroke.color)} RG {_num(stroke.width)} w 0 J 0 j [{dash}] 0 d"


def _outline(points: Sequence[tuple[float, float]], closed: bool) -> str:
    (x, y), rest = points[0], points[1:]
    return (f"{_num(x)} {_num(y)} m " + " ".join(f"{_num(px)} {_num(py)} l" for px, py in rest)
            + (" h" if closed else ""))


def _circle(center: tuple[float, float], r: float) -> str:
    cx, cy = center
    k = _KAPPA * r
    quarters = [((cx + r, cy + k), (cx + k, cy + r), (cx, cy + r)), ((cx - k, cy + r), (cx - r, cy + k), (cx - r, cy)),
                ((cx - r, cy - k), (cx - k, cy - r), (cx, cy - r)), ((cx + k, cy - r), (cx + r, cy - k), (cx + r, cy))]
    curves = " ".join(" ".join(f"{_num(x)} {_num(y)}" for x, y in q) + " c" for q in quarters)
    return f"{_num(cx + r)} {_num(cy)} m {curves} h"


def _to_unicode(used: dict[int, int]) -> str:
    def utf16(code: int) -> str:
        return chr(code).encode("utf-16-be").hex().upper()

    pairs = sorted(used.items())
    chunks = []
    for k in range(0, len(pairs), 100):
        part = pairs[k:k + 100]
        chunks.append(f"{len(part)} beginbfchar\n" + "\n".join(f"<{gid:04X}> <{utf16(code)}>" for gid, code in part)
                      + "\nendbfchar")
    return ("/CIDInit /ProcSet findresource begin\n12 dict begin\nbegincmap\n/CIDSystemInfo << /Registry (Adobe) "
            "/Ordering (UCS) /Supplement 0 >> def\n/CMapName /Adobe-Identity-UCS def\n/CMapType 2 def\n"
            "1 begincodespacerange\n<0000> <FFFF>\nendcodespacerange\n" + "\n".join(chunks)
            + "\nendcmap\nCMapName currentdict /CMap defineresource pop\nend\nend\n")


def _string(text: str) -> str:
    """A PDF text string: literal when ASCII, else UTF-16 with its byte-order mark."""
    if text.isascii() and text.isprintable():
        return "(" + text.replace("\\", "\\\\").replace("(", "\\(").replace(")", "\\)") + ")"
    return "<FEFF" + text.encode("utf-16-be").hex().upper() + ">"


def pdf_bytes(sheets: Sequence[Sheet], title: str) -> bytes:
    """The sheets as one PDF, a page each, fonts embedded."""
    writer = _Writer()
    catalog, pages_number = writer.reserve(), writer.reserve()
    page_numbers = []
    for sheet in sheets:
        w, h = sheet.width, sheet.height
        box = f"{_num(-w)} {_num(-h)} {_num(2 * w)} {_num(2 * h)}"  # what is drawn beyond the page is cut there
        names = [writer.form(layer.items, box) for layer in sheet.layers if layer.items]
        content = f"q {_num(_PT_PER_MM)} 0 0 {_num(_PT_PER_MM)} 0 0 cm\n" + "".join(f"/{n} Do\n" for n in names) + "Q\n"
        stream = writer.add(writer.stream("", content.encode("ascii")))
        page_numbers.append(writer.add(
            (f"<< /Type /Page /Parent {pages_number} 0 R /MediaBox [0 0 {_num(w * _PT_PER_MM)} {_num(h * _PT_PER_MM)}] "
             f"/Resources {{resources}} /Contents {stream} 0 R >>").encode()))
    fonts = " ".join(f"/F{2 if bold else 1} {writer.font(bold)} 0 R" for bold in (False, True) if writer.used[bold])
    alphas = " ".join(f"/{name} << /Type /ExtGState /ca {_num(opacity)} >>" for opacity, name in writer.alphas.items())
    forms = " ".join(f"/{name} {number} 0 R" for name, number in writer.form_objects.items())
    resources = writer.add(f"<< /Font << {fonts} >> /ExtGState << {alphas} >> /XObject << {forms} >> >>".encode())
    writer.put(pages_number, (f"<< /Type /Pages /Kids [{' '.join(f'{n} 0 R' for n in page_numbers)}] "
                              f"/Count {len(page_numbers)} >>").encode())
    writer.put(catalog, f"<< /Type /Catalog /Pages {pages_number} 0 R >>".encode())
    info = writer.add(f"<< /Creator (kinepoly) /Title {_string(title)} >>".encode())
    out = io.BytesIO()
    out.write(b"%PDF-1.6\n%\xe2\xe3\xcf\xd3\n")
    offsets = []
    shared = f"{resources} 0 R".encode()
    for number, body in enumerate(writer.objects, 1):
        assert body is not None
        offsets.append(out.tell())
        out.write(f"{number} 0 obj\n".encode() + _resolve(body, shared) + b"\nendobj\n")
    start = out.tell()
    out.write(f"xref\n0 {len(offsets) + 1}\n0000000000 65535 f \n".encode())
    out.write("".join(f"{offset:010d} 00000 n \n" for offset in offsets).encode())
    out.write(f"trailer\n<< /Size {len(offsets) + 1} /Root {catalog} 0 R /Info {info} 0 R >>\n"
              f"startxref\n{start}\n%%EOF\n".encode())
    return out.getvalue()


def _resolve(body: bytes, resources: bytes) -> bytes:
    """The object with the shared resources' reference in place of its placeholder (only in its dictionary)."""
    head, sep, rest = body.partition(b"stream\n")
    return head.replace(b"{resources}", resources) + sep + rest


def write_pdf_pages(sheets: Sequence[Sheet], target: Any, title: str) -> None:
    """Write the sheets as one PDF, a page each, to a path or a binary file object."""
    data = pdf_bytes(sheets, title)
    if hasattr(target, "write"):
        target.write(data)
    else:
        with open(target, "wb") as stream:
            stream.write(data)
