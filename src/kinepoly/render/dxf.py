"""DXF (R2010) through ezdxf: one layer per sheet layer, real millimetres, real entities.

Lines and outlines are LWPOLYLINEs, shading is a solid HATCH with transparency, arrow heads
are SOLIDs, labels are TEXT entities (one per run, DejaVu Sans, height = cap height), colours
are true colours and widths DXF lineweights. The header carries fixed metadata so that the
same sheet always gives the same file.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from kinepoly.render.primitives import Arrow, Circle, Path, Sheet, Stroke, Text
from kinepoly.render.text import CAP_HEIGHT_EM

if TYPE_CHECKING:
    from ezdxf.document import Drawing
    from ezdxf.layouts import Modelspace

__all__ = ["dxf_document", "write_dxf"]

_LINEWEIGHTS = (0, 5, 9, 13, 15, 18, 20, 25, 30, 35, 40, 50, 53, 60, 70, 80, 90, 100, 106, 120, 140, 158, 200, 211)
_STYLE, _STYLE_BOLD = "KINEPOLY", "KINEPOLY-BOLD"


def _lineweight(width_mm: float) -> int:
    return min(_LINEWEIGHTS, key=lambda w: abs(w - 100.0 * width_mm))


def _rgb(color: str) -> tuple[int, int, int]:
    return (int(color[1:3], 16), int(color[3:5], 16), int(color[5:7], 16))


def _linetype(doc: Drawing, dash: tuple[float, ...]) -> str:
    name = "KINEPOLY-DASH-" + "-".join(f"{d:g}".replace(".", "_") for d in dash)
    if name not in doc.linetypes:
        pattern = [sum(dash)] + [d if k % 2 == 0 else -d for k, d in enumerate(dash)]
        doc.linetypes.add(name, pattern, description="kinepoly " + " ".join(f"{d:g}" for d in dash))
    return name


def _attribs(doc: Drawing, layer: str, stroke: Stroke) -> dict[str, Any]:
    attribs: dict[str, Any] = {"layer": layer, "lineweight": _lineweight(stroke.width)}
    if stroke.dash:
        attribs["linetype"] = _linetype(doc, stroke.dash)
    return attribs


def _fill(msp: Modelspace, layer: str, color: str, opacity: float, outline: Any) -> None:
    hatch = msp.add_hatch(dxfattribs={"layer": layer})
    from ezdxf.colors import RGB

    hatch.set_solid_fill(rgb=RGB(*_rgb(color)))
    outline(hatch)
    if opacity < 1.0:
        hatch.transparency = 1.0 - opacity


def _add(doc: Drawing, msp: Modelspace, layer: str, item: Path | Circle | Arrow | Text) -> None:
    if isinstance(item, Path):
        if item.closed and item.fill is not None:
            _fill(msp, layer, item.fill, item.fill_opacity,
                  lambda h: h.paths.add_polyline_path(list(item.points), is_closed=True))
        if item.stroke is not None:
            line = msp.add_lwpolyline(list(item.points), close=item.closed,
                                      dxfattribs=_attribs(doc, layer, item.stroke))
            line.rgb = _rgb(item.stroke.color)
    elif isinstance(item, Circle):
        if item.fill is not None:
            def outline(h: Any) -> None:
                h.paths.add_edge_path().add_arc(item.center, item.radius, 0.0, 360.0)

            _fill(msp, layer, item.fill, 1.0, outline)
        if item.stroke is not None:
            circle = msp.add_circle(item.center, item.radius, dxfattribs=_attribs(doc, layer, item.stroke))
            circle.rgb = _rgb(item.stroke.color)
    elif isinstance(item, Arrow):
        shaft = msp.add_line(item.start, item.shaft_end,
                             dxfattribs=_attribs(doc, layer, Stroke(item.color, item.width)))
        shaft.rgb = _rgb(item.color)
        tip, left, right = item.head
        head = msp.add_solid([tip, left, right], dxfattribs={"layer": layer})
        head.rgb = _rgb(item.color)
    else:
        for run in item.runs:
            text = msp.add_text(run.text, height=run.size * CAP_HEIGHT_EM,
                                dxfattribs={"layer": layer, "style": _STYLE_BOLD if item.bold else _STYLE})
            text.set_placement((item.x + run.dx, item.y + run.dy))
            text.rgb = _rgb(item.color)


def dxf_document(sheet: Sheet) -> Drawing:
    """The sheet as an ezdxf document: model space in mm, the page's border included."""
    import ezdxf

    doc = ezdxf.new("R2010", setup=["linetypes"], units=4)
    doc.header["$MEASUREMENT"] = 1
    doc.header["$LWDISPLAY"] = 1
    doc.header["$LTSCALE"] = 1.0
    doc.header["$EXTMIN"] = (0.0, 0.0, 0.0)
    doc.header["$EXTMAX"] = (sheet.width, sheet.height, 0.0)
    doc.styles.add(_STYLE, font="DejaVuSans.ttf")
    doc.styles.add(_STYLE_BOLD, font="DejaVuSans-Bold.ttf")
    msp = doc.modelspace()
    for layer in sheet.layers:
        doc.layers.add(layer.name)
        for item in layer.items:
            _add(doc, msp, layer.name, item)
    doc.set_modelspace_vport(height=sheet.height, center=(sheet.width / 2, sheet.height / 2))
    return doc


def write_dxf(sheet: Sheet, target: Any) -> None:
    """Write the DXF to a text file object (UTF-8), with fixed metadata so that output is repeatable."""
    import ezdxf

    fixed = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True  # dates, GUIDs and ezdxf's own markers fixed
    try:
        dxf_document(sheet).write(target)
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = fixed
