"""SVG through svgwrite: one ``<g id="LAYER">`` per layer, page in millimetres, y turned down.

Deterministic: no automatic ids (the only ids are the layers'), every number printed by
``number`` (at most three decimals, no trailing zeros), attributes in a fixed order, one
element per line, so that a change of the drawing reads as a diff.
"""

from __future__ import annotations

import re
from typing import Any

from kinepoly.render.primitives import Arrow, Circle, Layer, Path, Sheet, Stroke, Text

__all__ = ["FONT_FAMILY", "number", "svg_text", "write_svg"]

FONT_FAMILY = "DejaVu Sans, Verdana, Arial, sans-serif"
_NOT_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ud800-\udfff\ufffe\uffff]")  # what XML 1.0 cannot hold


def number(x: float) -> str:
    """A coordinate or length in mm, to the micrometre, without trailing zeros (``-0`` is ``0``)."""
    text = f"{x:.3f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _points(points: Any, height: float) -> str:
    return " ".join(f"{number(x)},{number(height - y)}" for x, y in points)


def _stroke(stroke: Stroke | None) -> dict[str, str]:
    if stroke is None:
        return {"stroke": "none"}
    out = {"stroke": stroke.color, "stroke-width": number(stroke.width)}
    if stroke.dash:
        out["stroke-dasharray"] = " ".join(number(d) for d in stroke.dash)
    return out


def _path_data(points: Any, height: float, closed: bool) -> str:
    return "M" + " L".join(_points([p], height) for p in points) + (" Z" if closed else "")


def _element(dwg: Any, item: Path | Circle | Arrow | Text, h: float) -> list[Any]:
    role = {"data-role": item.role} if item.role else {}
    if isinstance(item, Path):
        fill = {"fill": item.fill, "fill-opacity": number(item.fill_opacity)} if item.fill else {"fill": "none"}
        return [dwg.path(d=_path_data(item.points, h, item.closed), **fill, **_stroke(item.stroke), **role)]
    if isinstance(item, Circle):
        return [dwg.circle(center=(number(item.center[0]), number(h - item.center[1])), r=number(item.radius),
                           fill=item.fill or "none", **_stroke(item.stroke), **role)]
    if isinstance(item, Arrow):
        shaft = dwg.line(start=(number(item.start[0]), number(h - item.start[1])),
                         end=(number(item.shaft_end[0]), number(h - item.shaft_end[1])),
                         **_stroke(Stroke(item.color, item.width)), **role)
        head = dwg.path(d=_path_data(item.head, h, True), fill=item.color, stroke="none", **role)
        return [shaft, head]
    weight = {"font-weight": "bold"} if item.bold else {}
    text = dwg.text("", fill=item.color, **weight, **role, **{"xml:space": "preserve"})  # keep " = " spaced
    for run in item.runs:
        text.add(dwg.tspan(run.text, x=[number(item.x + run.dx)], y=[number(h - item.y - run.dy)],
                           **{"font-size": number(run.size)}))
    return [text]


def svg_text(sheet: Sheet, made: dict[Any, str] | None = None,
             view: tuple[float, float, float, float] | None = None) -> str:
    """The sheet as an SVG document (text); ``made``, shared by the sheets of one document (a handout's
    pages), holds each layer's ``<g>`` and each item's elements once written: what the pages share is
    written once. ``view``, a rectangle of the sheet (x0, y0, x1, y1 in mm, y up), is the part shown:
    the document's size and viewBox are the rectangle's, after the other attributes of its ``<svg>``."""
    import svgwrite

    w, h = sheet.width, sheet.height
    dwg = svgwrite.Drawing(size=(f"{number(w)}mm", f"{number(h)}mm"), viewBox=f"0 0 {number(w)} {number(h)}",
                           profile="full", debug=False)
    if view is not None:
        for name in ("width", "height", "viewBox"):
            del dwg.attribs[name]
    dwg.set_desc(title=sheet.title)
    dwg.add(dwg.rect(insert=(0, 0), size=(number(w), number(h)), fill="#ffffff"))
    head = _lines(dwg.tostring()).removesuffix("</svg>")
    if view is not None:
        x0, y0, x1, y1 = view
        size = (f' width="{number(x1 - x0)}mm" height="{number(y1 - y0)}mm" '
                f'viewBox="{number(x0)} {number(h - y1)} {number(x1 - x0)} {number(y1 - y0)}"')
        end = head.index(">")  # the end of the <svg> tag, the first of the document
        head = head[:end] + size + head[end:]
    made = made if made is not None else {}
    for layer in sheet.layers:
        if (layer, h) not in made:
            made[layer, h] = _group_text(dwg, layer, h, made)
    body = head + "".join(made[layer, h] + "\n" for layer in sheet.layers) + "</svg>"
    return '<?xml version="1.0" encoding="utf-8" ?>\n' + body + "\n"


def _group_text(dwg: Any, layer: Layer, height: float, made: dict[Any, str]) -> str:
    """A layer's ``<g>``, its items' elements taken from ``made`` when written before (by item and height)."""
    shell = dwg.g(id=layer.name, **{"font-family": FONT_FAMILY, "stroke-linecap": "butt"}).tostring()
    if not layer.items:
        return _lines(shell)
    parts = []
    for item in layer.items:
        text = made.get((item, height))
        if text is None:
            text = made[item, height] = "".join(_tostring(element) for element in _element(dwg, item, height))
        parts.append(text)
    return _lines(shell.removesuffix(" />") + ">" + "".join(parts) + "</g>")


_SURROGATE = re.compile("[\ud800-\udfff]")


def _tostring(element: Any) -> str:
    """``element.tostring()`` (svgwrite's: ElementTree's UTF-8 bytes, decoded), made by ElementTree as text at once;
    a lone surrogate, which UTF-8 cannot hold, left to svgwrite's (a character reference)."""
    from xml.etree import ElementTree

    text = ElementTree.tostring(element.get_xml(), encoding="unicode")
    return element.tostring() if _SURROGATE.search(text) else text


def _lines(text: str) -> str:
    """One element per line for readable diffs, but nothing between a text's runs (it would be drawn); any
    character XML cannot hold replaced (the scene refuses them; any other text is still well-formed XML)."""
    return _NOT_XML.sub("\ufffd", re.sub(r"><(?!tspan|/text)", ">\n<", text))


def write_svg(sheet: Sheet, target: Any) -> None:
    """Write the SVG to a text file object."""
    target.write(svg_text(sheet))
