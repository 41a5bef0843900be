"""A sweep's near-singular row says how large its error may be ("relative error about X (velocities), Y
(accelerations)"). Near a dead point the position's own rounding, which the nearly parallel lines there amplify,
dominates: the row's estimate is the solve's (``check.estimate``, with the velocity equations' condition number at
the row), and it bounds the construction's error against the 50-digit reference (``kinepoly.bench``). It once gave
the crossing's term alone: 5e-11 at the dump body's end, where the error is 1.8e-5."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from tests.scenes import EXAMPLES, four_bar, slider_crank

import kinepoly
from kinepoly.bench.methods import Setting, construction_values
from kinepoly.bench.reference import reference_values
from kinepoly.bench.run import bench_keys, kind_errors
from kinepoly.bench.sweep import solve_at
from kinepoly.sweep import sweep
from kinepoly.sweep.rows import row_guesses

_STATED = re.compile(r"([0-9.e+-]+) \((?:velocities|accelerations)\)")
_ROCKER_END = math.degrees(math.acos((100**2 + 60**2 - 95**2) / (2 * 100 * 60)))
"""Where the four-bar's crank (60) stops: |A B0| = coupler + rocker = 95 with the frame 100."""

SCENES = {  # a scene, and a range whose ends lie just inside its dead points (in the input's unit)
    "dump body": ((EXAMPLES / "dump-body.toml").read_text(), 232.79224489278, 1500.0),
    "four-bar, rocker input": (four_bar(100, 60, 50, 45, 40, 10, 0, guess_b=(110, 50)), -_ROCKER_END + 1e-9,
                               _ROCKER_END - 1e-7),
    "slider-crank, slider input": (slider_crank(40, 120, 0, 0, 10, 0).split("[input]")[0]
                                   + '[input]\nslider = "14"\ns = 130\ns_dot = 100\n\n[guess]\nA = [20, 35]\n',
                                   80.0 + 1e-9, 160.0 - 1e-7),
}


def _near_rows(text: str, start: float, stop: float) -> list[tuple[str, float]]:
    """Each near-singular row of a sweep from ``start`` to ``stop``: its warning, and the construction's error there
    against the 50-digit reference (normwise, relative to each kind's size in the scene, as the bench measures)."""
    scene = kinepoly.loads_scene(text)
    solution = kinepoly.solve(scene)
    result = sweep(scene, steps=8, start=start, stop=stop)
    keys = bench_keys(solution)
    setting = Setting(solution, keys)
    guesses = row_guesses(result)
    radians = result.scene.units.angle == "deg" and result.input.name.startswith("theta")
    out = []
    for row in range(result.rows):
        if result.status_name(row) != "near-singular":
            continue
        t = float(np.radians(result.input.values[row]) if radians else result.input.values[row])
        got = solve_at(solution, t, guesses[row])
        assert got.inside is not None
        reference = reference_values(setting.mechanism, got.inside.pose, list(keys), t=t, origin=setting.origin)
        errors = kind_errors(construction_values(got, keys, setting.origin), reference, dict(got.check.scales))
        out.append((result.warnings[row], max(errors.values())))
    return out


@pytest.mark.parametrize("name", sorted(SCENES))
def test_a_near_singular_rows_stated_error_bounds_its_error(name: str) -> None:
    rows = _near_rows(*SCENES[name])
    assert rows, "the range ends near a dead point: some row is near-singular"
    for warning, error in rows:
        stated = [float(x) for x in _STATED.findall(warning)]
        assert stated, warning
        assert math.isfinite(error) and error <= max(stated), (error, warning)
    assert max(error for _, error in rows) > 1e-9  # near a dead point indeed: far above the rounding of a sound row
