"""The angle a reader recognises: a link written in the frame's coordinates (its x-axis is no line of it) is
shown by the angle of a named line of it, a cylinder's barrel by its axis; the JSON's ``angle`` stays theta."""

from __future__ import annotations

import math

import kinepoly
from kinepoly.present.report import named_line, table_text
from kinepoly.render.primitives import Text
from kinepoly.render.sheet import build_sheet

# A platform lever 2 lifted by a cylinder (barrel 3 on the frame at C0, rod 4 pinned to the lever at D), every
# point written in the frame's coordinates: the links' x-axes lie along no line of theirs.
_PLATFORM = """
title = "Platform lifted by a cylinder"
[links]
1 = { points = { O = [0, 0], C0 = [100, 0] } }
2 = { points = { O = [0, 0], D = [200, 100], E = [300, 100] } }
3 = { points = { C0 = [100, 0] } }
4 = { points = { D = [200, 100] } }
[[sliders]]
block = "4"
guide = "3"
point = "D"
line = { through = [100, 0], angle = 45 }
[input]
slider = "34"
s = 141.42135623730951
s_dot = 10
s_ddot = 0
[guess]
D = [200, 100]
[find]
velocity = ["D", "E"]
omega = ["2", "3"]
alpha = ["2", "3"]
"""


def test_a_link_in_frame_coordinates_shows_its_named_line() -> None:
    solution = kinepoly.solve(kinepoly.loads_scene(_PLATFORM))
    assert abs(solution.angle("2")) < 1e-9 and abs(solution.angle("3")) < 1e-9  # theta: the x-axes, unturned
    line, at = named_line(solution, "2")
    assert line == "OD" and math.isclose(at, math.atan2(100.0, 200.0), abs_tol=1e-12)
    line, at = named_line(solution, "3")
    assert line == "axis 34" and math.isclose(math.degrees(at), 45.0, abs_tol=1e-9)  # the barrel stands at 45
    data = kinepoly.to_json(solution)
    assert abs(data["links"]["3"]["angle"]) < 1e-9  # the contract's theta, unchanged
    assert data["links"]["3"]["line"]["name"] == "axis 34" and math.isclose(data["links"]["3"]["line"]["angle"], 45.0)
    table = table_text(solution)
    assert any(row.split()[:3] == ["3", "(axis", "34)"] and row.split()[3] == "45" for row in table.splitlines())
    assert any(row.split()[:2] == ["2", "(OD)"] and row.split()[2].startswith("26.565") for row in table.splitlines())
    words = [i.string for i in build_sheet(solution).layer("title").items if isinstance(i, Text)]
    assert any(w.startswith("link 3 (axis 34)45") for w in words)  # the title block's row: name, then theta


def test_a_link_whose_x_axis_is_a_named_line_keeps_its_theta() -> None:
    from tests.scenes import EXAMPLES

    data = kinepoly.to_json(kinepoly.solve(kinepoly.load_scene(EXAMPLES / "four-bar.toml")))
    assert all("line" not in entry for entry in data["links"].values())
