"""A chain of N four-bar loops: the scene the scaling benchmark and the hardening tests grow.

Loop 1 is the four-bar A0-P1-Q1-G1 (crank "2", coupler "c1", rocker "r1"); each further loop i
pins a new coupler ``ci`` to the previous coupler at ``Pi`` and a new rocker ``ri`` to the
frame at ``Gi``; they meet at ``Qi``. 2N + 2 links, every loop the same shape shifted by 100
along x, every transmission angle about 56 degrees. Points are given where they are at the
input's 60 degrees (each link's own frame is the world's), with a guess for every ``Qi``.
"""

from __future__ import annotations

import math

__all__ = ["chain_text"]

_PITCH = 100.0
_P = (20.0, 40.0 * math.sin(math.radians(60.0)))  # P1, the crank's end at 60 degrees
_Q = (110.0, 80.0)


def _xy(x: float, y: float) -> str:
    return f"[{x:.10g}, {y:.10g}]"


def chain_text(loops: int, *, find: str | None = None, title: str | None = None) -> str:
    """The scene text of a chain of ``loops`` four-bar loops driven by the crank "2" at 60 degrees.

    ``find`` is the [find] table's body; None asks the last loop's Q's velocity and acceleration
    and the last rocker's omega and alpha (the whole chain is solved for it); "" writes no [find]
    (every point and link asked).
    """
    if loops < 1:
        raise ValueError("a chain has at least one loop")
    frame = {"A0": (0.0, 0.0)} | {f"G{i}": (_PITCH * i, 0.0) for i in range(1, loops + 1)}
    lines = [f'title = "{title or f"chain of {loops} four-bar loops"}"', "", "[links]",
             "1 = { points = { " + ", ".join(f"{k} = {_xy(*v)}" for k, v in frame.items()) + " } }",
             "2 = { points = { A0 = [0, 0], P1 = [40, 0] } }"]
    guesses = []
    for i in range(1, loops + 1):
        shift = _PITCH * (i - 1)
        p = (_P[0] + shift, _P[1])
        q = (_Q[0] + shift, _Q[1])
        nxt = (_P[0] + shift + _PITCH, _P[1])
        coupler = {f"P{i}": p, f"Q{i}": q} | ({f"P{i + 1}": nxt} if i < loops else {})
        lines.append(f"c{i} = {{ points = {{ " + ", ".join(f"{k} = {_xy(*v)}" for k, v in coupler.items()) + " } }")
        lines.append(f"r{i} = {{ points = {{ G{i} = {_xy(_PITCH * i, 0.0)}, Q{i} = {_xy(*q)} }} }}")
        guesses.append(f"Q{i} = {_xy(*q)}")
    lines += ["", "[input]", 'link = "2"', "angle = 60", "omega = 10", "alpha = 5", "", "[guess]", *guesses, ""]
    if find is None:
        find = (f'velocity = ["Q{loops}"]\nacceleration = ["Q{loops}"]\nomega = ["r{loops}"]\n'
                f'alpha = ["r{loops}"]')
    lines += ["[find]", find, ""] if find else []
    return "\n".join(lines)
