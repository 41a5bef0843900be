"""The layer higher-pairs of a drawing: what is drawn where, measured on the neutral sheet against the
scene's own numbers, and its group in the SVG and layer in the DXF."""

from __future__ import annotations

import io
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinepoly
from kinepoly.render.primitives import Circle, Item, Sheet
from kinepoly.render.primitives import Path as Line
from kinepoly.render.sheet import build_sheet, layout_sheet

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _drawn(name: str) -> tuple[kinepoly.Solution, Sheet, object]:
    solution = kinepoly.solve(kinepoly.load_scene(EXAMPLES / f"{name}.toml"))
    layout = layout_sheet(solution)
    sheet = build_sheet(solution, (layout.width, layout.height), layout=layout)
    panel = layout.panel("mechanism")
    return solution, sheet, panel


def _items(sheet: Sheet, layer: str) -> dict[str, Item]:
    return {item.role: item for item in sheet.layer(layer).items}


def _center_radius(points: tuple[tuple[float, float], ...]) -> tuple[complex, float, float]:
    z = np.array([complex(*p) for p in points])
    center = complex(z.mean())
    r = np.abs(z - center)
    return center, float(r.mean()), float(r.max() - r.min())


def _on_line(p: complex, a: complex, b: complex) -> float:
    """The distance of p from the line a b."""
    d = (b - a) / abs(b - a)
    return abs(((p - a) * d.conjugate()).imag)


def test_roller_rocker_layer() -> None:
    solution, sheet, panel = _drawn("cam-roller-rocker")
    items = _items(sheet, "higher-pairs")
    paper = panel.paper  # type: ignore[attr-defined]
    k_scale = panel.scale  # type: ignore[attr-defined]
    theta = math.radians(30.0)
    disc = complex(15.0 * math.cos(theta), 15.0 * math.sin(theta))  # K turned with the cam
    profile = items["cam profile 23"]
    assert isinstance(profile, Line) and profile.closed
    center, radius, spread = _center_radius(profile.points)
    assert abs(center - complex(*paper((disc.real, disc.imag)))) < 1e-9
    assert radius == pytest.approx(40.0 * k_scale, rel=1e-3) and spread < 1e-9
    w = solution.position("W")
    roller = items["roller 23"]
    assert isinstance(roller, Line)
    center, radius, spread = _center_radius(roller.points)
    assert abs(center - complex(*paper(w))) < 1e-9 and radius == pytest.approx(10.0 * k_scale, rel=1e-3)
    eq = solution.scene.cams[0].equivalent
    assert eq == "4"  # numbered as a textbook numbers the link the pair is replaced by
    link = items[f"equivalent link {eq}"]
    assert isinstance(link, Line) and link.stroke is not None and link.stroke.dash
    assert link.points[0] == pytest.approx(paper((disc.real, disc.imag)), abs=1e-9)
    assert link.points[1] == pytest.approx(paper(w), abs=1e-9)
    # the contact lies on the disc, R from K toward W; the normal runs through it, K and W
    contact = complex(*solution.contacts["23"].point)
    assert contact == pytest.approx(disc + 40.0 * (complex(*w) - disc) / abs(complex(*w) - disc), abs=1e-12)
    dot = items["contact C23"]
    assert isinstance(dot, Circle)
    assert complex(*dot.center) == pytest.approx(complex(*paper(solution.contacts["23"].point)))
    normal = items["common normal 23"]
    assert isinstance(normal, Line)
    a, b = (complex(*p) for p in normal.points)
    for p in (disc, complex(*w)):
        assert _on_line(complex(*paper((p.real, p.imag))), a, b) < 1e-9
    labels = [item for item in sheet.layer("higher-pairs").items if item.role == "point C23"]
    assert len(labels) == 1
    assert not any(item.role == f"link {eq}" for item in sheet.layer("mechanism").items)


def test_flat_face_layer() -> None:
    solution, sheet, panel = _drawn("eccentric-cam-flat")
    items = _items(sheet, "higher-pairs")
    paper = panel.paper  # type: ignore[attr-defined]
    face = items["flat face 23"]
    assert isinstance(face, Line)
    contact = solution.contacts["23"].point
    a, b = (complex(*p) for p in face.points)
    assert abs((b - a).imag) < 1e-9  # the face is horizontal: square to the vertical guide
    assert _on_line(complex(*paper(contact)), a, b) < 1e-9
    assert min(a.real, b.real) < paper(contact)[0] < max(a.real, b.real)
    eq = solution.scene.cams[0].equivalent
    assert eq == "4"  # numbered as a textbook numbers the block the pair is replaced by
    assert {f"equivalent slide 3-{eq}", f"equivalent block {eq}"} <= set(items)
    assert not any(item.role.startswith(f"block {eq}") for item in sheet.layer("mechanism").items)


def test_svg_group_and_dxf_layer() -> None:
    import ezdxf

    from kinepoly.render.dxf import dxf_document
    from kinepoly.render.svg import svg_text

    _, sheet, _ = _drawn("cam-roller-rocker")
    root = ET.fromstring(svg_text(sheet))
    groups = [g for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("id") == "higher-pairs"]
    assert len(groups) == 1 and len(list(groups[0])) >= 6
    stream = io.StringIO()
    dxf_document(sheet).write(stream)
    doc = ezdxf.read(io.StringIO(stream.getvalue()))
    assert "higher-pairs" in doc.layers
    on_layer = [e for e in doc.modelspace() if e.dxf.layer == "higher-pairs"]
    assert {e.dxftype() for e in on_layer} >= {"LWPOLYLINE", "TEXT"}


@settings(max_examples=10, deadline=None)
@given(st.floats(-180.0, 180.0))
def test_the_profile_turns_with_the_cam_at_any_input(angle: float) -> None:
    text = (EXAMPLES / "cam-roller-rocker.toml").read_text().replace("angle = 30", f"angle = {angle!r}")
    solution = kinepoly.solve(kinepoly.loads_scene(text))
    layout = layout_sheet(solution)
    sheet = build_sheet(solution, (layout.width, layout.height), layout=layout)
    panel = layout.panel("mechanism")
    assert panel is not None
    items = _items(sheet, "higher-pairs")
    profile = items["cam profile 23"]
    assert isinstance(profile, Line)
    center, radius, _ = _center_radius(profile.points)
    theta = math.radians(angle)
    assert abs(center - complex(*panel.paper((15.0 * math.cos(theta), 15.0 * math.sin(theta))))) < 1e-9
    assert radius == pytest.approx(40.0 * panel.scale, rel=1e-3)
    # the contact point lies on the profile and on the roller: R from K, r from W
    contact = complex(*solution.contacts["23"].point)
    k = complex(15.0 * math.cos(theta), 15.0 * math.sin(theta))
    assert abs(abs(contact - k) - 40.0) < 1e-9 and abs(abs(contact - complex(*solution.position("W"))) - 10.0) < 1e-9
