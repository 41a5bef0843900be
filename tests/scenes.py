"""Scene texts for tests: the project's examples and random mechanisms of the standard kinds.

The texts are ``kinepoly.bench.cases``' (the stability suite's mechanisms); here they take the
tests' arguments: every rate given, the assembly chosen by a guess, and a [find] of the test's own.
"""

from __future__ import annotations

import math
from pathlib import Path

from kinepoly.bench.cases import four_bar_text, slider_crank_text, slotted_lever_text

__all__ = ["EXAMPLES", "cam_rocker", "four_bar", "slider_crank", "slotted_lever"]

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def four_bar(a1: float, a2: float, a3: float, a4: float, theta12_deg: float, omega: float, alpha: float,
             guess_b: tuple[float, float], coupler: tuple[float, float] = (60.0, 30.0), find: str = "") -> str:
    return four_bar_text(a1, a2, a3, a4, theta12_deg, omega, alpha, guess_b, coupler=coupler,
                         title="random four-bar", find=find)


def slider_crank(a2: float, a3: float, offset: float, theta12_deg: float, omega: float, alpha: float,
                 find: str = "") -> str:
    """B guessed ahead of the crank, at (a2 + a3, offset)."""
    return slider_crank_text(a2, a3, offset, theta12_deg, omega, alpha, (a2 + a3, offset),
                             title="random slider-crank", find=find)


def slotted_lever(a1: float, a2: float, offset: float, theta12_deg: float, omega: float, alpha: float,
                  guess_f: tuple[float, float], find: str = "") -> str:
    """Its [find] asks A and A@4, omega and alpha of 4, and slider 43; ``find`` adds to it."""
    return slotted_lever_text(a1, a2, offset, theta12_deg, omega, alpha, guess_f, title="random slotted lever",
                              find=find)


def cam_rocker(follower: str) -> str:
    """A disc cam (eccentricity 15, radius 40, on O) and a rocker (pivot P = (80, 20), W 70 from it) touching
    it with a knife edge W (``follower = "knife"``) or a roller of radius 10 in a groove (``"inside"``); the
    [guess] puts W on the side of the line K P counter-clockwise of it at the input, 30 deg."""
    reach = 40.0 if follower == "knife" else 30.0  # W's distance from the disc's centre K
    t = math.radians(30.0)
    k, p = 15.0 * complex(math.cos(t), math.sin(t)), complex(80.0, 20.0)
    d = abs(p - k)
    along = (reach**2 - 70.0**2 + d * d) / (2.0 * d)
    u = (p - k) / d
    w = k + along * u + math.sqrt(reach**2 - along**2) * 1j * u
    touch = 'knife = "W"' if follower == "knife" else 'roller = { center = "W", radius = 10 }\ncontact = "inside"'
    return f"""title = "Disc cam on a rocker ({follower})"

[links]
1 = {{ points = {{ O = [0, 0], P = [80, 20] }} }}
2 = {{ points = {{ O = [0, 0] }} }}
3 = {{ points = {{ P = [0, 0], W = [-70, 0] }} }}

[[cams]]
cam = "2"
follower = "3"
profile = {{ circle = {{ center = [15, 0], radius = 40 }} }}
{touch}

[input]
link = "2"
angle = 30
omega = 20
alpha = 4

[guess]
W = [{w.real:.1f}, {w.imag:.1f}]

[find]
velocity = ["W"]
acceleration = ["W"]
omega = ["3"]
alpha = ["3"]
instant_centers = ["23"]
"""
