"""A dashed line is as long in a PNG as its pattern says in mm, whatever its width (the SVG and PDF writers
take the pattern in mm as given; matplotlib takes points and, by default, scales them by the line width)."""

from __future__ import annotations

import io

import numpy as np
import pytest
from PIL import Image

from kinepoly.render.mpl import write_png
from kinepoly.render.primitives import LAYERS, Layer, Path, Sheet, Stroke

PX_PER_MM = 10  # at 254 dpi


def _runs(row: np.ndarray) -> tuple[list[int], list[int]]:
    """The lengths of the dark runs along a row of pixels, and of the light gaps between them."""
    dark = row < 128
    edges = np.flatnonzero(np.diff(dark.astype(np.int8)))
    starts, ends = edges[::2] + 1, edges[1::2] + 1
    return list(ends - starts), list(starts[1:] - ends[:-1])


@pytest.mark.parametrize("width", [0.25, 0.5, 1.0])
@pytest.mark.parametrize("dash", [(3.0, 2.0), (6.0, 1.5)])
def test_a_png_dash_is_as_long_as_its_pattern_in_mm(width: float, dash: tuple[float, float]) -> None:
    line = Path(((10.0, 20.0), (90.0, 20.0)), Stroke("#000000", width, dash))
    sheet = Sheet(100.0, 40.0, "dashes", tuple(Layer(name, (line,) if name == LAYERS[0] else ()) for name in LAYERS))
    stream = io.BytesIO()
    write_png(sheet, stream, dpi=254)
    pixels = np.asarray(Image.open(stream).convert("L"))
    dashes, gaps = _runs(pixels[pixels.shape[0] - 20 * PX_PER_MM])
    assert len(dashes) >= 8
    inner_dashes, inner_gaps = dashes[1:-1], gaps[1:-1]  # the first and the last may be cut by the line's ends
    assert max(abs(d - dash[0] * PX_PER_MM) for d in inner_dashes) <= 1.5  # antialiasing: a pixel either side
    assert max(abs(g - dash[1] * PX_PER_MM) for g in inner_gaps) <= 1.5
