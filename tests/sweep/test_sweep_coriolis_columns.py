"""A slider's Coriolis columns only where its guide can turn.

A guide on the frame never turns, so 2 omega_guide x v_rel is zero at every row: the sweep leaves
``coriolis_<name>_x/_y`` out there (the JSON of ``kinepoly solve`` keeps its ``coriolis`` key) and keeps
every other column as it was. A guide that turns (the slotted lever's) keeps them.
"""

from __future__ import annotations

import csv
import io

from tests.scenes import EXAMPLES
from tests.sweep_support import row_scene

import kinepoly
from kinepoly.sweep import sweep
from kinepoly.sweep.table import csv_text

SLIDER_CRANK = (EXAMPLES / "slider-crank.toml").read_text().replace("[find]\n", '[find]\nsliders = ["14"]\n')


def test_a_slider_on_the_frame_has_no_coriolis_columns_and_its_term_is_zero() -> None:
    result = sweep(kinepoly.loads_scene(SLIDER_CRANK), steps=12)
    header = csv_text(result).splitlines()[0].split(",")
    assert {"s_14", "s_dot_14", "s_ddot_14"} <= set(header)
    assert not any(name.startswith("coriolis_") for name in header)
    for row in (0, 5, 9):  # what was left out is zero: the solve at that row says so
        data = kinepoly.to_json(kinepoly.solve(kinepoly.loads_scene(row_scene(SLIDER_CRANK, result, row))))
        assert data["sliders"]["14"]["coriolis"] == [0.0, 0.0]


def test_a_turning_guide_keeps_its_coriolis_columns_and_they_are_not_zero() -> None:
    text = (EXAMPLES / "slotted-lever.toml").read_text().replace('alpha = ["4"]', 'alpha = ["4"]\nsliders = ["43"]')
    rows = list(csv.DictReader(io.StringIO(csv_text(sweep(kinepoly.loads_scene(text), steps=12)))))
    assert max(abs(float(r["coriolis_43_x"])) + abs(float(r["coriolis_43_y"])) for r in rows) > 1.0
