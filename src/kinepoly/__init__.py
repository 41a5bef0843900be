"""kinepoly: velocity and acceleration polygons of planar mechanisms, constructed and checked.

A notebook needs four names::

    import kinepoly
    scene = kinepoly.load_scene("examples/four-bar.toml")   # or kinepoly.loads_scene(text)
    solution = kinepoly.solve(scene)
    kinepoly.to_json(solution)["links"]["3"]["omega"]

``solution`` shows as its drawing in a notebook; ``kinepoly.draw(solution, part="velocity-polygon")``
is SVG text; ``kinepoly.animate(scene, "four-bar.gif")`` is ``kinepoly animate`` (docs/python.md).
"""

from typing import TYPE_CHECKING, Any

from kinepoly.errors import (
    AssemblyError,
    CatalogueError,
    HandoutError,
    KinepolyError,
    MobilityError,
    OutputError,
    SceneError,
    SingularityError,
)
from kinepoly.present.report import steps_text, table_text, to_json
from kinepoly.scene.loader import load_scene, loads_scene
from kinepoly.scene.spec import Scene
from kinepoly.solution import Solution, solve

if TYPE_CHECKING:
    from kinepoly.motion.api import animate, draw

__all__ = [
    "AssemblyError",
    "CatalogueError",
    "HandoutError",
    "KinepolyError",
    "MobilityError",
    "OutputError",
    "Scene",
    "SceneError",
    "SingularityError",
    "Solution",
    "animate",
    "draw",
    "load_scene",
    "loads_scene",
    "solve",
    "steps_text",
    "table_text",
    "to_json",
]


def _solution_svg(solution: Solution) -> str:
    """A notebook shows a solution as its drawing (``Solution._repr_svg_``, set here, at the package's face, so
    that the solution does not import the drawing code above it)."""
    from kinepoly.motion.api import draw

    return draw(solution)


setattr(Solution, "_repr_svg_", _solution_svg)  # noqa: B010 (a method the class does not declare)


def __getattr__(name: str) -> Any:
    """``animate`` and ``draw`` load the drawing and animation code (matplotlib, the sweep) when first
    used, so that ``import kinepoly`` and ``kinepoly solve`` start fast."""
    if name in ("animate", "draw"):
        from kinepoly.motion import api

        return getattr(api, name)
    raise AttributeError(f"module 'kinepoly' has no attribute {name!r}")
