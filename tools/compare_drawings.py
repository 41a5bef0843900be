"""Drawings compared as a reviewer would: SVG and DXF canonically as text, PNG with a tolerance.

Canonical forms leave out what a library version may change without changing the drawing
(attribute order, namespaces, DXF handles and header) and round coordinates to 0.01 mm.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Any

__all__ = ["PNG_RMS_TOLERANCE", "canonical_dxf", "canonical_svg", "png_rms"]

PNG_RMS_TOLERANCE = 2.0
"""Largest root-mean-square difference (0..255 grey levels) between two PNGs of one drawing.

Text anti-aliasing differs a little between matplotlib and FreeType versions; a moved label
or a changed colour costs more than this."""

_NUMBER = re.compile(r"-?\d+\.\d+")


def _round(text: str) -> str:
    def fix(m: re.Match[str]) -> str:
        value = f"{float(m.group(0)):.2f}".rstrip("0").rstrip(".")
        return "0" if value == "-0" else value

    return _NUMBER.sub(fix, text)


def canonical_svg(text: str) -> list[str]:
    """One line per element: tag, sorted attributes (numbers to 0.01) and text."""
    import xml.etree.ElementTree as ET

    root = ET.fromstring(text)
    lines: list[str] = []

    def walk(element: Any, depth: int) -> None:
        tag = element.tag.rpartition("}")[2]
        attributes = " ".join(f"{k.rpartition('}')[2]}={_round(v)!r}" for k, v in sorted(element.attrib.items()))
        body = (element.text or "").strip()
        lines.append(f"{'  ' * depth}{tag} {attributes} {body!r}" if body else f"{'  ' * depth}{tag} {attributes}")
        for child in element:
            walk(child, depth + 1)

    walk(root, 0)
    return lines


def _coords(entity: Any) -> str:
    kind = entity.dxftype()
    dxf = entity.dxf
    if kind == "LINE":
        points = [dxf.start, dxf.end]
    elif kind == "LWPOLYLINE":
        points = [(p[0], p[1]) for p in entity.get_points("xy")]
    elif kind == "CIRCLE":
        points = [dxf.center, (dxf.radius, 0.0)]
    elif kind == "SOLID":
        points = [dxf.vtx0, dxf.vtx1, dxf.vtx2]
    elif kind == "TEXT":
        points = [dxf.insert, (dxf.height, 0.0)]
    elif kind == "HATCH":
        points = [(0.0, 0.0)] if not entity.paths else [
            (v[0], v[1]) for path in entity.paths for v in getattr(path, "vertices", [])]
    else:
        points = []
    return " ".join(f"{p[0]:.2f},{p[1]:.2f}" for p in points).replace("-0.00", "0.00")


def canonical_dxf(path: str | Path) -> list[str]:
    """One line per model-space entity: layer, type, colour, rounded geometry, text."""
    import ezdxf

    doc = ezdxf.readfile(str(path))
    lines = []
    for entity in doc.modelspace():
        text = entity.dxf.text if entity.dxftype() == "TEXT" else ""
        rgb = entity.rgb if entity.rgb is not None else ""
        lines.append(f"{entity.dxf.layer} {entity.dxftype()} {rgb} {_coords(entity)} {text}".rstrip())
    return lines


def png_rms(first: str | Path, second: str | Path) -> float:
    """Root-mean-square grey-level difference of two PNGs (inf when their sizes differ)."""
    import numpy as np
    from PIL import Image

    with Image.open(first) as a, Image.open(second) as b:
        if a.size != b.size:
            return float("inf")
        x = np.asarray(a.convert("L"), dtype=float)
        y = np.asarray(b.convert("L"), dtype=float)
    return float(np.sqrt(np.mean((x - y) ** 2)))
