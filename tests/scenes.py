"""Scene texts for tests: the project's examples and random mechanisms of the standard kinds."""

from __future__ import annotations

from pathlib import Path

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def four_bar(a1: float, a2: float, a3: float, a4: float, theta12_deg: float, omega: float, alpha: float,
             guess_b: tuple[float, float], coupler: tuple[float, float] = (60.0, 30.0), find: str = "") -> str:
    return f"""
title = "random four-bar"
[links]
1 = {{ points = {{ A0 = [0, 0], B0 = [{a1!r}, 0] }} }}
2 = {{ points = {{ A0 = [0, 0], A = [{a2!r}, 0] }} }}
3 = {{ points = {{ A = [0, 0], B = [{a3!r}, 0], C = {{ polar = [{coupler[0]!r}, {coupler[1]!r}] }} }} }}
4 = {{ points = {{ B0 = [0, 0], B = [{a4!r}, 0] }} }}
[input]
link = "2"
angle = {theta12_deg!r}
omega = {omega!r}
alpha = {alpha!r}
[guess]
B = [{guess_b[0]!r}, {guess_b[1]!r}]
{find}
"""


def slider_crank(a2: float, a3: float, offset: float, theta12_deg: float, omega: float, alpha: float,
                 find: str = "") -> str:
    return f"""
title = "random slider-crank"
[links]
1 = {{ points = {{ A0 = [0, 0] }} }}
2 = {{ points = {{ A0 = [0, 0], A = [{a2!r}, 0] }} }}
3 = {{ points = {{ B = [0, 0], A = [{a3!r}, 0], C = {{ polar = [{0.4 * a3!r}, -30] }} }} }}
4 = {{ points = {{ B = [0, 0] }} }}
[[sliders]]
block = "4"
guide = "1"
point = "B"
line = {{ through = [0, {offset!r}], angle = 0 }}
[input]
link = "2"
angle = {theta12_deg!r}
omega = {omega!r}
alpha = {alpha!r}
[guess]
B = [{a2 + a3!r}, {offset!r}]
{find}
"""


def slotted_lever(a1: float, a2: float, offset: float, theta12_deg: float, omega: float, alpha: float,
                  guess_f: tuple[float, float], find: str = "") -> str:
    return f"""
title = "random slotted lever"
[links]
1 = {{ points = {{ A0 = [0, 0], B0 = [{a1!r}, 0] }} }}
2 = {{ points = {{ A0 = [0, 0], A = [{a2!r}, 0] }} }}
3 = {{ points = {{ A = [0, 0] }} }}
4 = {{ points = {{ B0 = [0, 0], F = [{offset!r}, 0] }} }}
[[sliders]]
block = "3"
guide = "4"
point = "A"
line = {{ through = [{offset!r}, 0], angle = 90 }}
[input]
link = "2"
angle = {theta12_deg!r}
omega = {omega!r}
alpha = {alpha!r}
[guess]
F = [{guess_f[0]!r}, {guess_f[1]!r}]
[find]
velocity = ["A", "A@4"]
acceleration = ["A", "A@4"]
omega = ["4"]
alpha = ["4"]
sliders = ["43"]
{find}
"""
