"""Scene texts for tests: the project's examples and random mechanisms of the standard kinds.

The texts are ``kinepoly.bench.cases``' (the stability suite's mechanisms); here they take the
tests' arguments: every rate given, the assembly chosen by a guess, and a [find] of the test's own.
"""

from __future__ import annotations

from pathlib import Path

from kinepoly.bench.cases import four_bar_text, slider_crank_text, slotted_lever_text

__all__ = ["EXAMPLES", "four_bar", "slider_crank", "slotted_lever"]

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
