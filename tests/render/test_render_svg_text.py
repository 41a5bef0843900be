"""The SVG of an item is what svgwrite writes for it, made by ElementTree as text at once (issue 28's speed-up)."""

from __future__ import annotations

import pytest
import svgwrite

from kinepoly.render import svg


@pytest.mark.parametrize("text", ["v_B", "α ≥ 0, ω₁₂ & <σ> \"q\"", "a\ud800b", "\U0001d6fc", ""])
def test_an_element_is_written_as_svgwrite_writes_it(text: str) -> None:
    dwg = svgwrite.Drawing(profile="full", debug=False)
    element = dwg.text("", fill="#000000", **{"data-role": f"label {text}", "xml:space": "preserve"})
    element.add(dwg.tspan(text, x=["1.5"], y=["2"], **{"font-size": "3"}))
    assert svg._tostring(element) == element.tostring()
    path = dwg.path(d="M0,0 L1,1", fill="none", stroke="#000000", **{"data-role": text})
    assert svg._tostring(path) == path.tostring()
