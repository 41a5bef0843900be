"""One notation for the terms of a point: a normal and a tangential term of the same point about the same
centre name the point alike (``a^n_A@4/B0`` beside ``a^t_A@4/B0``), and alpha is read off the tangential
term the construction found, by the same name (``alpha14 = |a^t_A@4/B0| / |B0A@4|``)."""

from __future__ import annotations

import re
from typing import Any

import pytest
from tests.scenes import EXAMPLES

import kinepoly

_TERM = re.compile(r"\b([va])(?:\^([nt]))?_([A-Za-z0-9@]+)/([A-Za-z0-9@]+)")


def _steps(name: str) -> list[dict[str, Any]]:
    data = kinepoly.to_json(kinepoly.solve(kinepoly.load_scene(EXAMPLES / name)))
    return list(data["steps"])


@pytest.mark.parametrize("name", sorted(p.name for p in EXAMPLES.glob("*.toml")))
def test_normal_and_tangential_terms_name_their_point_alike(name: str) -> None:
    steps = _steps(name)
    seen: set[str] = set()
    for step in steps:
        terms = _TERM.findall(step["equation"])
        named: dict[tuple[str, str], set[str]] = {}
        for letter, kind, point, centre in terms:
            if letter == "a" and kind in ("n", "t"):
                named.setdefault((point.partition("@")[0], centre), set()).add(point)
        assert all(len(points) == 1 for points in named.values()), (step["equation"], named)
        if step["kind"] == "read" and step["polygon"] == "acceleration":
            term = step["equation"].split("|")[1]
            assert term in seen, (step["equation"], sorted(seen))
        seen |= {m.group(0) for m in _TERM.finditer(step["equation"])}
        seen |= {vector["label"] for vector in step["vectors"]}
